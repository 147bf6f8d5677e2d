// eig, model, modes, export: the model and its modes at one speed.
#include <gyrokit/analysis/mode_shapes.hpp>
#include <gyrokit/io/export.hpp>
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
    std::string speed, dir, select, per = "node";
    int modes = kNotGiven;
    bool rigid_body = false;
};

// The shared options with this command's --modes.
RotorRequest request(const Options& o) {
    RotorRequest r = request_of(o.common);
    r.modes = given_modes(o.modes);
    return r;
}

// eig: every eigenvalue at one speed.
Command eig_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* eig = app.add_subcommand("eig", "the eigenvalues at one speed (all, or the K lowest with --modes K)");
    add_common(eig, o->common, false);
    add_motion_option(eig, o->common);
    add_solver_options(eig, o->common);
    eig->add_option("--speed", o->speed, "spin speed (in --units)")->required();
    eig->add_option("--modes", o->modes, "the K lowest modes (sparse: the K nearest --target); default: the scene's, else all "
                                          "(sparse: 6)");
    eig->add_flag("--rigid-body", o->rigid_body, "list the rigid-body eigenvalues (lambda = 0) after the modes");
    return {eig, [o](std::ostream& out) {
        const Context c = open_scene(o->common, request(*o), false);
        const double w = parse_speed(o->speed, "--speed", c.unit);
        const SolverOptions& so = c.study.solver;
        const SpectrumStudy st = spectrum_study(c.scene.system, w, so, c.unit);
        // With --rigid-body the table lists them: no note.
        if (o->rigid_body)
            print_diagnostics(st.diagnostics, {Diagnostic::Topic::RigidBody});
        else
            print_diagnostics(st.diagnostics);
        const QuadraticSpectrum& s = st.spectrum;
        write_table(out, eig_table(s, w, c.unit, o->rigid_body), c.format);
    }};
}

// model: what the scene's model is, and an FE rotor drawn.
Command model_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* model = app.add_subcommand("model", "what the scene's model is: DOFs, mass, nodes, damping, bearings; "
                                              "--plot draws an FE rotor");
    model->add_option("scene", o->common.scene, "scene file (TOML)")->required();
    model->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    add_output_option(model, "--plot", o->common.plot, "FE rotors: draw the shaft, disks and bearings into FILE.svg|.png");
    add_motion_option(model, o->common);
    return {model, [o](std::ostream& out) {
        const TableFormat format = parse_format(o->common);
        check_plot_path(o->common.plot);
        const Scene sc = load_motion_scene(o->common);
        if (!o->common.plot.empty() && !sc.fe_rotor())
            throw InputError("--plot: draws finite-element rotors; this model is " + sc.model_type());
        write_table(out, model_summary(sc), format);
        if (sc.fe_rotor()) plot_if(o->common.plot, fe_rotor_figure(sc));
    }};
}

// modes: mode shapes at one speed, as orbits per node or entries per DOF.
Command modes_command(CLI::App& app, const std::shared_ptr<Options>& o) {
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
    add_output_option(modes, "--plot", o->common.plot, "draw the shapes along the axis (or the orbits) into FILE.svg|.png");
    return {modes, [o](std::ostream& out) {
        const Context c = open_scene(o->common, request(*o), false);
        if (o->per != "node" && o->per != "dof")
            throw InputError("--per '" + o->per + "': allowed: node, dof");
        const double w = o->speed.empty() ? 0.0 : parse_speed(o->speed, "--speed", c.unit);
        const ModeShapeStudy st = mode_shape_study(c.scene.system, w, c.study.solver, c.unit,
                                                   o->select.empty() ? std::vector<int>{}
                                                                     : parse_harmonics(o->select, {}, "--mode"));
        print_diagnostics(st.diagnostics);
        const std::vector<ModeShape>& shapes = st.shapes;
        const auto& sys = c.scene.system;
        const bool per_dof = o->per == "dof" || sys.whirl_pairs.empty();
        Table detail = per_dof ? mode_dof_table(shapes, sys.dofs.names, sys.dofs.units, w, c.unit)
                               : mode_orbit_table(shapes, w, c.unit, c.scene.length_unit());
        // A person reads the list first; a script gets one table.
        if (c.format == TableFormat::Text)
            write_tables(out, {mode_list_table(shapes, sys.dofs.names, w, c.unit), detail}, c.format);
        else
            write_table(out, detail, c.format);
        plot_if(o->common.plot,
                mode_shape_figure(shapes, w, c.unit, c.scene.title, c.scene.length_unit(), axis_marks(c.scene)));
    }};
}

// export: the matrices at one speed as Matrix Market files.
Command export_command(CLI::App& app, const std::shared_ptr<Options>& o) {
    auto* exp = app.add_subcommand("export", "M, D, G, K, N and the state matrices as Matrix Market");
    add_common(exp, o->common, false);
    add_motion_option(exp, o->common);
    exp->add_option("--speed", o->speed, "spin speed for the assembled matrices (in --units)")->required();
    add_output_option(exp, "--dir", o->dir, "output directory (created if missing)", true)->required();
    return {exp, [o](std::ostream&) {
        const Context c = open_scene(o->common, false);
        const double w = parse_speed(o->speed, "--speed", c.unit);
        note_extrapolation(c, w);
        const ExportReport r = export_matrices(c.scene.system, w, o->dir);
        for (const auto& n : r.notes) std::cerr << "note: " << spell_fields(n, flag_words) << "\n";
        std::cerr << "wrote the matrices at " << c.unit.factor * w << " " << c.unit.name << " into " << o->dir
                  << "\n";
    }};
}

}  // namespace

std::vector<Command> add_spectrum_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    return {eig_command(app, o), model_command(app, o), modes_command(app, o), export_command(app, o)};
}

}  // namespace gyrokit::cli
