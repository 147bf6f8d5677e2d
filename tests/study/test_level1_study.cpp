// The Level I screen of a scene: QA from the stages against a hand computation of
// API 617's formula, Q at the middle of the bearing span, and Q0 against an
// independent computation on the exported matrices (the state matrix shifted and
// inverted near the crossing, Eigen's complex eigensolver: Re(lambda) changes sign
// across Q0 (1 -+ 1e-6)).
#include <gyrokit/core/constants.hpp>
#include <gyrokit/gyrokit.hpp>

#include "api_checks.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>

using namespace gyrokit;
using namespace gyrokit::test;

namespace {

// The rotor of data/three_disk_rotor.toml without its own [api].
std::string three_disk_text() {
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    std::stringstream s;
    s << in.rdbuf();
    const std::string text = s.str();
    return text.substr(0, text.find("\n[api]"));
}

const char* kStages = R"(
[api]
machine = "centrifugal"
mcs = 10000
gas_density = 40
[[api.stage]]
z = 0.35
power = 1e6
diameter = 0.4
width = 0.02
density_ratio = 1.5
[[api.stage]]
z = 0.85
power = 5e5
diameter = 0.35
width = 0.015
density_ratio = 1.3
)";

}  // namespace

TEST_CASE("Level I of an FE rotor: QA by API 617's formula, Q at mid-span, Q0 against an independent solve",
          "[level1]") {
    const Scene sc = parse_scene(three_disk_text() + kStages, "three_disk_level1.toml", GYROKIT_DATA_DIR);
    const Level1Screen s = level1_study(sc).verdict();
    // QA by hand: 3 x 9.55 x P rho_d/rho_s / (D H N), N = 10000 rpm.
    const double qa1 = 3 * 9.55 * 1e6 * 1.5 / (0.4 * 0.02 * 10000), qa2 = 3 * 9.55 * 5e5 * 1.3 / (0.35 * 0.015 * 10000);
    REQUIRE(s.stage_qa.size() == 2);
    CHECK(s.stage_qa[0] == Approx(qa1).epsilon(1e-12));
    CHECK(s.stage_qa[1] == Approx(qa2).epsilon(1e-12));
    CHECK(s.qa == Approx(qa1 + qa2).epsilon(1e-12));
    // Both stages lie between the bearings (z = 0.05 and 1.15): Q at the node nearest z = 0.6.
    CHECK(s.layout == "between bearings");
    REQUIRE(s.stations.size() == 1);
    CHECK(s.station_z[0] == Approx(0.6).margin(1e-12));
    CHECK(s.at_zero.whirl == Whirl::Forward);
    CHECK(s.at_zero.log_decrement > 0);
    REQUIRE(s.curve.q0.has_value());
    const double q0 = *s.curve.q0;
    CHECK(s.curve.q0_bound <= 1e-6 * q0);
    // The followed eigenvalue at Q0 sits on the imaginary axis; an independent solve on either side.
    const double mcs = 10000 * 2 * kPi / 60;
    double omega = 0;
    for (const Level1Point& p : s.curve.points)
        if (p.q <= q0) omega = p.lambda.imag();
    const auto re_at = [&](double q) {
        const GyroscopicSystem g = with_cross_coupling(sc.system, s.stations, q);
        // The crossing's frequency: from the last curve point before Q0, refined by two shifts.
        std::complex<double> l = nearest_eigenvalue(g, mcs, {0.0, omega});
        l = nearest_eigenvalue(g, mcs, {0.0, l.imag()});
        return l;
    };
    const std::complex<double> below = re_at(q0 * (1 - 1e-6)), above = re_at(q0 * (1 + 1e-6));
    CHECK(below.real() < 0);
    CHECK(above.real() > 0);
    CHECK(std::fabs(below.imag() - above.imag()) <= 1e-6 * above.imag());
    // The verdict follows the criteria as stated.
    const double ratio = q0 / s.qa;
    REQUIRE(s.csr.has_value());
    REQUIRE(s.region_boundary.has_value());
    CHECK(*s.region_boundary == Approx(2.69 - 0.0115 * 40));
    const bool level2 = ratio < 2 || s.at_qa.log_decrement < 0.1 || (ratio < 10 && *s.csr > *s.region_boundary);
    CHECK(s.level2_required == level2);
}

