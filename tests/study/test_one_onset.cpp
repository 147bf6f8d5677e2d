// One onset wherever an instability is named: the Campbell summary, its warnings, the
// response's stability check, the stability study and the screening all give the
// refined edge of the unstable range, never the first unstable grid speed.
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <cmath>
#include <string>

using namespace gyrokit;

namespace {

// A Jeffcott rotor with rotating (internal) damping c_i and stationary damping c_e:
// the forward mode loses stability at w_n (1 + c_e / c_i), in closed form.
GyroscopicSystem jeffcott(double m, double k, double ce, double ci) {
    Eigen::Matrix2d J;
    J << 0, 1, -1, 0;
    GyroscopicSystem g;
    g.M = m * Eigen::Matrix2d::Identity();
    g.K = k * Eigen::Matrix2d::Identity();
    g.damping.push_back({"c_e", ce * Eigen::Matrix2d::Identity()});
    g.damping.push_back({"c_i", ci * Eigen::Matrix2d::Identity()});
    g.N = ci * J;
    g.unbalance = Eigen::Vector2cd(m * 1e-4, std::complex<double>(0, -m * 1e-4));
    g.dofs.names = {"x", "y"};
    g.whirl_pairs = {{0, 1}};
    return g;
}

bool contains(const Diagnostics& d, const std::string& text) {
    for (const Diagnostic& x : d)
        if (x.text.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("one onset: the Campbell study's unstable range starts at the closed-form threshold", "[stability][onset]") {
    const double m = 2.0, k = 5e3, ce = 4.0, ci = 8.0;
    const double threshold = std::sqrt(k / m) * (1.0 + ce / ci);   // 75 rad/s
    const GyroscopicSystem sys = jeffcott(m, k, ce, ci);
    StudyOptions so;
    so.speeds = SpeedRange{0.0, 100.0, 37}.points();   // the threshold falls between grid speeds
    so.workers = 1;
    const CampbellStudy st = campbell_study(sys, so);
    REQUIRE(st.unstable.size() == 1);
    const UnstableRange& r = st.unstable.front();
    CHECK(r.from_refined);
    CHECK(!r.to_refined);
    CHECK(r.to_last);
    CHECK(r.to == 100.0);
    // The bound covers the truth and the grid speed lies outside it.
    CHECK(std::abs(r.from - threshold) <= r.from_bound);
    CHECK(r.from_bound < 1e-6 * threshold);
    CHECK(so.speeds[r.first_index] - threshold > 1.0);
    // The same speed as the stability study's change, named the same way everywhere.
    const StabilityStudy ss = stability_of(sys, st, so);
    REQUIRE(ss.changes.size() == 1);
    CHECK(ss.changes.front().speed == r.from);
    const std::string span = unstable_span(r, so.unit);
    CHECK(span == fmt::format("from {:.6g} to 100 rad/s", round_to_bound(r.from, r.from_bound)));
    CHECK(contains(st.diagnostics, "is unstable " + span));
    const Table summary = campbell_summary(st, {}, so.unit, "");
    bool named = false;
    for (std::size_t i = 0; i < summary.rows(); ++i)
        if (std::get<std::string>(summary.row(i).front()) == "stability")
            named = std::get<std::string>(summary.row(i).back()).find("unstable " + span) != std::string::npos;
    CHECK(named);
    // The response's own check (a coarser grid of its speeds) names the same onset.
    ResponseRequest rq;
    rq.outputs = {0};
    const ResponseStudy resp = response_study(sys, so, rq);
    CHECK(contains(resp.diagnostics, fmt::format("is unstable from {:.6g}", round_to_bound(r.from, r.from_bound))));
}

TEST_CASE("one onset: a stable rotor refines nothing, a grid edge is named as one", "[stability][onset]") {
    const GyroscopicSystem sys = jeffcott(2.0, 5e3, 4.0, 8.0);
    StudyOptions so;
    so.speeds = SpeedRange{0.0, 70.0, 15}.points();   // below the threshold
    so.workers = 1;
    const CampbellStudy st = campbell_study(sys, so);
    CHECK(st.unstable.empty());
    CHECK(st.changes.empty());
    // An edge with no refined change inside the range is printed as a grid speed.
    UnstableRange r;
    r.branch = 1;
    r.from = 10.0;
    r.to = 20.0;
    r.first_index = 2;
    CHECK(unstable_span(r, so.unit) == "from 10 (a grid speed) to 20 (a grid speed) rad/s");
    r.first_index = 0;
    r.to_last = true;
    CHECK(unstable_span(r, so.unit) == "from 10 to 20 rad/s");
}
