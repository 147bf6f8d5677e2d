// The unbalance response as every front end runs it (study/response_study.hpp):
// its checks live in the library, the stability tracking can be skipped without
// changing a digit of the response, and the summary's maxima are the refined peaks.
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <string>

using namespace gyrokit;

namespace {

const Scene& three_disk() {
    static const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    return sc;
}

StudyOptions speeds(int n) {
    StudyOptions so = study_options(three_disk());
    so.speeds = SpeedRange{0.0, 1500.0, n}.points();
    so.workers = 1;
    return so;
}

}  // namespace

TEST_CASE("the response study checks its request in the library", "[response][errors]") {
    const GyroscopicSystem& sys = three_disk().system;
    ResponseRequest both;
    both.outputs = {0};
    both.probes = {probe_at_node(sys, "12@0", 12, 0.0)};
    CHECK_THROWS_WITH(response_study(sys, speeds(5), both), Catch::Contains("allowed: one of them"));
    ResponseRequest outside;
    outside.outputs = {sys.size()};
    CHECK_THROWS_WITH(response_study(sys, speeds(5), outside), Catch::Contains("allowed: 0 to"));
    StudyOptions none = speeds(5);
    none.speeds.clear();
    CHECK_THROWS_AS(response_study(sys, none, {}), InputError);
}

TEST_CASE("the response study: the same response with or without the stability tracking, the peaks refined",
          "[response]") {
    const GyroscopicSystem& sys = three_disk().system;
    ResponseRequest r;
    r.outputs = dofs_by_name("x12,y12", sys.dofs.names, "dofs");
    const ResponseStudy checked = response_study(sys, speeds(16), r);
    r.stability_check = false;
    const ResponseStudy quick = response_study(sys, speeds(16), r);
    CHECK(quick.si == checked.si);
    CHECK(quick.curve.Z == checked.curve.Z);
    REQUIRE(checked.maxima.size() == 2);
    for (std::size_t k = 0; k < 2; ++k) {
        INFO(k);
        // The grid misses the resonance: the refined peak lies between grid speeds and above every grid value.
        CHECK(checked.maxima[k].refined);
        CHECK(checked.maxima[k].amplitude > checked.curve.Z.col(static_cast<Eigen::Index>(k)).cwiseAbs().maxCoeff());
        CHECK(checked.maxima[k].amplitude == quick.maxima[k].amplitude);
    }
    // Lengths in metres here: the curve as shown is the SI one.
    CHECK(checked.curve.Z == checked.si);
    for (const int k : r.outputs) CHECK(checked.units[static_cast<std::size_t>(k)] == "m");
}
