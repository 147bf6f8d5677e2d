// The HTML report of a scene: its sections in order, each table in the page under its key,
// each figure an inline SVG with hover titles, nothing fetched from the network and no
// script; an analysis that fails leaves its section with the reason and the others run;
// the page's text escaped; a request out of range refused.
#include <gyrokit/gyrokit.hpp>
#include <gyrokit/io/svg_figure.hpp>
#include <gyrokit/reports/html_report.hpp>
#include <gyrokit/study/report_study.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

using namespace gyrokit;

namespace {

std::string data_text(const std::string& name) {
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/" + name);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

}  // namespace

TEST_CASE("Report of an FE rotor: every section, its tables under their keys and its figures inline", "[report]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const Report rep = report_study(sc);
    std::vector<std::string> keys;
    std::size_t figures = 0;
    for (const ReportSection& s : rep.sections) {
        keys.push_back(s.key);
        CHECK(s.failed.empty());
        figures += s.figures.size();
    }
    CHECK(keys == std::vector<std::string>{"model", "map", "campbell", "modes", "stability", "api_unbalance", "level1"});
    CHECK(failed_sections(rep).empty());
    REQUIRE(rep.inputs.size() == 1);
    CHECK(rep.inputs[0].fingerprint.size() == 16);
    CHECK(rep.unit == "rpm");
    const std::string page = html_report(rep);
    for (const ReportSection& s : rep.sections) {
        CHECK(page.find("<section id=\"section-" + s.key + "\">") != std::string::npos);
        for (const Table& t : s.tables) CHECK(page.find("<table class=\"data\" id=\"" + t.key + "\">") != std::string::npos);
    }
    CHECK(page.find("id=\"critical_speeds\"") != std::string::npos);
    CHECK(page.find("id=\"level1_summary\"") != std::string::npos);
    CHECK(count(page, "<svg ") == static_cast<int>(figures));
    CHECK(count(page, "<title>") > 100);   // hover values
    // Self-contained: no script, nothing to fetch (the SVG namespace is a name, not a fetch).
    CHECK(page.find("<script") == std::string::npos);
    CHECK(count(page, "http") == count(page, "xmlns=\"http://www.w3.org/2000/svg\""));
    CHECK(page.find("@media print") != std::string::npos);
    // The mode shapes of the API 684 critical speeds of the 1x line only (not of the heavily
    // damped crossings): one figure each, the lowest first.
    const ReportSection& modes = rep.sections[3];
    int critical = 0;
    for (const Table& t : rep.sections[2].tables)
        if (t.key == "critical_speeds") critical = static_cast<int>(t.rows());
    CHECK(critical >= 1);
    CHECK(static_cast<int>(modes.figures.size()) == std::min(critical, 4));
    // Ids unique in the page.
    CHECK(count(page, "id=\"model\"") == 1);
    CHECK(page.find("<p>Speeds in rpm: 151 speeds from 0 to 15000 rpm") != std::string::npos);
}

TEST_CASE("Report: a failing analysis leaves its section with the reason, the others run, text escaped",
          "[report]") {
    // [api] with an mcs but neither stages nor qa: the unbalance cases run, Level I cannot.
    std::string text = data_text("three_disk_rotor.toml");
    text = text.substr(0, text.find("\n[api]")) + "\n[api]\nmcs = 10000\n";
    const std::size_t t = text.find("title = ");
    text.replace(t, text.find('\n', t) - t, "title = \"rotor <A&B>\"");
    const Scene sc = parse_scene(text, "partial.toml", GYROKIT_DATA_DIR);
    ReportRequest r;
    r.mode_shapes = 1;
    const Report rep = report_study(sc, r);
    const ReportSection& l1 = rep.sections.back();
    REQUIRE(l1.key == "level1");
    CHECK_THAT(l1.failed, Catch::Contains("the anticipated cross-coupling is unknown"));
    CHECK(l1.tables.empty());
    CHECK(rep.sections[rep.sections.size() - 2].failed.empty());   // the unbalance cases ran
    REQUIRE(failed_sections(rep).size() == 1);
    CHECK(rep.sections[3].figures.size() == 1);
    const std::string page = html_report(rep);
    CHECK(page.find("<p class=\"failed\">Not computed: ") != std::string::npos);
    CHECK(page.find("<h1>rotor &lt;A&amp;B&gt;</h1>") != std::string::npos);
    CHECK(page.find("<A&B>") == std::string::npos);
    ReportRequest bad;
    bad.mode_shapes = 21;
    CHECK_THROWS_WITH(report_study(sc, bad), Catch::Contains("21: allowed: 0 to 20"));
}

TEST_CASE("Report of a model that is no FE rotor: the sections it supports", "[report]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml");
    const Report rep = report_study(sc);
    std::vector<std::string> keys;
    for (const ReportSection& s : rep.sections) keys.push_back(s.key);
    CHECK(keys == std::vector<std::string>{"model", "campbell", "modes", "stability"});
}

TEST_CASE("SVG axes: a span that rounding makes is one value, ticks do not jump on an ulp", "[report]") {
    CHECK(axis_ticks(0, 1.2000000000000002, false) == axis_ticks(0, 1.2, false));
    CHECK(axis_ticks(1e8, std::nextafter(1e8, 2e8), false).size() <= 25);   // no runaway loop
    Figure f;
    Panel p;
    p.series.push_back({{1e8, 1e8}, {std::nextafter(1e8, 2e8), 1e8}, "", "lines", ""});
    p.series.push_back({{1e308, -1e308}, {1e308, -1e308}, "", "lines", ""});
    p.series.push_back({{3.0}, {4.0}, "one", "lines", ""});
    f.panels.push_back(p);
    const std::string svg = svg_figure(f);
    CHECK(svg.find("nan") == std::string::npos);
    CHECK(svg.find("inf") == std::string::npos);
    CHECK(svg.find("<title>one: ") != std::string::npos);   // a lone point is drawn as a marker
}
