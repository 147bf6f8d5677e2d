// transient: time integration of the unbalance response at a constant speed or in a run-up / run-down.
#include "cli/common.hpp"
#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/analysis/transient_signals.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/number_text.hpp>
#include <gyrokit/io/output_file.hpp>
#include <gyrokit/reports/transient_reports.hpp>
#include <gyrokit/study/transient_study.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <sstream>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string speed, run_up, acceleration, duration, dt, dofs, node, start = defaults::transient_start, out, waterfall;
    long long max_steps = defaults::max_steps;
};

// --run-up FROM:TO as two numbers (their range is the study's to check).
std::array<double, 2> run_up_of(const std::string& text, const SpeedUnit& u) {
    const std::size_t colon = text.find(':');
    const std::string allowed = fmt::format("FROM:TO, two different speeds >= 0 ({})", u.name);
    if (colon == std::string::npos) throw InputError(fmt::format("--run-up '{}': allowed: {}", text, allowed));
    return {parse_decimal(text.substr(0, colon), "--run-up", allowed),
            parse_decimal(text.substr(colon + 1), "--run-up", allowed)};
}

TransientRequest request_of(const Options& o, const SpeedUnit& u) {
    TransientRequest r;
    if (!o.speed.empty()) r.speed = parse_number(o.speed, "--speed");
    if (!o.run_up.empty()) r.run_up = run_up_of(o.run_up, u);
    if (!o.acceleration.empty()) r.acceleration = parse_number(o.acceleration, "--acceleration");
    if (!o.duration.empty()) r.duration = parse_number(o.duration, "--duration");
    if (!o.dt.empty()) r.dt = parse_number(o.dt, "--dt");
    r.dofs = split_names(o.dofs);
    if (!o.node.empty()) {
        const double node = parse_number(o.node, "--node");
        if (std::to_string(static_cast<int>(node)) != o.node) throw InputError("--node '" + o.node + "': allowed: a node number");
        r.node = static_cast<int>(node);
    }
    r.start = o.start;
    r.max_steps = o.max_steps;
    return r;
}

void draw(const Options& o, const Scene& scene, const TransientStudy& st) {
    const bool steady = st.options.start_steady;
    const GyroscopicSystem& sys = scene.system;
    if (!o.common.plot.empty())
        plot_if(o.common.plot, transient_figure(sys, st.result, st.unit, steady, st.options.kind, st.length));
    if (!o.waterfall.empty())
        plot_if(o.waterfall, transient_waterfall_figure(sys, st.result, st.unit, steady, st.length), "--waterfall");
}

void run(const Options& o, std::ostream& out) {
    check_plot_path(o.waterfall, "--waterfall");
    const Context c = open_scene(o.common, false);
    const TransientRequest rq = request_of(o, c.unit);
    const TransientOptions opt = transient_options(c.scene, c.request, rq);   // checked before any file is claimed
    if (!o.common.plot.empty() && opt.profile.acceleration == 0.0 && opt.outputs.size() < 2)
        throw InputError("--plot at a constant speed draws an orbit: allowed: two DOFs (--node N, or --dofs X,Y)");
    std::optional<OutputFile> history;
    if (!o.out.empty()) history.emplace(o.out, "--out", "history");   // claimed and opened before the run
    const TransientStudy st = transient_study(c.scene, c.request, rq);
    for (const std::string& n : st.result.notes) std::cerr << "note: " << spell_fields(n, flag_words) << "\n";
    write_table(out, st.table, c.format);
    if (history) {
        std::ostringstream text;
        write_table(text, transient_history_table(c.scene.system.dofs.names, st.result, st.unit), TableFormat::Csv);
        history->write(text.str());
        history->commit();
    }
    draw(o, c.scene, st);
}

}  // namespace

std::vector<Command> add_transient_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("transient", "transient unbalance response by time integration (Newmark): at a "
                                                "constant speed or in a run-up / run-down; orbit, envelope, waterfall");
    add_common(cmd, o->common, false);
    add_motion_option(cmd, o->common);
    cmd->add_option("--speed", o->speed, "constant speed (in --units)");
    cmd->add_option("--run-up", o->run_up, "run-up (or run-down) W0:W1 (in --units), with --acceleration");
    cmd->add_option("--acceleration", o->acceleration, "angular acceleration of the run-up (--units per s: rad/s^2, "
                                                       "Hz/s, rpm/s); < 0 for a run-down");
    cmd->add_option("--duration", o->duration, "length of the run in s (default: the ramp; at a constant speed 100 "
                                               "revolutions); after the ramp the speed holds");
    cmd->add_option("--dt", o->dt, "time step in s (default: 32 steps per period of 1.5 x the top speed)");
    cmd->add_option("--max-steps", o->max_steps, "largest number of time steps allowed")->capture_default_str();
    cmd->add_option("--dofs", o->dofs, "DOFs recorded, by name, e.g. x12,y12 (default: the node of the unbalance)");
    cmd->add_option("--node", o->node, "record the lateral translations x, y of this node");
    cmd->add_option("--start", o->start, "initial state: rest, or steady (the steady response at the first speed)")
        ->capture_default_str();
    add_output_option(cmd, "--out", o->out, "the full history (every step) as CSV into FILE");
    add_output_option(cmd, "--plot", o->common.plot, "FILE.svg|.png: the orbit (constant speed) or the run-up envelope "
                                              "against the steady response");
    add_output_option(cmd, "--waterfall", o->waterfall, "FILE.svg|.png: spectra of windows of the signal against speed");
    return {{cmd, [o](std::ostream& out) { run(*o, out); }}};
}

}  // namespace gyrokit::cli
