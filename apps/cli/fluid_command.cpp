// fluid: critical speeds of a liquid-filled rotor (liquid moving, undamped and
// damped; liquid frozen as a solid), the sloshing coefficients, and with --fill a
// sweep of the free-surface radius R0 (the paper's Bild 2).
#include <gyrokit/study/fluid_study.hpp>
#include <gyrokit/reports/fluid_reports.hpp>
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>

#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct FluidOptions {
    Common common;
    std::string fill, table;
};

}  // namespace

std::vector<Command> add_fluid_commands(CLI::App& app) {
    auto o = std::make_shared<FluidOptions>();
    std::vector<Command> cmds;
    auto* fl = app.add_subcommand("fluid", "liquid-filled rotor: critical speeds with moving and rigid liquid, "
                                           "sloshing coefficients, sweep over the fill level");
    add_common(fl, o->common, false);
    fl->add_option("--fill", o->fill, "sweep the free-surface radius R0 over FROM:TO:N (m)");
    fl->add_option("--table", o->table,
                   "only this table: critical_speeds, sloshing_modes or liquid (default: all; CSV holds the first)");
    add_output_option(fl, "--plot", o->common.plot, "with --fill: critical speeds against R0 into FILE.svg or FILE.png");
    cmds.push_back({fl, [o](std::ostream& out) {
        if (!o->common.plot.empty() && o->fill.empty()) throw InputError("--plot: only together with --fill");
        const Context c = open_scene(o->common, false);
        FluidRequest rq;
        rq.unit = c.request.unit;
        if (!o->fill.empty()) rq.fill = SpeedRange::parse(o->fill, "--fill").points();
        const FluidStudy st = fluid_study(c.scene, rq);
        print_diagnostics(st.diagnostics);
        if (st.sweep) {
            write_result(out, {fill_sweep_table(*st.sweep, st.unit)}, c.format, o->table);
            if (!o->common.plot.empty()) plot_if(o->common.plot, fill_sweep_figure(*st.sweep, st.unit, c.scene.title));
            return;
        }
        write_result(out,
                     {fluid_critical_table(*st.critical, st.unit), sloshing_modes_table(st.rotor, *st.critical, st.unit),
                      liquid_table(st.rotor, *st.critical)},
                     c.format, o->table);
    }});
    return cmds;
}

}  // namespace gyrokit::cli
