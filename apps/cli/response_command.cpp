// response: the unbalance response over speed.
#include <gyrokit/analysis/unbalance_response.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/number_text.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/reports.hpp>
#include <gyrokit/study/response_study.hpp>

#include <algorithm>
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string dofs, nodes, at, probes;
    int modes = kNotGiven;
    bool extrema = false, rows = false, polar = false, no_stability_check = false, log_amplitude = false;
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
    std::vector<int> out = dofs_by_name(o.dofs, sys.dofs.names, "--dofs");
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
    resp->add_flag("--log-amplitude", o->log_amplitude, "with --plot: the amplitude on a log axis (default linear)");
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
    resp->add_flag("--no-stability-check", o->no_stability_check,
                   "skip tracking the modes over the range (the warning where a mode is unstable and the response "
                   "is no steady state)");
    cmds.push_back({resp, [o](std::ostream& out) {
        if (o->polar && o->common.plot.empty()) throw InputError("--polar: only together with --plot FILE");
        RotorRequest r = request_of(o->common);
        r.modes = given_modes(o->modes);
        const Context c = open_scene(o->common, r, true);
        const Scene& sc = c.scene;
        if (!o->probes.empty() && !(o->dofs.empty() && o->nodes.empty() && o->at.empty()))
            throw InputError("--probes and --dofs, --nodes, --at: allowed: probes alone");
        ResponseRequest rq;
        rq.probes = parse_probes(o->probes, sc.system);
        rq.outputs = response_outputs(*o, sc.system, sc.length_unit());
        rq.length = sc.length_unit();
        rq.stability_check = !o->no_stability_check;
        const bool summary = c.format == TableFormat::Text && !o->rows && !o->extrema;
        // Peaks refined between grid speeds: the summary, --extrema, and the choice of curves to draw.
        rq.peaks = summary || o->extrema || (!o->common.plot.empty() && rq.outputs.empty());
        rq.antiresonances = o->extrema;
        const ResponseStudy st =
            response_study(sc.system, c.study, rq);
        print_diagnostics(st.diagnostics);
        if (o->extrema)
            write_table(out, extrema_table(st.names, st.units, st.extrema, c.unit), c.format);
        else if (summary)
            write_table(out, response_summary(st.names, st.units, st.maxima, c.unit, 8), c.format);
        else
            write_table(out, response_table(st.names, st.units, st.curve, c.unit), c.format);
        if (o->common.plot.empty()) return;
        plot_if(o->common.plot, o->polar ? response_polar_figure(st.names, st.units, st.curve, c.unit, sc.title, st.plotted)
                                         : response_figure(st.names, st.units, st.curve, c.unit, sc.title, st.plotted,
                                                           "speed", o->log_amplitude));
    }});

    return cmds;
}

}  // namespace gyrokit::cli
