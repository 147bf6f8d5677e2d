// frf: frequency response functions at a fixed spin speed (a unit harmonic force or moment at one DOF).
#include "cli/common.hpp"
#include <gyrokit/study/frf_study.hpp>
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
    bool polar = false, log_amplitude = false;
};

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
    cmd->add_flag("--log-amplitude", o->log_amplitude, "with --plot: the amplitude on a log axis (default linear)");
    return {{cmd, [o](std::ostream& out) {
                 if (o->polar && o->common.plot.empty()) throw InputError("--polar: only together with --plot FILE");
                 const Context c = open_scene(o->common, false);
                 FrfRequest rq;
                 rq.input = o->input;
                 rq.speed = parse_number(o->speed, "--speed");
                 if (!o->frequencies.empty())
                     rq.frequencies = SpeedRange::parse(o->frequencies, "--frequencies").points();
                 rq.dofs = split_names(o->dofs);
                 rq.probes = parse_probes(o->probes, c.scene.system);
                 const FrfStudy st = frf_study(c.scene, c.request, rq);
                 print_diagnostics(st.diagnostics);
                 const FrequencyResponse& r = st.response;
                 const ProbeOutputs& named = st.named;
                 write_table(out, frf_table(named.names, named.units, r, c.unit), c.format);
                 if (!o->common.plot.empty())
                     plot_if(o->common.plot, frf_figure(named.names, named.units, r, c.unit, o->polar, o->log_amplitude));
             }}};
}

}  // namespace gyrokit::cli
