// api-unbalance: the API 617 unbalance response cases of an FE rotor.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/api_unbalance_reports.hpp>
#include <gyrokit/study/api_unbalance_study.hpp>

#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string mcs, min_speed, trip_speed, table;
    int speeds = defaults::api_speeds;
};

std::optional<double> number_if(const std::string& text, const std::string& option) {
    if (text.empty()) return std::nullopt;
    return parse_number(text, option);
}

}  // namespace

std::vector<Command> add_api_unbalance_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("api-unbalance",
                                   "FE rotors: the API 617 unbalance cases (an unbalance of 2 x 6350 W/N g mm placed "
                                   "by each critical speed's mode shape, the response from 0 to the trip speed at the "
                                   "probes and close clearances, AF, separation margins, Scc, a verdict per case)");
    cmd->add_option("scene", o->common.scene, "scene file (TOML) with an fe_rotor [model] and a [api] table")
        ->required();
    cmd->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    cmd->add_option("--units", o->common.units, "unit of the speeds in and out: rad/s, Hz or rpm; default: the "
                                                "scene's [speeds] units, else rad/s");
    cmd->add_option("--mcs", o->mcs, "the maximum continuous speed (in --units); default: [api] mcs");
    cmd->add_option("--min-speed", o->min_speed, "the minimum operating speed (in --units); default: [api] "
                                                 "min_speed, else the mcs");
    cmd->add_option("--trip-speed", o->trip_speed, "the trip speed (in --units), the end of the responses; default: "
                                                   "[api] trip_speed, else 1.05 x the mcs");
    cmd->add_option("--speeds", o->speeds, "grid speeds from 0 to the highest speed sought (peaks are refined "
                                           "between them)")
        ->capture_default_str()
        ->check(CLI::Range(11, 100000));
    cmd->add_option("--table", o->table, "one table: api_unbalance_summary, api_unbalance_cases, api_unbalance_loads, "
                                         "api_unbalance_margins or api_unbalance_amplitudes");
    add_output_option(cmd, "--plot", o->common.plot, "draw each case's orbits against speed into FILE.svg|.png");
    return {{cmd, [o](std::ostream& out) {
                 const TableFormat format = parse_format(o->common);
                 if (!o->common.units.empty()) SpeedUnit::parse(o->common.units);   // before any work
                 check_plot_path(o->common.plot);
                 ApiUnbalanceRequest r;
                 if (!o->common.units.empty()) r.unit = o->common.units;
                 r.mcs = number_if(o->mcs, "--mcs");
                 r.min_speed = number_if(o->min_speed, "--min-speed");
                 r.trip_speed = number_if(o->trip_speed, "--trip-speed");
                 r.speeds = o->speeds;
                 const Scene sc = load_scene(o->common.scene);
                 const ApiUnbalanceStudy s = api_unbalance_study(sc, r);
                 print_diagnostics(s.diagnostics);
                 write_result(out, api_unbalance_tables(s), format, o->table);
                 plot_if(o->common.plot, api_unbalance_figure(s, sc.title));
             }}};
}

}  // namespace gyrokit::cli
