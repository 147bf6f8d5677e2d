// campbell, critical, stability, pervasive: the modes over speed.
#include <gyrokit/analysis/pervasive_damping.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/reports.hpp>

#include <algorithm>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string harmonics, critical_method = "branches";
    int modes = kNotGiven;
    double tolerance = defaults::pervasive_tolerance;
    bool rows = false;
};

// The shared options with this command's --modes and --harmonics.
RotorRequest request(const Options& o) {
    RotorRequest r = request_of(o.common);
    r.modes = given_modes(o.modes);
    if (!o.harmonics.empty()) r.harmonics = parse_harmonics(o.harmonics, {});
    return r;
}

// campbell: the tracked diagram; on the first screen a summary with the critical speeds.
Command campbell_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* camp = app.add_subcommand("campbell", "modes tracked over speed (Campbell diagram)");
    add_common(camp, o->common, true);
    add_motion_option(camp, o->common);
    add_solver_options(camp, o->common);
    add_cut_option(camp, o->common);
    camp->add_option("--modes", o->modes, "number of modes to track: the K lowest by frequency (0 = all; sparse: "
                                          "the K nearest --target, default 6); default: the scene's, else the "
                                          "modes in range");
    add_output_option(camp, "--plot", o->common.plot, "draw the diagram into FILE.svg or FILE.png");
    camp->add_option("--harmonics", o->harmonics, "harmonic lines drawn, e.g. 1,2 (default: the scene's, else 1)");
    camp->add_flag("--rows", o->rows, "table format: every row of the diagram instead of the summary");
    return {camp, [o](std::ostream& out) {
        const Context c = open_scene(o->common, request(*o), true);
        const StudyOptions so = with_progress(c.study);
        const std::vector<int>& h = so.harmonics;
        const CampbellStudy st = campbell_study(c.scene.system, so);
        const CampbellDiagram& cd = st.diagram;
        // The first screen (table format): a summary and the critical speeds; the rows on request.
        const bool summary = c.format == TableFormat::Text && !o->rows;
        std::vector<CriticalSpeed> cs;
        if (summary || !o->common.plot.empty()) cs = critical_speeds_of(c.scene.system, st, so);
        if (summary) {
            write_table(out, campbell_summary(st, cs, c.unit, o->common.plot), c.format);
            out << "\n";
            write_tables(out, critical_tables(cs, c.unit), c.format);
        } else {
            write_table(out, campbell_table(cd, c.unit), c.format);
        }
        if (!o->common.plot.empty()) plot_if(o->common.plot, campbell_figure(cd, cs, h, c.unit, c.scene.title));
        // The summary names the modes out of range in a row of its own.
        if (summary)
            print_diagnostics(st.diagnostics, {Diagnostic::Topic::OutOfRange});
        else
            print_diagnostics(st.diagnostics);
    }};
}

// critical: crossings with the k x speed lines, on tracked branches or by the direct method.
Command critical_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* crit = app.add_subcommand("critical", "critical speeds: crossings with the k x speed lines");
    add_common(crit, o->common, true);
    add_motion_option(crit, o->common);
    add_solver_options(crit, o->common);
    add_cut_option(crit, o->common);
    crit->add_option("--harmonics", o->harmonics, "harmonics k, e.g. 1,2 (default: the scene's, else 1)");
    crit->add_option("--modes", o->modes, "number of modes considered (0 = all); default: the scene's, else the modes in range");
    crit->add_option("--critical-method", o->critical_method,
                     "branches (root finding on tracked modes) or direct (linear eigenproblem; undamped only)")
        ->capture_default_str();
    return {crit, [o](std::ostream& out) {
        if (o->critical_method != "branches" && o->critical_method != "direct")
            throw InputError("--critical-method '" + o->critical_method + "': allowed: branches, direct");
        const Context c = open_scene(o->common, request(*o), true);
        const std::vector<int>& h = c.study.harmonics;
        std::vector<CriticalSpeed> cs;
        if (o->critical_method == "direct") {
            require_dense(c, "critical --critical-method direct");
            for (int k : h) {
                auto d = critical_speeds_direct(c.scene.system, k, c.speeds.front(), c.speeds.back());
                cs.insert(cs.end(), d.begin(), d.end());
            }
            std::sort(cs.begin(), cs.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
            set_amplification_factors(cs, c.scene.system);
        } else {
            const CriticalSpeedStudy st = critical_speed_study(c.scene.system, with_progress(c.study));
            cs = st.critical;
            print_diagnostics(st.tracked.diagnostics);
        }
        // A person reads the critical speeds and the heavily damped crossings apart; a script gets one table.
        if (c.format == TableFormat::Text)
            write_tables(out, critical_tables(cs, c.unit), c.format);
        else
            write_table(out, critical_table(cs, c.unit), c.format);
    }};
}

// stability: the speeds where a mode becomes unstable or stable again.
Command stability_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* stab = app.add_subcommand("stability", "speeds where a mode becomes unstable or stable again");
    add_common(stab, o->common, true);
    add_motion_option(stab, o->common);
    add_solver_options(stab, o->common);
    add_cut_option(stab, o->common);
    stab->add_option("--modes", o->modes, "number of modes considered (0 = all; sparse: default 6); default: the scene's, else the "
                                          "modes in range");
    return {stab, [o](std::ostream& out) {
        const Context c = open_scene(o->common, request(*o), true);
        const StabilityStudy st = stability_study(c.scene.system, with_progress(c.study));
        write_table(out, stability_table(st.changes, c.unit), c.format);
        print_diagnostics(st.tracked.diagnostics);
    }};
}

// pervasive: the Hautus check for each damping component.
Command pervasive_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* perv = app.add_subcommand("pervasive", "Hautus pervasive-damping check for each damping component");
    add_common(perv, o->common, true);
    add_motion_option(perv, o->common);
    add_solver_options(perv, o->common);
    perv->add_option("--tolerance", o->tolerance, "largest residual of a loss (a loss must also be within 1e3 "
                                                  "times the eigenpair's backward error)")
        ->capture_default_str();
    perv->add_option("--modes", o->modes, "number of modes checked: the K lowest (0 = all); default: the scene's, else the "
                                                  "modes in range")
        ->check(CLI::Range(0, 100000000));
    return {perv, [o](std::ostream& out) {
        const Context c = open_scene(o->common, request(*o), true);
        const PervasiveStudy st = pervasive_study(c.scene.system, c.study, o->tolerance);
        print_diagnostics(st.diagnostics);
        // Csv holds one table: the losses; Text and Json the summary too.
        if (c.format == TableFormat::Csv)
            write_table(out, pervasive_table(st.report, c.unit), c.format);
        else
            write_tables(out, {pervasive_summary(st.report, c.unit), pervasive_table(st.report, c.unit)}, c.format);
    }};
}

}  // namespace

std::vector<Command> add_tracking_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    return {campbell_command(app, o), critical_command(app, o), stability_command(app, o), pervasive_command(app, o)};
}

}  // namespace gyrokit::cli
