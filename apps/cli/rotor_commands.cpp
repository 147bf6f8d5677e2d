// eig, campbell, critical, stability, pervasive, response, export.
#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/export.hpp>
#include <gyrokit/reports/reports.hpp>

#include <algorithm>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

// Option values of the rotor commands; one instance lives as long as the app.
struct Options {
    Common common;
    std::string speed, dir, harmonics, critical_method = "branches", dofs, nodes, at, select, per = "node";
    int modes = -1;
    double tolerance = 1e-8;
    bool extrema = false, rigid_body = false, rows = false, polar = false;
};

int wanted_modes(const Context& c, int modes) { return modes >= 0 ? modes : c.scene.modes; }

// The tracking of `modes` asked (kModesInRange: those the speeds and harmonics excite).
CampbellOptions campbell_options(const Context& c, const SolverChoice& plan, int modes, const std::vector<int>& harmonics) {
    CampbellOptions co = tracking_options(plan, modes, c.speeds, harmonics, c.jobs);
    co.eig = c.eig;
    co.progress = progress_bar("speeds");
    return co;
}

// Notes on speed-dependent bearings used outside their tables: over the sweep, or at one speed.
void note_extrapolation(const Context& c, std::optional<double> at = std::nullopt) {
    if (!at && c.speeds.empty()) return;
    const double from = at ? *at : c.speeds.front(), to = at ? *at : c.speeds.back();
    for (const auto& n : extrapolation_notes(c.scene.system.bearings, from, to)) std::cerr << "note: " << n << "\n";
}

// The items of a comma-separated list.
std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    size_t start = 0;
    while (!text.empty() && start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        out.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

// The response outputs: DOFs by name (--dofs), the DOFs in metres of nodes
// (--nodes) and of the nodes nearest axial positions (--at, m); empty: all.
std::vector<int> response_outputs(const Options& o, const GyroscopicSystem& sys);

// DOF indices from a list of names (empty: all).
std::vector<int> parse_dofs(const std::string& text, const std::vector<std::string>& names) {
    std::vector<int> out;
    size_t start = 0;
    while (!text.empty() && start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string name = text.substr(start, end - start);
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end())
            throw InputError(fmt::format("--dofs: '{}' is not a DOF of the model; allowed: names such as {}", name,
                                         names.empty() ? std::string("-") : names.front()));
        if (std::find(out.begin(), out.end(), static_cast<int>(it - names.begin())) != out.end())
            throw InputError(fmt::format("--dofs '{}': '{}' is listed twice; allowed: each DOF once", text, name));
        out.push_back(static_cast<int>(it - names.begin()));
        start = end + 1;
    }
    return out;
}

std::vector<int> response_outputs(const Options& o, const GyroscopicSystem& sys) {
    std::vector<int> out = parse_dofs(o.dofs, sys.dof_names);
    const auto add_node = [&](int node) {
        const std::vector<int> dofs = sys.node_translations(node);
        // Nothing would mean every DOF: a node held by a support is an error, not "all".
        if (dofs.empty())
            throw InputError(fmt::format("node {} has no free lateral translation (a support holds it, or the "
                                         "model has no lateral DOFs); allowed: a node with free x or y",
                                         node));
        for (const int k : dofs)
            if (std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
    };
    for (const std::string& item : split_list(o.nodes)) {
        try {
            size_t pos = 0;
            const int node = std::stoi(item, &pos);
            if (pos != item.size()) throw std::invalid_argument(item);
            add_node(node);
        } catch (const InputError& e) {
            throw InputError("--nodes " + item + ": " + e.what());
        } catch (const std::exception&) {
            throw InputError("--nodes '" + o.nodes + "': allowed: node numbers separated by commas");
        }
    }
    for (const std::string& item : split_list(o.at)) {
        double z = 0.0;
        try {
            size_t pos = 0;
            z = std::stod(item, &pos);
            if (pos != item.size()) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw InputError("--at '" + o.at + "': allowed: axial positions in m separated by commas");
        }
        try {
            add_node(sys.nearest_node(z));
        } catch (const InputError& e) {
            throw InputError("--at " + item + ": " + e.what());
        }
    }
    return out;
}

// What the tracked diagram says besides its rows: solver notes, rigid-body
// eigenvalues left out, ambiguity, and every unstable range (a warning).
void note_diagram(const CampbellDiagram& cd, const Context& c, bool in_summary = false) {
    for (const auto& n : cd.notes) std::cerr << "note: " << n << "\n";
    if (cd.rigid_body > 0)
        std::cerr << "note: " << cd.rigid_body << " rigid-body eigenvalues (lambda = 0: free motion of a singular K) "
                  << "are not modes and are not tracked\n";
    if (cd.ambiguous_steps > 0)
        std::cerr << "note: " << cd.ambiguous_steps
                  << " speed steps stayed ambiguous at the refinement limit; use a finer --speeds grid\n";
    for (const auto& w : instability_warnings(cd, c.unit)) std::cerr << "warning: " << w << "\n";
    if (std::isfinite(cd.band) && !in_summary) std::cerr << "note: " << out_of_range_note(cd, c.unit) << "\n";
}

// The steady unbalance response is no state the rotor reaches where a mode is
// unstable: the modes are tracked over the range (at most 21 speeds of it, a
// bounded cost next to the response itself; `campbell` checks every speed) and
// every unstable range is a warning.
void warn_unstable_response(const Context& c, int modes) {
    std::vector<double> grid = c.speeds;
    if (grid.size() > 21) {
        grid.clear();
        for (int k = 0; k <= 20; ++k) grid.push_back(c.speeds.front() + (c.speeds.back() - c.speeds.front()) * k / 20.0);
    }
    const SolverChoice plan = plan_solver(c, modes);
    CampbellOptions co = campbell_options(c, plan, modes, c.scene.harmonics);
    co.progress = {};
    const CampbellDiagram cd = campbell(tracking_solver(plan.make, co, grid), grid, co);
    for (const auto& w : instability_warnings(cd, c.unit))
        std::cerr << "warning: " << w << "; the unbalance response there is not a steady state\n";
}

}  // namespace

