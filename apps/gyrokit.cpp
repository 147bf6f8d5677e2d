// gyrokit: command-line front end. Parses options, calls the library, prints.
// Exit status: 0 success, 2 bad input, 3 solver failure, 1 anything else.
#include "analysis/campbell.hpp"
#include "analysis/critical_speeds.hpp"
#include "analysis/pervasive_damping.hpp"
#include "analysis/unbalance_response.hpp"
#include "core/error.hpp"
#include "io/export.hpp"
#include "io/reports.hpp"
#include "io/scene.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

using namespace gyrokit;

namespace {

// Options every command shares.
struct Common {
    std::string scene, format = "table", units = "rad/s", speeds, method = "qz";
};

void add_common(CLI::App* c, Common& o, bool with_speeds) {
    c->add_option("scene", o.scene, "scene file (TOML)")->required();
    c->add_option("--format", o.format, "output format: table, csv or json")->capture_default_str();
    c->add_option("--units", o.units, "unit of speeds and frequencies on the command line and in the output: "
                                      "rad/s, Hz or rpm")->capture_default_str();
    c->add_option("--method", o.method, "eigensolver: qz (scaled QZ, default) or state (M^-1 state matrix)")
        ->capture_default_str();
    if (with_speeds) c->add_option("--speeds", o.speeds, "speed range FROM:TO:N (overrides the scene's [speeds])");
}

struct Context {
    Scene scene;
    TableFormat format;
    SpeedUnit unit;
    EigenOptions eig;
    std::vector<double> speeds;
};

// Checked before any work, so that a bad name costs nothing and prints nothing.
void check_plot_path(const std::string& path) {
    if (path.empty()) return;
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext != ".svg" && ext != ".png")
        throw InputError(fmt::format("--plot '{}': unsupported extension '{}'; allowed: .svg, .png", path, ext));
}

Context open(const Common& o, bool need_speeds) {
    Context c;
    c.format = parse_table_format(o.format);
    c.unit = SpeedUnit::parse(o.units);
    c.eig.method = parse_eigen_method(o.method);
    c.scene = load_scene(o.scene);
    if (!o.speeds.empty()) {
        c.speeds = SpeedRange::parse(o.speeds, "--speeds", c.unit.factor).points();
    } else if (c.scene.speeds) {
        c.speeds = c.scene.speeds->points();
    } else if (need_speeds) {
        throw InputError(o.scene + ": no speed range; give --speeds FROM:TO:N or a [speeds] table in the scene");
    }
    return c;
}

double parse_speed(const std::string& text, const std::string& option, const SpeedUnit& u) {
    try {
        size_t pos = 0;
        const double v = std::stod(text, &pos);
        if (pos == text.size() && std::isfinite(v) && v >= 0.0) return v / u.factor;
    } catch (const std::exception&) {
    }
    throw InputError(fmt::format("{} '{}': allowed: a finite number >= 0 ({})", option, text, u.name));
}

std::vector<int> parse_harmonics(const std::string& text, const std::vector<int>& fallback) {
    if (text.empty()) return fallback;
    std::vector<int> h;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        try {
            size_t pos = 0;
            const long v = std::stol(item, &pos);
            if (pos != item.size() || v < 1 || v > 1000) throw std::out_of_range(item);
            h.push_back(static_cast<int>(v));
        } catch (const std::exception&) {
            throw InputError(fmt::format("--harmonics '{}': allowed: whole numbers in [1, 1000] separated by commas",
                                         text));
        }
        start = end + 1;
    }
    return h;
}

void plot_if(const std::string& path, const Figure& f) {
    if (path.empty()) return;
    render_figure(f, path);
    std::cerr << "wrote " << path << "\n";
}

