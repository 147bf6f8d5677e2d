// transient: time integration of the unbalance response at a constant speed or in a run-up / run-down.
#include "cli/common.hpp"
#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/analysis/transient_signals.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/number_text.hpp>
#include <gyrokit/io/output_file.hpp>
#include <gyrokit/reports/transient_reports.hpp>

#include <algorithm>
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
    std::string speed, run_up, acceleration, duration, dt, dofs, node, start = "rest", out, waterfall;
    long long max_steps = defaults::max_steps;
};

double number(const std::string& text, const std::string& option, const std::string& allowed) {
    return parse_decimal(text, option, allowed);
}

// The speed history from --speed, or --run-up FROM:TO with --acceleration, in rad/s.
SpeedProfile profile_of(const Options& o, const SpeedUnit& u) {
    if (!o.speed.empty() && !o.run_up.empty())
        throw InputError("--speed and --run-up: allowed: one of them (a constant speed, or a run-up or run-down)");
    if (o.speed.empty() && o.run_up.empty())
        throw InputError("no speed: allowed: --speed W (a constant speed) or --run-up W0:W1 with --acceleration A");
    if (!o.speed.empty()) {
        if (!o.acceleration.empty()) throw InputError("--acceleration: only together with --run-up W0:W1");
        const double w = parse_speed(o.speed, "--speed", u);
        return {w, w, 0.0};
    }
    const std::size_t colon = o.run_up.find(':');
    const std::string allowed = fmt::format("FROM:TO, two different speeds >= 0 ({})", u.name);
    if (colon == std::string::npos) throw InputError(fmt::format("--run-up '{}': allowed: {}", o.run_up, allowed));
    const double from = number(o.run_up.substr(0, colon), "--run-up", allowed);
    const double to = number(o.run_up.substr(colon + 1), "--run-up", allowed);
    if (from < 0.0 || to < 0.0 || from == to)
        throw InputError(fmt::format("--run-up '{}': allowed: {}", o.run_up, allowed));
    if (o.acceleration.empty())
        throw InputError(fmt::format("--run-up needs --acceleration A ({}; > 0 for a run-up, < 0 for a run-down)",
                                     u.per_second()));
    const std::string sign = to > from ? "> 0" : "< 0";
    const double a = number(o.acceleration, "--acceleration", fmt::format("a finite number {} ({})", sign, u.per_second()));
    if ((to - from) * a <= 0.0)
        throw InputError(fmt::format("--acceleration {} {} with a {} from {} to {} {}: allowed: a finite number {}",
                                     o.acceleration, u.per_second(), to > from ? "run-up" : "run-down", from, to, u.name,
                                     sign));
    return {from / u.factor, to / u.factor, a / u.factor};
}

std::vector<int> outputs_of(const Options& o, const GyroscopicSystem& sys) {
    if (!o.dofs.empty() && !o.node.empty()) throw InputError("--dofs and --node: allowed: one of them");
    std::vector<int> out;
    if (!o.node.empty()) {
        const int node = static_cast<int>(number(o.node, "--node", "a node number"));
        if (std::to_string(node) != o.node) throw InputError("--node '" + o.node + "': allowed: a node number");
        try {
            out = sys.node_translations(node);
        } catch (const InputError& e) {
            throw InputError("--node " + o.node + ": " + e.what());
        }
        if (out.empty())
            throw InputError(fmt::format("--node {}: no free lateral translation (a support holds it, or the model "
                                         "has no lateral DOFs); allowed: a node with free x or y",
                                         node));
    }
    if (!o.dofs.empty()) out = dofs_by_name(o.dofs, sys.dof_names, "--dofs");
    return out.empty() ? transient_outputs(sys) : out;
}

void draw(const Options& o, const Context& c, const TransientResult& r, SolverKind kind) {
    const bool steady = o.start == "steady";
    if (!o.common.plot.empty()) plot_if(o.common.plot, transient_figure(c.scene.system, r, c.unit, steady, kind, c.scene.length_unit()));
    if (!o.waterfall.empty()) plot_if(o.waterfall, transient_waterfall_figure(c.scene.system, r, c.unit, steady, c.scene.length_unit()), "--waterfall");
}

void run(const Options& o, std::ostream& out) {
    check_plot_path(o.waterfall, "--waterfall");
    if (o.start != "rest" && o.start != "steady")
        throw InputError("--start '" + o.start + "': allowed: rest, steady");
    const Context c = open_scene(o.common, false);
    const GyroscopicSystem& sys = c.scene.system;
    TransientOptions opt;
    opt.profile = profile_of(o, c.unit);
    opt.unit = c.unit;
    // 0 means the default to the library: given, it is refused here.
    if (!o.duration.empty() && (opt.duration = number(o.duration, "--duration", "a finite time > 0 (s)")) == 0.0)
        throw InputError("--duration 0 s: allowed: a finite time > 0 (s); none: the ramp or 100 revolutions");
    if (!o.dt.empty() && (opt.dt = number(o.dt, "--dt", "a finite time step > 0 (s)")) == 0.0)
        throw InputError("--dt 0 s: allowed: a finite time step > 0 (s); none: 32 steps per period of the band");
    opt.outputs = outputs_of(o, sys);
    opt.start_steady = o.start == "steady";
    opt.max_steps = o.max_steps;
    opt.kind = use_sparse(c) ? SolverKind::Sparse : SolverKind::Dense;
    if (!o.common.plot.empty() && opt.profile.acceleration == 0.0 && opt.outputs.size() < 2)
        throw InputError("--plot at a constant speed draws an orbit: allowed: two DOFs (--node N, or --dofs X,Y)");
    std::optional<OutputFile> history;
    if (!o.out.empty()) history.emplace(o.out, "--out", "history");   // claimed and opened before the run
    const TransientResult r = transient_response(sys, opt);
    for (const std::string& n : r.notes) std::cerr << "note: " << spell_fields(n, flag_words) << "\n";
    const Table t = transient_run_table(sys, r, c.unit, opt.start_steady, opt.kind, c.scene.length_unit());
    write_table(out, t, c.format);
    if (history) {
        std::ostringstream text;
        write_table(text, transient_history_table(sys.dof_names, r, c.unit), TableFormat::Csv);
        history->write(text.str());
        history->commit();
    }
    draw(o, c, r, opt.kind);
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