TEST_CASE("Level I of an overhung stage: Q acts at the stage, or QA given directly", "[level1]") {
    std::string text = three_disk_text() + R"(
[api]
machine = "axial"
mcs = 9000
[[api.stage]]
z = 1.2
power = 2e5
diameter = 0.3
width = 0.04
)";
    const Scene sc = parse_scene(text, "overhung.toml", GYROKIT_DATA_DIR);
    const Level1Screen s = level1_study(sc).verdict();
    CHECK(s.layout == "overhung");
    REQUIRE(s.station_z.size() == 1);
    CHECK(s.station_z[0] == Approx(1.2).margin(1e-12));
    // Alford's form: Bt = 1.5, no density ratio.
    CHECK(s.qa == Approx(1.5 * 9.55 * 2e5 / (0.3 * 0.04 * 9000)).epsilon(1e-12));
    // QA given: the stage still says where Q acts.
    Level1Request r;
    r.qa = 1e5;
    const Level1Screen given = level1_study(sc, r).verdict();
    CHECK(given.qa == 1e5);
    CHECK(given.layout == "overhung");
    CHECK(given.station_z[0] == Approx(1.2).margin(1e-12));
    r.station = 0.6;
    const Level1Screen placed = level1_study(sc, r).verdict();
    CHECK(placed.layout == "station given");
    CHECK(placed.station_z[0] == Approx(0.6).margin(1e-12));
    // An axial machine has no density ratio to switch to a centrifugal one with.
    Level1Request c;
    c.machine = "centrifugal";
    try {
        level1_study(sc, c).verdict();
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("density_ratio is missing"));
    }
    // Axial: the critical speed ratio's region does not enter the verdict.
    CHECK_FALSE(s.region_boundary.has_value());
    for (const std::string& why : s.reasons) CHECK_THAT(why, !Catch::Contains("region"));
}

TEST_CASE("Level I verdicts: each criterion named", "[level1]") {
    const Scene sc = parse_scene(three_disk_text() + kStages, "three_disk_level1.toml", GYROKIT_DATA_DIR);
    const Level1Screen base = level1_study(sc).verdict();
    REQUIRE(base.curve.q0.has_value());
    const double q0 = *base.curve.q0;
    const auto with = [&](double qa, std::optional<double> rho) {
        Level1Request r;
        r.qa = qa;
        r.gas_density = rho;
        r.intervals = 4;   // the verdict needs Q0 and QA, not the curve's detail
        return level1_study(sc, r).verdict();
    };
    // Q0/QA < 2.
    const Level1Screen low = with(q0 / 1.5, 40.0);
    CHECK(low.level2_required);
    CHECK_THAT(low.reasons.front(), Catch::Contains("< 2"));
    // Q0/QA in [2, 10): region A at 40 kg/m^3 (ratio 2.05 < 2.23) passes; beyond the chart (70) is region B.
    CHECK_FALSE(with(q0 / 4, 40.0).level2_required);
    const Level1Screen dense = with(q0 / 4, 70.0);
    CHECK(dense.level2_required);
    CHECK_THAT(dense.reasons.front(), Catch::Contains("region B"));
    // No gas density: the region is unknown, which does not pass.
    Level1Request none;
    none.qa = q0 / 4;
    none.intervals = 4;
    ApiMachine m = *sc.api;
    m.gas_density.reset();
    Scene no_rho = sc;
    no_rho.api = m;
    const Level1Screen unknown = level1_study(no_rho, none).verdict();
    CHECK(unknown.level2_required);
    CHECK_THAT(unknown.reasons.front(), Catch::Contains("region of the critical speed ratio is unknown"));
    // Q0/QA >= 10 passes whatever the region.
    const Level1Screen high = with(q0 / 20, 70.0);
    CHECK_FALSE(high.level2_required);
    CHECK_FALSE(high.curve.q0.has_value());   // beyond 10 QA
}