CampbellOptions campbell_options(const Context& c, int modes) {
    CampbellOptions co;
    co.eig = c.eig;
    co.modes = modes >= 0 ? modes : c.scene.modes;
    return co;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"gyrokit: Campbell diagrams, critical speeds, pervasive damping and unbalance response "
                 "of gyroscopic systems"};
    app.require_subcommand(1);
    Common o;

    std::string speed_text, plot, dir, harmonics, crit_method = "branches";
    int modes = -1;
    double tolerance = 1e-8;
    bool extrema = false;

    auto* eig = app.add_subcommand("eig", "all eigenvalues at one speed");
    add_common(eig, o, false);
    eig->add_option("--speed", speed_text, "spin speed (in --units)")->required();

    auto* camp = app.add_subcommand("campbell", "modes tracked over speed (Campbell diagram)");
    add_common(camp, o, true);
    camp->add_option("--modes", modes, "number of modes to track: the K lowest by frequency (0 = all)");
    camp->add_option("--plot", plot, "draw the diagram into FILE.svg or FILE.png");
    camp->add_option("--harmonics", harmonics, "harmonic lines drawn, e.g. 1,2 (default: the scene's, else 1)");

    auto* crit = app.add_subcommand("critical", "critical speeds: crossings with the k x speed lines");
    add_common(crit, o, true);
    crit->add_option("--harmonics", harmonics, "harmonics k, e.g. 1,2 (default: the scene's, else 1)");
    crit->add_option("--modes", modes, "number of modes considered (0 = all)");
    crit->add_option("--critical-method", crit_method,
                     "branches (root finding on tracked modes) or direct (linear eigenproblem; undamped only)")
        ->capture_default_str();

    auto* stab = app.add_subcommand("stability", "speeds where a mode becomes unstable or stable again");
    add_common(stab, o, true);

    auto* perv = app.add_subcommand("pervasive", "Hautus pervasive-damping check for each damping component");
    add_common(perv, o, true);
    perv->add_option("--tolerance", tolerance, "residual below which damping counts as not pervading")
        ->capture_default_str();

    auto* resp = app.add_subcommand("response", "unbalance response: amplitude and phase per DOF");
    add_common(resp, o, true);
    resp->add_option("--plot", plot, "draw amplitude and phase into FILE.svg or FILE.png");
    resp->add_flag("--extrema", extrema, "print the peaks and antiresonances instead of the curve");

    auto* exp = app.add_subcommand("export", "M, D, G, K, N and the state matrices as Matrix Market");
    add_common(exp, o, false);
    exp->add_option("--speed", speed_text, "spin speed for the assembled matrices (in --units)")->required();
    exp->add_option("--dir", dir, "output directory (created if missing)")->required();

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "error: " << e.what() << " (see --help)\n";
        return 2;
    }

    try {
        check_plot_path(plot);
        std::ostream& out = std::cout;
        if (eig->parsed()) {
            Context c = open(o, false);
            const double w = parse_speed(speed_text, "--speed", c.unit);
            const QuadraticSpectrum s = solve_at_speed(c.scene.system, w, c.eig);
            write_table(out, eig_table(s, w, c.unit), c.format);
        } else if (camp->parsed()) {
            Context c = open(o, true);
            const CampbellDiagram cd = campbell(c.scene.system, c.speeds, campbell_options(c, modes));
            write_table(out, campbell_table(cd, c.unit), c.format);
            if (!plot.empty()) {
                const auto h = parse_harmonics(harmonics, c.scene.harmonics);
                plot_if(plot, campbell_figure(cd, critical_speeds(c.scene.system, cd, h, c.eig), h, c.unit,
                                              c.scene.title));
            }
            if (cd.ambiguous_steps > 0)
                std::cerr << "note: " << cd.ambiguous_steps
                          << " speed steps stayed ambiguous at the refinement limit; use a finer --speeds grid\n";
        } else if (crit->parsed()) {
            Context c = open(o, true);
            const auto h = parse_harmonics(harmonics, c.scene.harmonics);
            std::vector<CriticalSpeed> cs;
            if (crit_method == "direct") {
                for (int k : h) {
                    auto d = critical_speeds_direct(c.scene.system, k, c.speeds.front(), c.speeds.back());
                    cs.insert(cs.end(), d.begin(), d.end());
                }
                std::sort(cs.begin(), cs.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
            } else if (crit_method == "branches") {
                const CampbellDiagram cd = campbell(c.scene.system, c.speeds, campbell_options(c, modes));
                cs = critical_speeds(c.scene.system, cd, h, c.eig);
            } else {
                throw InputError("--critical-method '" + crit_method + "': allowed: branches, direct");
            }
            write_table(out, critical_table(cs, c.unit), c.format);
        } else if (stab->parsed()) {
            Context c = open(o, true);
            const CampbellDiagram cd = campbell(c.scene.system, c.speeds, campbell_options(c, 0));
            write_table(out, stability_table(stability_changes(c.scene.system, cd, c.eig), c.unit), c.format);
        } else if (perv->parsed()) {
            Context c = open(o, true);
            if (!(tolerance > 0.0 && tolerance < 1.0))
                throw InputError(fmt::format("--tolerance {}: allowed: 0 < tolerance < 1", tolerance));
            write_table(out, pervasive_table(pervasive_damping(c.scene.system, c.speeds, {tolerance}), c.unit),
                        c.format);
        } else if (resp->parsed()) {
            Context c = open(o, true);
            const ResponseCurve rc = unbalance_response(c.scene.system, c.speeds);
            if (extrema)
                write_table(out, extrema_table(c.scene.system, response_extrema(c.scene.system, rc), c.unit),
                            c.format);
            else
                write_table(out, response_table(c.scene.system, rc, c.unit), c.format);
            plot_if(plot, response_figure(c.scene.system, rc, c.unit, c.scene.title));
        } else if (exp->parsed()) {
            Context c = open(o, false);
            const double w = parse_speed(speed_text, "--speed", c.unit);
            export_matrices(c.scene.system, w, dir);
            std::cerr << "wrote the matrices at " << c.unit.factor * w << " " << c.unit.name << " into " << dir << "\n";
        }
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const SolverError& e) {
        std::cerr << "solver error: " << e.what() << "\n";
        return 3;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
