// The Bode figure of a response: the amplitude on a linear axis unless asked for a log
// one (a resonance's half-power band reads off a linear axis), one amplitude panel per
// physical unit, then the phase.
#include <gyrokit/io/svg_figure.hpp>
#include <gyrokit/reports/response_reports.hpp>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>

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

TEST_CASE("polar figure: speed marks at the grid points nearest round speeds, labelled with their own speed",
          "[reports]") {
    // A Jeffcott-like circle Z(w) = 1 / (1 - (w/10)^2 + 0.2 i w/10) over 0..30 rad/s on an uneven
    // grid: the marks fall on grid points (5, 10, 15, 20, 25, 30 rad/s nearest), each label the
    // grid speed it sits on, none at 0 (the origin), none crowding another of its curve.
    ResponseCurve c;
    for (int i = 0; i <= 90; ++i) c.speeds.push_back(30.0 * std::pow(i / 90.0, 1.3));
    c.dofs = {0};
    c.Z.resize(static_cast<Eigen::Index>(c.speeds.size()), 1);
    for (std::size_t i = 0; i < c.speeds.size(); ++i) {
        const double r = c.speeds[i] / 10.0;
        c.Z(static_cast<Eigen::Index>(i), 0) = 1.0 / std::complex<double>(1.0 - r * r, 0.2 * r);
    }
    const Figure f = response_polar_figure({"x"}, {"m"}, c, SpeedUnit{}, "t");
    REQUIRE(f.panels.size() == 1);
    const Series& s = f.panels[0].series.at(0);
    REQUIRE(s.point_labels.size() == s.x.size());
    CHECK(!s.color.empty());
    std::vector<double> marked;
    for (std::size_t i = 0; i < s.point_labels.size(); ++i) {
        if (s.point_labels[i].empty()) continue;
        CHECK(s.point_labels[i] == fmt::format("{:.6g} rad/s", c.speeds[i]));
        CHECK(c.speeds[i] > 0.0);
        marked.push_back(c.speeds[i]);
    }
    REQUIRE(marked.size() >= 3);
    for (const double w : marked) {
        // The grid point nearest a multiple of 5.
        const double round = 5.0 * std::round(w / 5.0);
        for (const double g : c.speeds) CHECK(std::abs(w - round) <= std::abs(g - round));
    }
    // In a unit that scales the speeds: the same points, the labels in that unit.
    const SpeedUnit rpm = SpeedUnit::parse("rpm");
    const Figure g = response_polar_figure({"x"}, {"m"}, c, rpm, "t");
    for (const std::string& l : g.panels[0].series.at(0).point_labels)
        if (!l.empty()) CHECK((l.find(" rpm") != std::string::npos && l.find("e+") == std::string::npos));
    // Drawn: gnuplot's script and the SVG carry the labels (a mismatched count is refused).
    const std::string svg = svg_figure(f);
    CHECK(svg.find(">" + s.point_labels[std::distance(s.point_labels.begin(),
                                                      std::find_if(s.point_labels.begin(), s.point_labels.end(),
                                                                   [](const std::string& t) { return !t.empty(); }))] +
                   "</text>") != std::string::npos);
    Figure bad = f;
    bad.panels[0].series[0].point_labels.pop_back();
    CHECK_THROWS_WITH(check_figure(bad, "polar"), Catch::Contains("point labels for") && Catch::Contains("one per point"));
}
