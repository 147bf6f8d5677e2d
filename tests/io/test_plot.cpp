#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/plot.hpp>

using namespace gyrokit;
namespace fs = std::filesystem;

namespace {

// A fresh directory whose name has a space and a quote, to exercise path quoting.
struct ScratchDir {
    fs::path path;
    ScratchDir() {
        std::string tmpl = (fs::temp_directory_path() / "gyrokit test's plot-XXXXXX").string();
        REQUIRE(mkdtemp(tmpl.data()));
        path = tmpl;
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

// Sets an environment variable for one scope.
struct EnvGuard {
    std::string name;
    std::optional<std::string> old;
    EnvGuard(std::string n, const std::string& value) : name(std::move(n)) {
        if (const char* v = std::getenv(name.c_str())) old = v;
        setenv(name.c_str(), value.c_str(), 1);
    }
    ~EnvGuard() {
        if (old) setenv(name.c_str(), old->c_str(), 1);
        else unsetenv(name.c_str());
    }
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Two panels: a Campbell-like diagram and a log-scale damping chart with the
// awkward inputs the renderer must survive.
Figure two_panel_figure() {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    Series fw{{0, 100, 200, 300}, {10, 12, 15, 19}, "forward whirl", "lines", "#1f77b4"};
    Series bw{{0, 100, 200, 300}, {10, 8, nan, 5}, "backward 'whirl'", "dashed", "#d62728"};
    Series line{{0, 300}, {0, 300}, "", "lines", ""};
    Series empty{{}, {}, "skipped", "points", ""};
    Series decay{{0, 100, 200, 300, 400}, {1e-1, 1e-3, -1.0, inf, 1e-5}, "zeta_1 ^ {x} @ & < >", "linespoints", ""};
    Series pts{{0, 100}, {2e-2, 3e-4}, "", "points", "dark-green"};

    Figure fig;
    fig.title = "Gyrostat: \"it's\" a test";
    fig.panels.push_back({"Ω (rad/s)", "ω (rad/s)", "Campbell", false, {fw, bw, line, empty}, {}, {}, {}, {}});
    // Two quotes in a row (a second derivative) and a backslash: gnuplot misreads '' twice in a row.
    fig.panels.push_back({"Ω (rad/s)", "damping ratio", "moment (E I x'', E I y'') back\\slash", true, {decay, pts},
                          1e-6, {}, {}, 400.0});
    return fig;
}

}  // namespace

TEST_CASE("render_figure writes a two-panel SVG and PNG and cleans up") {
    ScratchDir out, tmp;
    EnvGuard tmpdir("TMPDIR", tmp.path.string());   // render_figure's scratch files land here
    const Figure fig = two_panel_figure();

    const fs::path svg = out.path / "fig.svg", png = out.path / "fig.PNG";
    render_figure(fig, svg.string());
    render_figure(fig, png.string());

    REQUIRE(fs::exists(svg));
    REQUIRE(fs::exists(png));
    CHECK(fs::file_size(svg) > 0);
    CHECK(fs::file_size(png) > 0);
    const std::string s = slurp(svg);
    CHECK((s.rfind("<?xml", 0) == 0 || s.find("<svg") != std::string::npos));
    CHECK(s.find("</svg>") != std::string::npos);
    CHECK(s.find("moment (E I x'', E I y'') back\\slash") != std::string::npos);
    CHECK(slurp(png).rfind("\x89PNG\r\n\x1a\n", 0) == 0);
    CHECK(fs::is_empty(tmp.path));   // temporary files removed
}

TEST_CASE("render_figure draws a panel without data as an empty frame") {
    ScratchDir out;
    Figure fig;
    Panel p;
    p.logy = true;
    p.series.push_back({{1, 2}, {-1, 0}, "nothing positive", "lines", ""});
    fig.panels = {p, Panel{}};
    const fs::path svg = out.path / "empty.svg";
    render_figure(fig, svg.string());
    CHECK(fs::file_size(svg) > 0);
}

TEST_CASE("render_figure rejects bad input") {
    ScratchDir out;
    Figure fig = two_panel_figure();
    const fs::path pdf = out.path / "fig.pdf";
    try {
        render_figure(fig, pdf.string());
        FAIL("no exception");
    } catch (const InputError& e) {
        const std::string msg = e.what();
        CHECK(msg.find(".pdf") != std::string::npos);
        CHECK(msg.find(".svg .png") != std::string::npos);
    }
    CHECK_THROWS_AS(render_figure(fig, (out.path / "noext").string()), InputError);
    CHECK_FALSE(fs::exists(pdf));

    const fs::path svg = out.path / "bad.svg";
    Figure styled = fig;
    styled.panels[0].series[0].style = "dashdot";
    CHECK_THROWS_AS(render_figure(styled, svg.string()), InputError);
    Figure ragged = fig;
    ragged.panels[1].series[0].y.pop_back();
    CHECK_THROWS_AS(render_figure(ragged, svg.string()), InputError);
    Figure logzero = fig;
    logzero.panels[1].ymin = 0.0;
    CHECK_THROWS_AS(render_figure(logzero, svg.string()), InputError);
    CHECK_THROWS_AS(render_figure(Figure{}, svg.string()), InputError);
    CHECK_FALSE(fs::exists(svg));
}

TEST_CASE("render_figure reports gnuplot failures") {
    ScratchDir out;
    Figure fig = two_panel_figure();
    const fs::path svg = out.path / "fig.svg";

    fig.panels[0].series[0].color = "not-a-colour";   // gnuplot rejects it
    try {
        render_figure(fig, svg.string());
        FAIL("no exception");
    } catch (const InputError&) {
        FAIL("gnuplot's failure is not an input error of ours");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("gnuplot failed") != std::string::npos);
        CHECK(std::string(e.what()).find("unrecognized color") != std::string::npos);
    }
    CHECK_FALSE(fs::exists(svg));

    EnvGuard path("PATH", "/nonexistent");
    try {
        render_figure(two_panel_figure(), svg.string());
        FAIL("no exception");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("gnuplot-nox") != std::string::npos);
    }
}
