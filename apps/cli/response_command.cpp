// response: the unbalance response over speed.
#include <gyrokit/analysis/unbalance_response.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/number_text.hpp>
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
    std::string dofs, nodes, at, probes;
    int modes = -1;
    bool extrema = false, rows = false, polar = false;
};

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
std::vector<int> response_outputs(const Options& o, const GyroscopicSystem& sys, const LengthUnit& length);

std::vector<int> response_outputs(const Options& o, const GyroscopicSystem& sys, const LengthUnit& length) {
    std::vector<int> out = dofs_by_name(o.dofs, sys.dof_names, "--dofs");
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
            const std::optional<double> x = decimal_number(item);
            if (!x) throw std::invalid_argument(item);
            z = *x;
        } catch (const std::exception&) {
            throw InputError("--at '" + o.at + "': allowed: axial positions in " + length.name +
                             " (the scene's length_unit) separated by commas");
        }
        try {
            add_node(sys.nearest_node(length.to_metres(z), length));
        } catch (const InputError& e) {
            throw InputError("--at " + item + ": " + e.what());
        }
    }
    return out;
}

}  // namespace

std::vector<Command> add_response_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    std::vector<Command> cmds;

    auto* resp = app.add_subcommand("response", "unbalance response: amplitude and phase per DOF");
    add_common(resp, o->common, true);
    add_motion_option(resp, o->common);
    add_solver_options(resp, o->common);
    add_cut_option(resp, o->common);
    add_output_option(resp, "--plot", o->common.plot, "draw amplitude (one panel per unit) and phase into FILE.svg or FILE.png");
    resp->add_flag("--polar", o->polar, "with --plot: a polar plot (Im Z against Re Z) instead of amplitude and phase");
    resp->add_option("--dofs", o->dofs, "DOFs reported, by name, e.g. x3,y3 (default: all)");
    resp->add_option("--nodes", o->nodes, "DOFs reported: the lateral translations x, y of these nodes, e.g. 12,20");
    resp->add_option("--at", o->at, "DOFs reported: the lateral translations x, y of the nodes nearest these axial positions (in the scene's length_unit: m or mm)");
    resp->add_option("--probes", o->probes, "outputs: displacement probes NODE@ANGLE, e.g. 12@45,12@-45 (x cos + y "
                                            "sin, degrees from +x towards +y), instead of DOFs");
    resp->add_flag("--extrema", o->extrema, "print the peaks and antiresonances instead of the curve");
    resp->add_flag("--rows", o->rows, "table format: every row of the curve instead of the summary");
    resp->add_option("--modes", o->modes, "modes checked for stability over the range (0 = all); default: the scene's, "
                                           "else the modes in range")
        ->check(CLI::Range(0, 100000000));
    cmds.push_back({resp, [o](std::ostream& out) {
        if (o->polar && o->common.plot.empty()) throw InputError("--polar: only together with --plot FILE");
        const Context c = open_scene(o->common, true);
        const Scene& sc = c.scene;
        if (!o->probes.empty() && !(o->dofs.empty() && o->nodes.empty() && o->at.empty()))
            throw InputError("--probes and --dofs, --nodes, --at: allowed: probes alone");
        const std::vector<Probe> probes = parse_probes(o->probes, sc.system);
        const std::vector<int> outputs = response_outputs(*o, sc.system, sc.length_unit());
        // The sparse LU of the dynamic stiffness where the solver choice is sparse.
        const SolverKind kind = use_sparse(c) ? SolverKind::Sparse : SolverKind::Dense;
        // With probes the outputs are their readings, named as given (in m); else the model's DOFs.
        ProbeOutputs named{sc.system.dof_names, sc.system.dof_units, {}};
        if (!probes.empty()) {
            named.names.clear(), named.units.clear();
            for (const Probe& p : probes) named.names.push_back(p.name), named.units.push_back("m");
        }
        // Lengths as the scene states them (an mm scene prints mm).
        const LengthUnit length = sc.length_unit();
        Eigen::VectorXd shown_in = Eigen::VectorXd::Ones(sc.dofs());   // models without DOF units: as they are
        for (std::size_t k = 0; k < sc.system.dof_units.size(); ++k)
            shown_in(static_cast<Eigen::Index>(k)) = length.display_factor(sc.system.dof_units[k]);
        const std::vector<std::string>& names = named.names;
        const std::vector<std::string> units = length.display_units(named.units);
        const ResponseSolver solve = [&](double w) -> Eigen::VectorXcd {
            const Eigen::VectorXcd Z = unbalance_response(sc.system, w, kind);
            if (probes.empty()) return Z.cwiseProduct(shown_in.cast<std::complex<double>>());
            Eigen::VectorXcd reading(static_cast<Eigen::Index>(probes.size()));
            for (std::size_t k = 0; k < probes.size(); ++k)
                reading(static_cast<Eigen::Index>(k)) = length.display_factor("m") * probe_response(probes[k], Z);
            return reading;
        };
        for (const auto& n : extrapolation_notes(sc.system.bearings, c.speeds.front(), c.speeds.back()))
            std::cerr << "note: " << n << "\n";
        const ResponseCurve rc =
            unbalance_response(solve, probes.empty() ? sc.dofs() : static_cast<int>(probes.size()), c.speeds, outputs);
        print_diagnostics(
            response_stability_warnings(sc.system, study_of(c, wanted_modes(c, o->modes), c.scene.harmonics, true)));
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

    return cmds;
}

}  // namespace gyrokit::cli
