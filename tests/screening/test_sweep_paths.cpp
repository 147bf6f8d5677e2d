// A sweep parameter addresses any numeric value of a scene by a path through its
// arrays of tables (model.bearing[1].kxx, model.shaft[*].outer_diameter): each
// swept value changes exactly the element it names, as a hand-edited scene does.
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/scene/scene_writer.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/screening/sweep.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include "test_helpers.hpp"
#include <catch2/catch.hpp>

#include <fstream>
#include <limits>
#include <sstream>

using namespace gyrokit;

namespace {

const std::string kScene = std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml";

std::string text_of(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

// The scene text with the `nth` (from 0) occurrence of `from` replaced by `to`.
std::string edited(std::string text, const std::string& from, const std::string& to, int nth) {
    std::size_t at = 0;
    for (int k = 0; k <= nth; ++k) {
        at = text.find(from, k == 0 ? 0 : at + 1);
        REQUIRE(at != std::string::npos);
    }
    return text.replace(at, from.size(), to);
}

void require_equal(const GyroscopicSystem& a, const GyroscopicSystem& b) {
    REQUIRE(a.size() == b.size());
    CHECK((a.M.dense() - b.M.dense()).norm() == 0.0);
    CHECK((a.K.dense() - b.K.dense()).norm() == 0.0);
    CHECK((a.G.dense() - b.G.dense()).norm() == 0.0);
    CHECK((a.damping_matrix(0.0) - b.damping_matrix(0.0)).norm() == 0.0);
}

std::string refusal(const std::map<std::string, double>& o) {
    try {
        load_scene(kScene, o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "accepted";
}

}  // namespace

TEST_CASE("a sweep path changes exactly the element it names, as a hand-edited scene") {
    const std::string text = text_of(kScene);
    const Scene base = load_scene(kScene);
    SECTION("one bearing's stiffness") {
        const Scene swept = load_scene(kScene, {{"model.bearing[1].kxx", 3e7}});
        const Scene hand = parse_scene(edited(text, "kxx = 2e7", "kxx = 3e7", 1), kScene, GYROKIT_DATA_DIR);
        require_equal(swept.system, hand.system);
        CHECK((swept.system.K.dense() - base.system.K.dense()).norm() == Approx(1e7));   // one entry, the second bearing
    }
    SECTION("one section's diameter: the mesh is rebuilt") {
        const Scene swept = load_scene(kScene, {{"model.shaft[2].outer_diameter", 0.11}});
        const Scene hand =
            parse_scene(edited(text, "outer_diameter = 0.10\n", "outer_diameter = 0.11\n", 0), kScene, GYROKIT_DATA_DIR);
        require_equal(swept.system, hand.system);
        CHECK((swept.system.M.dense() - base.system.M.dense()).norm() > 0.0);
    }
    SECTION("every entry, and several tied paths") {
        const Scene swept = load_scene(kScene, {{"model.bearing[*].kxx", 3e7}, {"model.bearing[*].kyy", 3e7}});
        std::string t = text;
        for (int k = 0; k < 2; ++k) t = edited(t, "kxx = 2e7", "kxx = 3e7", 0);
        for (int k = 0; k < 2; ++k) t = edited(t, "kyy = 1.5e7", "kyy = 3e7", 0);
        require_equal(swept.system, parse_scene(t, kScene, GYROKIT_DATA_DIR).system);
    }
}

TEST_CASE("a bad sweep path is one line naming the path and what exists") {
    CHECK(refusal({{"model.bearing[7].kxx", 1e7}}) ==
          kScene + ": parameter 'model.bearing[7].kxx': model.bearing has 2 entries; allowed: model.bearing[0] to "
                   "model.bearing[1], or model.bearing[*]");
    CHECK_THAT(refusal({{"model.material", 1.0}}),
               Catch::Contains("parameter 'model.material': model.material is not a number in the scene"));
    CHECK_THAT(refusal({{"model.bearings[0].kxx", 1.0}}),
               Catch::Contains("model.bearings[...] is not an array of tables of the scene; allowed below model: "
                               "bearing[0..1], disk[0..2], shaft[0..4]"));
    CHECK_THAT(refusal({{"model.bearing[x].kxx", 1.0}}), Catch::Contains("'[x]' is not an index"));
    CHECK_THAT(refusal({{"model.bearing[0]", 1.0}}), Catch::Contains("the last step indexes an array"));
    // A geometry value that breaks the mesh: the reader's message, naming the element as the path does.
    CHECK_THAT(refusal({{"model.shaft[1].length", -0.25}}),
               Catch::Contains("[model.shaft[1]] length = -0.25: out of range"));
    CHECK_THAT(refusal({{"model.disk[0].z", 0.37}}), Catch::Contains("[model.disk[0]] z = 0.37 m is not a node"));
}

TEST_CASE("a tied sweep parameter sets each of its paths, and a path set twice is refused") {
    Sweep s;
    s.path = "test sweep";
    s.scene = kScene;
    SweepParameter k{"k_bearing", 0, 0, 0, {1e7, 2e7}, false, {"model.bearing[*].kxx", "model.bearing[*].kyy"}};
    SweepParameter d{"model.shaft[2].outer_diameter", 0, 0, 0, {0.1}, false, {}};
    s.parameters = {k, d};
    const auto o = design_overrides(s, {2e7, 0.1});
    CHECK(o == std::map<std::string, double>{{"model.bearing[*].kxx", 2e7},
                                             {"model.bearing[*].kyy", 2e7},
                                             {"model.shaft[2].outer_diameter", 0.1}});
    s.parameters[1].paths = {"model.bearing[*].kyy"};
    CHECK_THROWS_WITH(design_overrides(s, {2e7, 0.1}), Catch::Contains("can name the same value"));
    // [*] meets every index, and an index is a number whatever its zeros: these overlap too.
    s.parameters[1].paths = {"model.bearing[1].kxx"};
    CHECK_THROWS_WITH(design_overrides(s, {2e7, 0.1}),
                      Catch::Contains("paths 'model.bearing[*].kxx' and 'model.bearing[1].kxx' can name the same value"));
    s.parameters[0].paths = {"model.bearing[01].kxx"};
    CHECK_THROWS_WITH(design_overrides(s, {2e7, 0.1}), Catch::Contains("can name the same value"));
    s.parameters[0].paths = {"model.bearing[0].kxx"};   // another bearing: fine
    CHECK(design_overrides(s, {2e7, 0.1}).size() == 2);
}

TEST_CASE("API 684 separation margin from the amplification factor: the closed form and its caps") {
    // None below AF 2.5; below the range 17 (1 - 1/(AF - 1.5)) up to 16 %, above it 10 % more up to 26 %.
    CHECK(api684_required_margin(2.4, false) == 0.0);
    CHECK(api684_required_margin(2.4, true) == 0.0);
    CHECK(api684_required_margin(2.5, false) == Approx(0.0).margin(1e-12));
    CHECK(api684_required_margin(2.5, true) == Approx(10.0));
    CHECK(api684_required_margin(3.5, false) == Approx(8.5));
    CHECK(api684_required_margin(3.5, true) == Approx(18.5));
    CHECK(api684_required_margin(18.5, false) == Approx(16.0));   // 17 (1 - 1/17) = 16: the cap begins
    CHECK(api684_required_margin(100.0, false) == 16.0);
    CHECK(api684_required_margin(100.0, true) == 26.0);
    CHECK(api684_required_margin(std::numeric_limits<double>::infinity(), true) == 26.0);   // undamped
    CHECK(api684_required_margin(std::numeric_limits<double>::quiet_NaN(), true) == 0.0);
}

TEST_CASE("screening with rule api684 judges each critical speed by the margin its amplification factor needs") {
    Sweep s;
    s.path = "test sweep";
    s.scene = kScene;
    s.unit = SpeedUnit::parse("rpm");
    s.op_from = 3000.0 / s.unit.factor;
    s.op_to = 12000.0 / s.unit.factor;
    SeparationCriterion sep;
    sep.api684 = true;
    sep.margin_percent = 26.0;
    s.criteria.separation = sep;
    s.sampling = Sampling::List;
    s.parameters = {SweepParameter{"k", 0, 0, 0, {}, false, {"model.bearing[*].kxx", "model.bearing[*].kyy"}}};
    s.designs = {{1e7}, {2e7}};
    finalize_sweep(s);
    // Soft bearings: every crossing heavily damped (checked apart: AF < 2.5), so no margin is needed.
    StudyOptions so = study_options(load_scene(kScene, {{"model.bearing[*].kxx", 1e7}, {"model.bearing[*].kyy", 1e7}}));
    so.speeds = SpeedRange{0.0, s.op_to * 1.26 * 1.05, 121}.points();
    for (const CriticalSpeed& c : critical_speed_study(load_scene(kScene, {{"model.bearing[*].kxx", 1e7},
                                                                           {"model.bearing[*].kyy", 1e7}}).system,
                                                       so).critical)
        CHECK(c.amplification < kApi684CriticalAmplification);
    CHECK(evaluate_design(s, 0).verdict == Verdict::Pass);
    // Stiffer: a critical speed inside the range fails; its required margin is the closed form of its AF.
    const DesignResult r = evaluate_design(s, 1);
    REQUIRE(r.verdict == Verdict::Fail);
    REQUIRE(r.quantities.size() == 4);
    const double af = *r.quantities[3], sm = *r.quantities[1];
    CHECK(af >= kApi684CriticalAmplification);
    CHECK(sm < 0.0);   // inside the operating range
    const bool above = *r.quantities[0] > 12000.0;
    CHECK(*r.quantities[2] == Approx(above ? std::min(10.0 + 17.0 * (1.0 - 1.0 / (af - 1.5)), 26.0)
                                           : std::min(17.0 * (1.0 - 1.0 / (af - 1.5)), 16.0)));
    CHECK_THAT(r.reason, Catch::Contains("AF ") && Catch::Contains("lies inside the operating range"));
}

TEST_CASE("a sweep on a scene built in code (its written text) judges as the sweep on the scene file") {
    // The three-disk rotor as a RotorModel read from its file and written back: the sweep file
    // names no scene, read_sweep takes the text, and every design's row equals the file's.
    const std::string sweep_file = std::string(GYROKIT_DATA_DIR) + "/screen_three_disk.toml";
    const Scene built = rotor_scene(*load_scene(kScene).rotor_model());
    const Sweep by_file = read_sweep(sweep_file);
    const Sweep by_text = read_sweep(sweep_file, scene_text(built), "three-disk rotor built in code");
    for (const std::size_t i : {std::size_t{0}, std::size_t{8}}) {
        INFO("design " << i);
        const DesignResult a = evaluate_design(by_file, i), b = evaluate_design(by_text, i);
        CHECK(b.verdict == a.verdict);
        CHECK(b.failed == a.failed);
        CHECK(b.reason == a.reason);
        REQUIRE(b.quantities.size() == a.quantities.size());
        for (std::size_t q = 0; q < a.quantities.size(); ++q) CHECK(b.quantities[q] == a.quantities[q]);
    }
}
