// The library's own SVG drawing of a Figure (io/svg_figure.hpp): ticks of 1, 2, 5 times a
// power of ten; a point drawn where the axes put it (read back from its hover circle);
// lines broken at dropped points; log axes dropping values <= 0; equal axes true to
// shape; text escaped; the figure checks of plot() applied.
#include <gyrokit/io/svg_figure.hpp>
#include <gyrokit/core/error.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <regex>
#include <string>

using namespace gyrokit;

namespace {

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The hover circles' centres, in order.
std::vector<std::pair<double, double>> circles(const std::string& svg) {
    std::vector<std::pair<double, double>> out;
    const std::regex c("<circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), c); it != std::sregex_iterator(); ++it)
        out.push_back({std::stod((*it)[1]), std::stod((*it)[2])});
    return out;
}

Figure one_panel(Series s) {
    Figure f;
    Panel p;
    p.xlabel = "x";
    p.ylabel = "y";
    p.series.push_back(std::move(s));
    f.panels.push_back(p);
    return f;
}

}  // namespace

TEST_CASE("SVG figure: ticks 1, 2 or 5 times a power of ten, decades on a log axis", "[svg]") {
    CHECK(axis_ticks(0, 10, false) == std::vector<double>{0, 2, 4, 6, 8, 10});
    CHECK(axis_ticks(-0.3, 0.7, false) == std::vector<double>{-0.2, 0.0, 0.2, 0.4, 0.6});
    const std::vector<double> big = axis_ticks(1234, 98765, false);
    CHECK(big.front() == 20000);
    CHECK(big[1] - big[0] == 20000);
    CHECK(axis_ticks(1e-3, 1e3, true) == std::vector<double>{1e-3, 1e-2, 1e-1, 1, 1e1, 1e2, 1e3});
    CHECK(axis_ticks(1e-10, 1e10, true).size() <= 7);   // thinned
    CHECK(axis_ticks(2, 5, true) == std::vector<double>{2, 5});   // no power inside: the ends
    CHECK(axis_ticks(1, 1, false).empty());
}

TEST_CASE("SVG figure: each point where the axes put it, a hover title with its values", "[svg]") {
    Series s;
    s.x = {0, 5, 10};
    s.y = {0, 50, 100};
    s.label = "speed & <load>";
    Figure f = one_panel(s);
    f.panels[0].xmin = 0;
    f.panels[0].xmax = 10;
    f.panels[0].ymin = 0;
    f.panels[0].ymax = 100;
    const std::string svg = svg_figure(f, "t");
    const auto c = circles(svg);
    REQUIRE(c.size() == 3);
    // Linear maps: equal steps in x and y land at equal steps in pixels, y pointing up.
    CHECK(c[1].first - c[0].first == Approx(c[2].first - c[1].first).margin(0.02));
    CHECK(c[0].second - c[1].second == Approx(c[1].second - c[2].second).margin(0.02));
    CHECK(c[0].second > c[2].second);
    CHECK(count(svg, "<title>") == 3);
    CHECK(svg.find("<title>speed &amp; &lt;load&gt;: x = 5, y = 50</title>") != std::string::npos);
    CHECK(count(svg, "<polyline") == 1);
    CHECK(svg.find("<clipPath id=\"t-p0\">") != std::string::npos);
}

TEST_CASE("SVG figure: lines broken at dropped points, log axes without values <= 0", "[svg]") {
    Series s;
    s.x = {1, 2, 3, 4, 5, 6};
    s.y = {1, 2, std::numeric_limits<double>::quiet_NaN(), 4, -5, 6};
    const std::string linear = svg_figure(one_panel(s));
    CHECK(count(linear, "<polyline") == 2);   // 1-2 | 4, -5, 6
    CHECK(circles(linear).size() == 5);
    Figure log = one_panel(s);
    log.panels[0].logy = true;
    const std::string l = svg_figure(log);
    CHECK(count(l, "<polyline") == 1);        // 1-2 | 4 | 6: single points draw no line
    CHECK(circles(l).size() == 4);
    // Every third decade labelled at most; the y axis spans the decades around 1 to 6.
    CHECK(l.find(">10</text>") != std::string::npos);
}

TEST_CASE("SVG figure: equal axes draw a circle round, many points keep a bounded number of titles", "[svg]") {
    Series s;
    for (int k = 0; k <= 3000; ++k) {
        s.x.push_back(2 * std::cos(2 * M_PI * k / 3000));
        s.y.push_back(2 * std::sin(2 * M_PI * k / 3000));
    }
    Figure f = one_panel(s);
    f.panels[0].equal_axes = true;
    const std::string svg = svg_figure(f);
    const auto c = circles(svg);
    CHECK(static_cast<int>(c.size()) <= kSvgTitledPoints + 1);
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (const auto& [x, y] : c) x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    CHECK(x1 - x0 == Approx(y1 - y0).epsilon(0.01));
}

TEST_CASE("SVG figure: refused as plot() refuses", "[svg]") {
    CHECK_THROWS_AS(svg_figure(Figure{}), InputError);
    Series s;
    s.x = {1, 2};
    s.y = {1};
    CHECK_THROWS_WITH(svg_figure(one_panel(s)), Catch::Contains("has 2 x values but 1 y values"));
    Series t;
    t.x = {1};
    t.y = {1};
    t.style = "wavy";
    CHECK_THROWS_WITH(svg_figure(one_panel(t)), Catch::Contains("unknown plot style 'wavy'"));
}