TEST_CASE("[api] is read, checked and written back", "[level1][scene]") {
    const Scene sc = parse_scene(three_disk_text() + kStages, "three_disk_level1.toml", GYROKIT_DATA_DIR);
    REQUIRE(sc.api.has_value());
    CHECK(*sc.api->mcs == Approx(10000 * 2 * kPi / 60).epsilon(1e-15));
    CHECK(sc.api->stages.size() == 2);
    const Scene back = parse_scene(scene_text(sc), "written.toml", GYROKIT_DATA_DIR);
    REQUIRE(back.api.has_value());
    CHECK(*back.api->mcs == Approx(*sc.api->mcs).epsilon(1e-15));
    CHECK(back.api->stages.size() == 2);
    CHECK(back.api->stages[1].density_ratio == 1.3);
    CHECK(back.api->gas_density == 40.0);
    // A scene in Hz: every key read in its unit and written back in the scene's speed unit.
    std::string text = three_disk_text();
    text.replace(text.find("units = \"rpm\""), 13, "units = \"Hz\" ");
    const Scene hz = parse_scene(text + R"(
[api]
machine = "axial"
mcs = 150
operating_speed = 140
qa = 2e6
station = 0.55
q_ratio = 5
[[api.stage]]
z = 0.6
power = 1e5
diameter = 0.3
width = 0.02
)", "hz.toml", GYROKIT_DATA_DIR);
    REQUIRE(hz.api.has_value());
    CHECK(*hz.api->mcs == Approx(150 * 2 * kPi).epsilon(1e-15));
    const Scene hz_back = parse_scene(scene_text(hz), "hz_written.toml", GYROKIT_DATA_DIR);
    const ApiMachine& a = *hz.api;
    const ApiMachine& b = *hz_back.api;
    CHECK(b.kind == MachineKind::axial);
    CHECK(*b.mcs == Approx(*a.mcs).epsilon(1e-15));
    CHECK(*b.operating_speed == Approx(*a.operating_speed).epsilon(1e-15));
    CHECK(b.qa == a.qa);
    CHECK(b.station == a.station);
    CHECK(b.q_ratio == 5.0);
    REQUIRE(b.stages.size() == 1);
    CHECK(b.stages[0].z == a.stages[0].z);
    CHECK(b.stages[0].diameter == a.stages[0].diameter);
    CHECK(b.stages[0].width == a.stages[0].width);
    CHECK_FALSE(b.stages[0].density_ratio.has_value());
    // A scene in mm: positions and sizes read in mm, held in m, written back in m.
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/drive_train.toml");
    std::stringstream drive;
    drive << in.rdbuf();
    const Scene mm = parse_scene(drive.str() + R"(
[api]
machine = "axial"
mcs = 100
qa = 1e6
station = 550
[[api.stage]]
z = 600
power = 1e5
diameter = 300
width = 20
)", "mm.toml", GYROKIT_DATA_DIR);
    REQUIRE(mm.length_unit().name == "mm");
    CHECK(*mm.api->station == Approx(0.55).epsilon(1e-15));
    CHECK(mm.api->stages[0].diameter == Approx(0.3).epsilon(1e-15));
    const Scene mm_back = parse_scene(scene_text(mm), "mm_written.toml", GYROKIT_DATA_DIR);
    CHECK(*mm_back.api->station == Approx(0.55).epsilon(1e-15));
    CHECK(mm_back.api->stages[0].z == Approx(0.6).epsilon(1e-15));
    CHECK(mm_back.api->stages[0].width == Approx(0.02).epsilon(1e-15));
    const auto error = [](const std::string& text) {
        try {
            parse_scene(three_disk_text() + "\n" + text, "bad.toml", GYROKIT_DATA_DIR);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(error("[api]\nmcs = 100\nmachine = \"axial\"\n[[api.stage]]\nz = 0.6\npower = 1e5\ndiameter = 0.3\n"
                     "width = 0.02\ndensity_ratio = 1.2\n"),
               Catch::Contains("density_ratio is given for an axial machine"));
    CHECK_THAT(error("[api]\nmcs = 100\nqa = -1\n"), Catch::Contains("qa = -1"));
    CHECK_THAT(error("[api]\nmcs = 100\nqa = 1\nq_ratio = 1\n"), Catch::Contains("q_ratio = 1: out of range; allowed: [2, 1000]"));
    CHECK_THAT(error("[api]\nmcs = 100\n[[api.stage]]\nz = 0.6\npower = 1e5\ndiameter = 0.3\nwidth = 0.02\n"),
               Catch::Contains("density_ratio' is missing"));
    CHECK_THAT(error("[api]\nmcs = 100\nqa = 1\nspeed = 3\n"), Catch::Contains("unknown key 'speed'"));
    // A scene without an FE rotor has no [api].
    try {
        level1_study(scene_of(sc.system)).verdict();
        FAIL("no error");
    } catch (const InputError& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains("fe_rotor"));
    }
}

namespace {

// data/three_disk_rotor_journal.toml with QA given (2e6 N/m) and, where `bands`, the
// films' clearance (50/60/75 um) and viscosity (0.011/0.015/0.024 Pa s) bands as the
// file gives them; else each film at `clearance` and `viscosity` without a band.
std::string journal_text(bool bands, const std::string& clearance = "60e-6", const std::string& viscosity = "0.015") {
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor_journal.toml");
    std::string text, line;
    while (std::getline(in, line)) {
        const auto starts = [&](const char* key) { return line.rfind(key, 0) == 0; };
        if (!bands && (starts("clearance_m") || starts("viscosity_m"))) continue;
        if (!bands && starts("clearance = 60e-6")) line = "clearance = " + clearance;
        if (!bands && starts("viscosity = 0.015")) line = "viscosity = " + viscosity;
        text += line + "\n";
        if (starts("mcs = ")) text += "qa = 2e6\n";
    }
    int films_with_bands = 0;
    for (std::size_t at = text.find("clearance_min = 50e-6"); at != std::string::npos;
         at = text.find("clearance_min = 50e-6", at + 1))
        ++films_with_bands;
    REQUIRE(films_with_bands == (bands ? 2 : 0));
    return text;
}

}  // namespace

TEST_CASE("Level I at both ends of the fluid films' tolerance bands: each end as its own scene, the worse governs",
          "[level1]") {
    const Scene sc = parse_scene(journal_text(true), "journal_bands.toml", GYROKIT_DATA_DIR);
    REQUIRE(sc.rotor_model()->bearings.at(0).film.clearance_min.has_value());
    Level1Request r;
    r.intervals = 10;
    const Level1Study st = level1_study(sc, r);
    REQUIRE(st.screens.size() == 2);
    CHECK(st.screens[0].bearing_set == "minimum clearance");
    CHECK(st.screens[1].bearing_set == "maximum clearance");
    // Each end equals the scene whose films are given at that end: the smallest clearance
    // with the largest viscosity, and the largest with the smallest.
    const std::pair<const char*, const char*> ends[] = {{"50e-6", "0.024"}, {"75e-6", "0.011"}};
    for (std::size_t i = 0; i < 2; ++i) {
        const Scene one = parse_scene(journal_text(false, ends[i].first, ends[i].second), "end.toml", GYROKIT_DATA_DIR);
        const Level1Study alone = level1_study(one, r);
        REQUIRE(alone.screens.size() == 1);
        CHECK(alone.screens[0].bearing_set.empty());
        const Level1Screen &a = alone.verdict(), &b = st.screens[i];
        REQUIRE(a.curve.q0.has_value());
        REQUIRE(b.curve.q0.has_value());
        CHECK(*b.curve.q0 == Approx(*a.curve.q0).epsilon(1e-12));
        CHECK(b.at_qa.log_decrement == Approx(a.at_qa.log_decrement).epsilon(1e-12));
    }
    // The larger clearance with the thinner oil is the less stable end, and governs.
    CHECK(*st.screens[1].curve.q0 < *st.screens[0].curve.q0);
    CHECK(st.governing == 1);
    CHECK(st.level2_required());
    CHECK(governing_screen({st.screens[0]}) == 0);

    // At the minimum clearance the lowest forward mode is the conical one, with a node at
    // mid-span where Q acts: passed over. Independently: its eigenvalue does not move with
    // Q, and Q0 of the followed mode brackets a sign change of Re(lambda).
    const Level1Screen& tight = st.screens[0];
    REQUIRE(tight.curve.passed.size() == 1);
    CHECK(tight.curve.notes.empty());   // every step decided (two heavily damped modes of one shape)
    const GyroscopicSystem sys = build(bearing_extremes(*sc.rotor_model())[0].model).system;
    const double mcs = 6000 * 2 * kPi / 60;
    const std::complex<double> sigma(-120.0, 330.0);   // near the conical mode (-124.7 + 327.1i 1/s)
    const std::complex<double> c0 = nearest_eigenvalue(with_cross_coupling(sys, tight.stations, 0.0), mcs, sigma);
    const std::complex<double> cq = nearest_eigenvalue(with_cross_coupling(sys, tight.stations, tight.qa), mcs, sigma);
    CHECK(std::abs(cq - c0) <= 1e-9 * std::abs(c0));
    CHECK(tight.at_zero.lambda.imag() > 1.05 * c0.imag());   // the followed mode is another
    const double q0 = *tight.curve.q0;
    const auto re_at = [&](double q) {
        const GyroscopicSystem g = with_cross_coupling(sys, tight.stations, q);
        std::complex<double> l = nearest_eigenvalue(g, mcs, {0.0, tight.curve.points.back().lambda.imag()});
        return nearest_eigenvalue(g, mcs, {0.0, l.imag()}).real();
    };
    CHECK(tight.curve.q0_bound <= 1e-6 * q0);
    CHECK(re_at(q0 * (1 - 1e-6)) < 0);
    CHECK(re_at(q0 * (1 + 1e-6)) > 0);
}

TEST_CASE("Fluid-film tolerance bands: given in pairs around the nominal value, each end a usable film, written back",
          "[level1]") {
    const auto error = [&](const std::string& from, const std::string& to) {
        std::string text = journal_text(true);
        REQUIRE(text.find(from) != std::string::npos);
        text.replace(text.find(from), from.size(), to);
        try {
            parse_scene(text, "bands.toml", GYROKIT_DATA_DIR);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(error("clearance_max = 75e-6\n", ""), Catch::Contains("clearance_min is given without clearance_max"));
    CHECK_THAT(error("viscosity_min = 0.011\n", ""), Catch::Contains("viscosity_max is given without viscosity_min"));
    CHECK_THAT(error("clearance_min = 50e-6", "clearance_min = 70e-6"),
               Catch::Contains("allowed: 0 < clearance_min <= clearance <= clearance_max"));
    CHECK_THAT(error("viscosity_max = 0.024", "viscosity_max = 0.012"),
               Catch::Contains("allowed: 0 < viscosity_min <= viscosity <= viscosity_max"));
    CHECK_THAT(error("clearance_max = 75e-6", "clearance_max = 0.031"),
               Catch::Contains("clearance_max = 0.031 m with diameter = 0.06 m; allowed: clearance_max < diameter / 2"));
    CHECK_THAT(error("clearance_min = 50e-6", "clearance_min = -1e-6"), Catch::Contains("clearance_min"));
    // The bands survive a scene written back and read again.
    const Scene sc = parse_scene(journal_text(true), "bands.toml", GYROKIT_DATA_DIR);
    const Scene again = parse_scene(scene_text(sc), "again.toml", GYROKIT_DATA_DIR);
    const JournalBearing &a = sc.rotor_model()->bearings.at(1).film, &b = again.rotor_model()->bearings.at(1).film;
    CHECK(b.clearance_min == a.clearance_min);
    CHECK(b.clearance_max == a.clearance_max);
    CHECK(b.viscosity_min == a.viscosity_min);
    CHECK(b.viscosity_max == a.viscosity_max);
    // A rotor without bands has one bearing set: its bearings as given.
    CHECK(bearing_extremes(*parse_scene(journal_text(false), "j.toml", GYROKIT_DATA_DIR).rotor_model()).empty());
}

TEST_CASE("Level I: a lower forward mode Q does not load is passed over, and its own damping still judged",
          "[level1]") {
    // A symmetric rotor rocking on its bearings (heavy disks overhung at both ends), Q at
    // mid-span, a damper there: the rocking mode has a node at Q's station and little
    // damping; the bouncing mode above it is loaded and well damped.
    const Scene sc = parse_scene(R"(
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 1.2
elements = 24
outer_diameter = 0.08
[[model.disk]]
z = 0.05
outer_diameter = 0.4
inner_diameter = 0.08
width = 0.06
[[model.disk]]
z = 1.15
outer_diameter = 0.4
inner_diameter = 0.08
width = 0.06
[[model.bearing]]
z = 0.35
k = 5e6
c = 300
[[model.bearing]]
z = 0.85
k = 5e6
c = 300
[[model.bearing]]
z = 0.6
k = 0
c = 3000
[api]
mcs = 3000
qa = 1e4
station = 0.6
)",
                                 "rocking.toml", GYROKIT_DATA_DIR);
    const Level1Screen s = level1_study(sc).verdict();
    REQUIRE(s.curve.passed.size() == 1);
    const PassedMode& rock = s.curve.passed[0];
    CHECK(rock.orbit_ratio < 1e-6);   // a node by symmetry, up to rounding
    // Independently: the rocking eigenvalue is the same at Q = 0 and at QA, lower than the
    // followed one, and its log decrement is below 0.1.
    const double mcs = 3000;
    const std::complex<double> r0 = nearest_eigenvalue(with_cross_coupling(sc.system, s.stations, 0.0), mcs,
                                                       rock.lambda);
    const std::complex<double> rq = nearest_eigenvalue(with_cross_coupling(sc.system, s.stations, s.qa), mcs,
                                                       rock.lambda);
    CHECK(std::abs(r0 - rock.lambda) <= rock.error_bound + 1e-9 * std::abs(r0));
    CHECK(std::abs(rq - r0) <= 1e-9 * std::abs(r0));
    CHECK(-2 * kPi * r0.real() / r0.imag() < 0.1);
    CHECK(rock.lambda.imag() < s.at_zero.lambda.imag());
    // The followed mode alone would pass; the rocking mode's damping requires Level II.
    CHECK(s.at_qa.log_decrement > 0.1);
    CHECK(!s.curve.q0.has_value());
    CHECK(s.level2_required);
    REQUIRE(s.reasons.size() == 1);
    CHECK_THAT(s.reasons[0], Catch::Contains("passed over (Q does not load it), has a log decrement of 0.0204"));
}

TEST_CASE("Level I: the governing bearing set, by the verdict, then Q0/QA, then the log decrement at QA",
          "[level1]") {
    const auto screen = [](bool level2, std::optional<double> q0, double delta) {
        Level1Screen s;
        s.qa = 1e6;
        s.level2_required = level2;
        s.curve.q0 = q0;
        s.at_qa.log_decrement = delta;
        return s;
    };
    CHECK(governing_screen({screen(false, 5e6, 0.5), screen(true, 9e6, 0.9)}) == 1);    // Level II first
    CHECK(governing_screen({screen(true, 1e6, 0.05), screen(false, 5e6, 0.5)}) == 0);
    CHECK(governing_screen({screen(false, 5e6, 0.2), screen(false, 4e6, 0.9)}) == 1);   // the smaller Q0/QA
    CHECK(governing_screen({screen(false, std::nullopt, 0.2), screen(false, 9e6, 0.9)}) == 1);   // none: above
    CHECK(governing_screen({screen(false, std::nullopt, 0.9), screen(false, std::nullopt, 0.3)}) == 1);   // delta
    CHECK(governing_screen({screen(false, 5e6, 0.3), screen(false, 5e6, 0.3)}) == 0);   // equal: the first
    CHECK_THROWS_AS(governing_screen({}), Error);
}
