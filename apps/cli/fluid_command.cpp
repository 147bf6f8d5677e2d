// fluid: critical speeds of a liquid-filled rotor (liquid moving, undamped and
// damped; liquid frozen as a solid), the sloshing coefficients, and with --fill a
// sweep of the free-surface radius R0 (the paper's Bild 2).
#include <gyrokit/analysis/fluid_critical_speeds.hpp>
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

std::vector<double> parse_fill(const std::string& text, double R) {
    const SpeedRange r = SpeedRange::parse(text, "--fill", 1.0);
    if (!(r.from > 0.0) || !(r.to < R))
        throw InputError(fmt::format("--fill '{}': R0 from {} to {}; allowed: 0 < R0 < R = {} (m)", text, r.from,
                                     r.to, R));
    return r.points();
}

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
        if (!c.scene.fluid)
            throw InputError(fmt::format("{}: [model] type = '{}'; the fluid command needs type = \"fluid_rotor\"",
                                         c.scene.path, c.scene.model_type));
        const FluidRotorParameters p0 = *c.scene.fluid;
        if (!o->fill.empty()) {
            const FillSweep sweep = fill_sweep(p0, parse_fill(o->fill, p0.R));
            write_result(out, {fill_sweep_table(sweep, c.unit)}, c.format, o->table);
            if (sweep.skipped)
                std::cerr << "note: " << sweep.skipped << " fill levels lie exactly at a sloshing resonance\n";
            if (!o->common.plot.empty()) plot_if(o->common.plot, fill_sweep_figure(sweep, c.unit, c.scene.title));
            return;
        }
        const FluidRotor f = build_fluid_rotor(p0);
        const FluidCriticalSpeeds cs = fluid_critical_speeds(f);
        write_result(out, {fluid_critical_table(cs, c.unit), sloshing_modes_table(f, cs, c.unit), liquid_table(f, cs)},
                     c.format, o->table);
    }});
    return cmds;
}

}  // namespace gyrokit::cli