std::vector<Command> add_rotor_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    std::vector<Command> cmds;

    auto* eig = app.add_subcommand("eig", "all eigenvalues at one speed");
    add_common(eig, o->common, false);
    add_motion_option(eig, o->common);
    add_solver_options(eig, o->common);
    eig->add_option("--speed", o->speed, "spin speed (in --units)")->required();
    eig->add_option("--modes", o->modes, "sparse solver: number of modes near --target (default: the scene's, else 6)");
    eig->add_flag("--rigid-body", o->rigid_body, "list the rigid-body eigenvalues (lambda = 0) after the modes");
    cmds.push_back({eig, [o](std::ostream& out) {
        const Context c = open_scene(o->common, false);
        const double w = parse_speed(o->speed, "--speed", c.unit);
        note_extrapolation(c, w);
        const SolverChoice plan = plan_solver(c, wanted_modes(c, o->modes));
        const QuadraticSpectrum s = plan.make()(w);
        for (const auto& n : s.notes) std::cerr << "note: " << n << "\n";
        if (!o->rigid_body && !s.rigid_body.empty())
            std::cerr << "note: " << rigid_body_note(s.rigid_body, c.scene.dof_names()) << " (--rigid-body lists them)\n";
        write_table(out, eig_table(s, w, c.unit, o->rigid_body), c.format);
    }});

    auto* model = app.add_subcommand("model", "what the scene's model is: DOFs, mass, nodes, damping, bearings; "
                                              "--plot draws an FE rotor");
    model->add_option("scene", o->common.scene, "scene file (TOML)")->required();
    model->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    model->add_option("--plot", o->common.plot, "FE rotors: draw the shaft, disks and bearings into FILE.svg|.png");
    add_motion_option(model, o->common);
    cmds.push_back({model, [o](std::ostream& out) {
        const TableFormat format = parse_format(o->common);
        check_plot_path(o->common.plot);
        const Scene sc = load_motion_scene(o->common);
        if (!o->common.plot.empty() && !sc.fe_rotor)
            throw InputError("--plot: draws finite-element rotors; this model is " + sc.model_type);
        write_table(out, model_summary(sc), format);
        if (sc.fe_rotor) plot_if(o->common.plot, fe_rotor_figure(*sc.fe_rotor, sc.system, sc.title));
    }});

    auto* modes = app.add_subcommand("modes", "mode shapes at one speed: orbits per node (or entries per DOF)");
    add_common(modes, o->common, false);
    add_motion_option(modes, o->common);
    add_solver_options(modes, o->common);
    modes->add_option("--speed", o->speed, "spin speed (in --units); default 0")->default_str("0");
    modes->add_option("--modes", o->modes, "number of modes (the lowest, or the sparse window; default: the "
                                           "scene's, else all dense / 6 sparse)")
        ->check(CLI::Range(0, 100000000));
    modes->add_option("--mode", o->select, "only these modes, by number from 1: K or K,L,...");
    modes->add_option("--per", o->per, "node: one row per whirl pair (orbit); dof: one row per DOF")
        ->capture_default_str();
    modes->add_option("--plot", o->common.plot, "draw the shapes along the axis (or the orbits) into FILE.svg|.png");
    cmds.push_back({modes, [o](std::ostream& out) {
        const Context c = open_scene(o->common, false);
        if (o->per != "node" && o->per != "dof")
            throw InputError("--per '" + o->per + "': allowed: node, dof");
        const double w = o->speed.empty() ? 0.0 : parse_speed(o->speed, "--speed", c.unit);
        note_extrapolation(c, w);
        SolverOptions so = c.solver;
        so.modes = wanted_modes(c, o->modes);
        std::vector<std::string> notes;
        std::vector<ModeShape> shapes = mode_shapes(c.scene.system, w, so, &notes);
        for (const auto& n : notes) std::cerr << "note: " << n << "\n";
        if (!o->select.empty()) {
            std::vector<ModeShape> chosen;
            for (const int k : parse_harmonics(o->select, {}, "--mode")) {
                if (k > static_cast<int>(shapes.size()))
                    throw InputError(shapes.empty() ? fmt::format("--mode {}: no mode was computed at this speed", k)
                                                    : fmt::format("--mode {}: allowed: 1 to {} (the modes computed)",
                                                                  k, shapes.size()));
                chosen.push_back(shapes[static_cast<size_t>(k - 1)]);
            }
            shapes = std::move(chosen);
        }
        const auto& sys = c.scene.system;
        const bool per_dof = o->per == "dof" || sys.whirl_pairs.empty();
        Table detail = per_dof ? mode_dof_table(shapes, sys.dof_names, sys.dof_units, w, c.unit)
                               : mode_orbit_table(shapes, w, c.unit);
        // A person reads the list first; a script gets one table.
        if (c.format == TableFormat::Text)
            write_tables(out, {mode_list_table(shapes, sys.dof_names, w, c.unit), detail}, c.format);
        else
            write_table(out, detail, c.format);
        plot_if(o->common.plot, mode_shape_figure(shapes, w, c.unit, c.scene.title));
    }});

    auto* camp = app.add_subcommand("campbell", "modes tracked over speed (Campbell diagram)");
    add_common(camp, o->common, true);
    add_motion_option(camp, o->common);
    add_solver_options(camp, o->common);
    camp->add_option("--modes", o->modes, "number of modes to track: the K lowest by frequency (0 = all; sparse: "
                                          "the K nearest --target, default 6); default: the scene's, else the "
                                          "modes in range");
    camp->add_option("--plot", o->common.plot, "draw the diagram into FILE.svg or FILE.png");
    camp->add_option("--harmonics", o->harmonics, "harmonic lines drawn, e.g. 1,2 (default: the scene's, else 1)");
    camp->add_flag("--rows", o->rows, "table format: every row of the diagram instead of the summary");
    cmds.push_back({camp, [o](std::ostream& out) {
        const Context c = open_scene(o->common, true);
        const auto h = parse_harmonics(o->harmonics, c.scene.harmonics);
        const int modes = wanted_modes(c, o->modes);
        const SolverChoice plan = plan_solver(c, modes);
        note_extrapolation(c);
        const CampbellOptions co = campbell_options(c, plan, modes, h);
        const SolverFactory solver = tracking_solver(plan.make, co, c.speeds);
        const CampbellDiagram cd = campbell(solver, c.speeds, co);
        // The first screen (table format): a summary and the critical speeds; the rows on request.
        const bool summary = c.format == TableFormat::Text && !o->rows;
        std::vector<CriticalSpeed> cs;
        if (summary || !o->common.plot.empty()) {
            cs = critical_speeds(solver, cd, h, c.jobs);
            set_amplification_factors(cs, c.scene.system);
        }
        if (summary) {
            // A sparse window's verdict covers its modes only (a dense diagram keeps every mode).
            const bool window = plan.kind == SolverKind::Sparse;
            write_table(out, campbell_summary(cd, cs, c.unit, o->common.plot, window), c.format);
            out << "\n";
            write_tables(out, critical_tables(cs, c.unit), c.format);
        } else {
            write_table(out, campbell_table(cd, c.unit), c.format);
        }
        if (!o->common.plot.empty()) plot_if(o->common.plot, campbell_figure(cd, cs, h, c.unit, c.scene.title));
        note_diagram(cd, c, summary);
    }});

    auto* crit = app.add_subcommand("critical", "critical speeds: crossings with the k x speed lines");
    add_common(crit, o->common, true);
    add_motion_option(crit, o->common);
    add_solver_options(crit, o->common);
    crit->add_option("--harmonics", o->harmonics, "harmonics k, e.g. 1,2 (default: the scene's, else 1)");
    crit->add_option("--modes", o->modes, "number of modes considered (0 = all); default: the scene's, else the modes in range");
    crit->add_option("--critical-method", o->critical_method,
                     "branches (root finding on tracked modes) or direct (linear eigenproblem; undamped only)")
        ->capture_default_str();
    cmds.push_back({crit, [o](std::ostream& out) {
        if (o->critical_method != "branches" && o->critical_method != "direct")
            throw InputError("--critical-method '" + o->critical_method + "': allowed: branches, direct");
        const Context c = open_scene(o->common, true);
        const auto h = parse_harmonics(o->harmonics, c.scene.harmonics);
        std::vector<CriticalSpeed> cs;
        if (o->critical_method == "direct") {
            require_dense(c, "critical --critical-method direct");
            for (int k : h) {
                auto d = critical_speeds_direct(c.scene.system, k, c.speeds.front(), c.speeds.back());
                cs.insert(cs.end(), d.begin(), d.end());
            }
            std::sort(cs.begin(), cs.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
        } else {
            const int modes = wanted_modes(c, o->modes);
            const SolverChoice plan = plan_solver(c, modes);
            note_extrapolation(c);
            const CampbellOptions co = campbell_options(c, plan, modes, h);
            const SolverFactory solver = tracking_solver(plan.make, co, c.speeds);
            const CampbellDiagram cd = campbell(solver, c.speeds, co);
            cs = critical_speeds(solver, cd, h, c.jobs);
            note_diagram(cd, c);
        }
        set_amplification_factors(cs, c.scene.system);
        // A person reads the critical speeds and the heavily damped crossings apart; a script gets one table.
        if (c.format == TableFormat::Text)
            write_tables(out, critical_tables(cs, c.unit), c.format);
        else
            write_table(out, critical_table(cs, c.unit), c.format);
    }});

    auto* stab = app.add_subcommand("stability", "speeds where a mode becomes unstable or stable again");
    add_common(stab, o->common, true);
    add_motion_option(stab, o->common);
    add_solver_options(stab, o->common);
    stab->add_option("--modes", o->modes, "number of modes considered (0 = all; sparse: default 6); default: the scene's, else the "
                                          "modes in range");
    cmds.push_back({stab, [o](std::ostream& out) {
        const Context c = open_scene(o->common, true);
        const int modes = wanted_modes(c, o->modes);
        const SolverChoice plan = plan_solver(c, modes);
        note_extrapolation(c);
        const CampbellOptions co = campbell_options(c, plan, modes, c.scene.harmonics);
        const SolverFactory solver = tracking_solver(plan.make, co, c.speeds);
        const CampbellDiagram cd = campbell(solver, c.speeds, co);
        const auto changes = stability_changes(solver, cd, c.jobs);
        write_table(out, stability_table(changes, c.unit), c.format);
        for (const auto& n : cd.notes) std::cerr << "note: " << n << "\n";
        if (std::isfinite(cd.band)) std::cerr << "note: " << out_of_range_note(cd, c.unit) << "\n";
        if (changes.empty())
            std::cerr << "note: no mode changes stability in the range; "
                      << (unstable_ranges(cd).empty() ? "none is unstable (neutral modes: Re lambda within its error bound)"
                                                      : "some are unstable throughout") << "\n";
    }});

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
    cmds.push_back({perv, [o](std::ostream& out) {
        if (!(o->tolerance > 0.0 && o->tolerance < 1.0))
            throw InputError(fmt::format("--tolerance {}: allowed: 0 < tolerance < 1", o->tolerance));
        const Context c = open_scene(o->common, true);
        PervasiveOptions po;
        po.tolerance = o->tolerance;
        po.modes = wanted_modes(c, o->modes);
        po.solver = c.solver;
        po.threads = c.jobs;
        if (use_sparse(c) && po.modes == 0)
            std::cerr << "note: the sparse solver checks the " << kDefaultSparseModes
                      << " modes nearest the target; set --modes K for another number\n";
        write_table(out, pervasive_table(pervasive_damping(c.scene.system, c.speeds, po), c.unit), c.format);
    }});

    auto* resp = app.add_subcommand("response", "unbalance response: amplitude and phase per DOF");
    add_common(resp, o->common, true);
    add_motion_option(resp, o->common);
    add_solver_options(resp, o->common);
    resp->add_option("--plot", o->common.plot, "draw amplitude (one panel per unit) and phase into FILE.svg or FILE.png");
    resp->add_flag("--polar", o->polar, "with --plot: a polar plot (Im Z against Re Z) instead of amplitude and phase");
    resp->add_option("--dofs", o->dofs, "DOFs reported, by name, e.g. x3,y3 (default: all)");
    resp->add_option("--nodes", o->nodes, "DOFs reported: the lateral translations x, y of these nodes, e.g. 12,20");
    resp->add_option("--at", o->at, "DOFs reported: the lateral translations x, y of the nodes nearest these axial positions (m)");
    resp->add_flag("--extrema", o->extrema, "print the peaks and antiresonances instead of the curve");
    resp->add_flag("--rows", o->rows, "table format: every row of the curve instead of the summary");
    resp->add_option("--modes", o->modes, "modes checked for stability over the range (0 = all); default: the scene's, "
                                           "else the modes in range")
        ->check(CLI::Range(0, 100000000));
    cmds.push_back({resp, [o](std::ostream& out) {
        if (o->polar && o->common.plot.empty()) throw InputError("--polar: only together with --plot FILE");
        const Context c = open_scene(o->common, true);
        const Scene& sc = c.scene;
        const std::vector<int> outputs = response_outputs(*o, sc.system);
        // The sparse LU of the dynamic stiffness where the solver choice is sparse.
        const SolverKind kind = use_sparse(c) ? SolverKind::Sparse : SolverKind::Dense;
        const std::vector<std::string>& names = sc.system.dof_names;
        const std::vector<std::string>& units = sc.system.dof_units;
        const ResponseSolver solve = [&](double w) { return unbalance_response(sc.system, w, kind); };
        note_extrapolation(c);
        const ResponseCurve rc = unbalance_response(solve, sc.dofs(), c.speeds, outputs);
        warn_unstable_response(c, wanted_modes(c, o->modes));
        const bool summary = c.format == TableFormat::Text && !o->rows && !o->extrema;
        // Peaks refined between grid speeds: the summary, --extrema, and the choice of curves to draw.
        std::vector<ResponseExtremum> extrema;
        if (summary || o->extrema || (!o->common.plot.empty() && outputs.empty()))
            extrema = response_extrema(solve, rc, !o->extrema);
        if (o->extrema)
            write_table(out, extrema_table(names, units, extrema, c.unit), c.format);
        else if (summary)
            write_table(out, response_summary(names, units, response_maxima(rc, extrema), c.unit, 8), c.format);
        else
            write_table(out, response_table(names, units, rc, c.unit), c.format);
        if (o->common.plot.empty()) return;
        // Many DOFs: the six largest of each unit, so the legend stays readable.
        const std::vector<int> shown =
            !outputs.empty() || rc.dofs.size() <= 6 ? std::vector<int>{}
                                                    : largest_responses(units, response_maxima(rc, extrema), 6);
        plot_if(o->common.plot, o->polar ? response_polar_figure(names, units, rc, c.unit, sc.title, shown)
                                         : response_figure(names, units, rc, c.unit, sc.title, shown));
    }});

    auto* exp = app.add_subcommand("export", "M, D, G, K, N and the state matrices as Matrix Market");
    add_common(exp, o->common, false);
    add_motion_option(exp, o->common);
    exp->add_option("--speed", o->speed, "spin speed for the assembled matrices (in --units)")->required();
    exp->add_option("--dir", o->dir, "output directory (created if missing)")->required();
    cmds.push_back({exp, [o](std::ostream&) {
        const Context c = open_scene(o->common, false);
        const double w = parse_speed(o->speed, "--speed", c.unit);
        note_extrapolation(c, w);
        const ExportReport r = export_matrices(c.scene.system, w, o->dir);
        for (const auto& n : r.notes) std::cerr << "note: " << n << "\n";
        std::cerr << "wrote the matrices at " << c.unit.factor * w << " " << c.unit.name << " into " << o->dir
                  << "\n";
    }});
    return cmds;
}

}  // namespace gyrokit::cli
