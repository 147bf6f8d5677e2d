// frf: frequency response functions at a fixed spin speed (a unit harmonic force or moment at one DOF).
#include "cli/common.hpp"
#include <gyrokit/analysis/frequency_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/frf_reports.hpp>
#include <gyrokit/reports/response_reports.hpp>

#include <algorithm>
#include <fmt/format.h>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string speed = "0", input, dofs, frequencies, probes;
    bool polar = false;
};

int dof_index(const std::vector<std::string>& names, const std::string& name, const char* option) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
        throw InputError(fmt::format("{} '{}': not a DOF of the model; allowed: names such as {}", option, name,
                                     names.empty() ? std::string("-") : names.front()));
    return static_cast<int>(it - names.begin());
}

}  // namespace

std::vector<Command> add_frf_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("frf", "frequency response to a unit harmonic force (or moment) at one DOF, at a "
                                          "fixed spin speed: amplitude, phase, Bode and polar plots");
    add_common(cmd, o->common, false);
    add_motion_option(cmd, o->common);
    cmd->add_option("--speed", o->speed, "spin speed (in --units), default 0")->capture_default_str();
    cmd->add_option("--input", o->input, "the DOF the force acts on, by name, e.g. y12 (a moment: tx12)")->required();
    cmd->add_option("--dofs", o->dofs, "output DOFs by name, e.g. x12,y12 (default: the input DOF: the driving point)");
    cmd->add_option("--probes", o->probes, "outputs: displacement probes NODE@ANGLE, e.g. 12@45,12@-45 (x cos + y sin, "
                                           "degrees from +x towards +y)");
    cmd->add_option("--frequencies", o->frequencies, "excitation frequencies FROM:TO:N (in --units); default: the "
                                                     "scene's [speeds] range");
    add_output_option(cmd, "--plot", o->common.plot, "Bode plot (amplitude and phase) into FILE.svg|.png");
    cmd->add_flag("--polar", o->polar, "with --plot: a polar plot (Im H against Re H)");
    return {{cmd, [o](std::ostream& out) {
                 if (o->polar && o->common.plot.empty()) throw InputError("--polar: only together with --plot FILE");
                 const Context c = open_scene(o->common, false);
                 const GyroscopicSystem& sys = c.scene.system;
                 std::vector<double> frequencies = c.speeds;   // the scene's [speeds] range
                 if (!o->frequencies.empty())
                     frequencies = SpeedRange::parse(o->frequencies, "--frequencies", c.unit.factor).points();
                 else if (frequencies.empty())
                     throw InputError(o->common.scene + ": no frequencies; give --frequencies FROM:TO:N or a [speeds] "
                                                        "table in the scene");
                 const double spin = parse_speed(o->speed, "--speed", c.unit);
                 const int input = dof_index(sys.dof_names, o->input, "--input");
                 if (!o->dofs.empty() && !o->probes.empty())
                     throw InputError("--dofs and --probes: allowed: one of them");
                 const std::vector<Probe> probes = parse_probes(o->probes, sys);
                 std::vector<int> outputs = probes.empty() ? dofs_by_name(o->dofs, sys.dof_names, "--dofs")
                                                           : probe_dofs(probes);
                 if (outputs.empty()) outputs.push_back(input);
                 note_extrapolation(c, spin);
                 FrequencyResponse r = frequency_response(sys, spin, frequencies, input, outputs,
                                                          use_sparse(c) ? SolverKind::Sparse : SolverKind::Dense);
                 // Probes: their readings are the outputs, named as given.
                 ProbeOutputs named{sys.dof_names, sys.dof_units, {}};
                 if (!probes.empty()) {
                     named = probe_outputs(sys, probes);
                     r.H = probe_readings(probes, r.outputs, r.H);
                     r.outputs = named.outputs;
                 }
                 to_length_unit(r.outputs, r.H, named.units, c.scene.length_unit());   // mm in an mm scene
                 write_table(out, frf_table(named.names, named.units, r, c.unit), c.format);
                 if (!o->common.plot.empty())
                     plot_if(o->common.plot, frf_figure(named.names, named.units, r, c.unit, o->polar));
             }}};
}

}  // namespace gyrokit::cli
