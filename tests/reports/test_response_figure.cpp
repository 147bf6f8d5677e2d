// The Bode figure of a response: the amplitude on a linear axis unless asked for a log
// one (a resonance's half-power band reads off a linear axis), one amplitude panel per
// physical unit, then the phase.
#include <gyrokit/reports/response_reports.hpp>

#include <catch2/catch.hpp>

using namespace gyrokit;

TEST_CASE("Bode figure: the amplitude axis linear by default, log on request", "[reports]") {
    ResponseCurve c;
    c.speeds = {0.0, 1.0, 2.0};
    c.dofs = {0, 1};
    c.Z = Eigen::MatrixXcd::Ones(3, 2);
    const std::vector<std::string> names{"x0", "t0"}, units{"m", "rad"};
    const Figure linear = response_figure(names, units, c, SpeedUnit{}, "t");
    REQUIRE(linear.panels.size() == 3);   // m, rad, phase
    CHECK(!linear.panels[0].logy);
    CHECK(!linear.panels[1].logy);
    CHECK(linear.panels[2].ylabel == "phase [deg]");
    const Figure log = response_figure(names, units, c, SpeedUnit{}, "t", {}, "speed", true);
    CHECK(log.panels[0].logy);
    CHECK(log.panels[1].logy);
    CHECK(!log.panels[2].logy);
}
