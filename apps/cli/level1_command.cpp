// level1: the API 617 Level I stability screen of an FE rotor.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/level1_reports.hpp>
#include <gyrokit/study/level1_study.hpp>

#include <fmt/format.h>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string machine, mcs, operating_speed, qa, station, gas_density, q_ratio, table;
    int intervals = kLevel1Intervals;
};

std::optional<double> number_if(const std::string& text, const std::string& option) {
    if (text.empty()) return std::nullopt;
    return parse_number(text, option);
}

}  // namespace

std::vector<Command> add_level1_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("level1", "FE rotors: API 617 Level I stability (the first forward mode's log "
                                             "decrement against cross-coupling Q at the maximum continuous speed, "
                                             "Q0, QA, the verdict)");
    cmd->add_option("scene", o->common.scene, "scene file (TOML) with an fe_rotor [model] and a [api] table")
        ->required();
    cmd->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    cmd->add_option("--units", o->common.units, "unit of the speeds in and out: rad/s, Hz or rpm; default: the "
                                                "scene's [speeds] units, else rad/s");
    cmd->add_option("--machine", o->machine, "centrifugal (QA with Bc = 3 and the density ratio) or axial (Bt = 1.5); "
                                             "default: the scene's [api] machine, else centrifugal");
    cmd->add_option("--mcs", o->mcs, "the maximum continuous speed (in --units); default: [api] mcs");
    cmd->add_option("--operating-speed", o->operating_speed, "the normal operating speed of QA's formula (in --units); "
                                                             "default: [api] operating_speed, else the mcs");
    cmd->add_option("--qa", o->qa, "the anticipated cross-coupling QA (N/m) in place of the stages'");
    cmd->add_option("--station", o->station, "where Q acts: an axial position (the scene's length unit); default: "
                                             "mid-span between the bearings, or the overhung stages");
    cmd->add_option("--gas-density", o->gas_density, "average gas density (kg/m^3) for the critical speed ratio's "
                                                     "region; default: [api] gas_density");
    cmd->add_option("--q-ratio", o->q_ratio, "the curve's range in multiples of QA; default: [api] q_ratio, else 10");
    cmd->add_option("--intervals", o->intervals, "equal steps of the curve")->capture_default_str()->check(
        CLI::Range(2, 10000));
    cmd->add_option("--method", o->common.method, "dense eigensolver: auto, qz, qz-classic or state")->capture_default_str();
    cmd->add_option("--table", o->table, "one table: level1_summary, level1_stages or level1_curve");
    add_output_option(cmd, "--plot", o->common.plot, "draw the log decrement against Q into FILE.svg|.png");
    return {{cmd, [o](std::ostream& out) {
                 const TableFormat format = parse_format(o->common);
                 if (!o->common.units.empty()) SpeedUnit::parse(o->common.units);   // before any work
                 check_plot_path(o->common.plot);
                 Level1Request r;
                 if (!o->common.units.empty()) r.unit = o->common.units;
                 if (!o->machine.empty()) r.machine = o->machine;
                 r.mcs = number_if(o->mcs, "--mcs");
                 r.operating_speed = number_if(o->operating_speed, "--operating-speed");
                 r.qa = number_if(o->qa, "--qa");
                 r.station = number_if(o->station, "--station");
                 r.gas_density = number_if(o->gas_density, "--gas-density");
                 r.q_ratio = number_if(o->q_ratio, "--q-ratio");
                 r.intervals = o->intervals;
                 r.method = o->common.method;
                 const Scene sc = load_scene(o->common.scene);
                 const Level1Study s = level1_study(sc, r);
                 print_diagnostics(s.diagnostics);
                 write_result(out, level1_tables(s), format, o->table);
                 plot_if(o->common.plot, level1_figure(s, sc.title));
             }}};
}

}  // namespace gyrokit::cli
