// critical-map: undamped critical speeds of an FE rotor against bearing stiffness.
#include "cli/common.hpp"
#include <gyrokit/core/number_text.hpp>
#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/critical_map_reports.hpp>
#include <gyrokit/study/critical_map_study.hpp>

#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string stiffness, table;
    int modes = defaults::critical_map_modes;
};

// --stiffness FROM:TO:N, N values log spaced from FROM to TO (N/m).
std::vector<double> parse_stiffness(const std::string& text) {
    const std::string allowed = "allowed: FROM:TO:N with 0 < FROM < TO (N/m), N in [2, 10000] (log spaced)";
    const std::size_t c1 = text.find(':'), c2 = c1 == std::string::npos ? c1 : text.find(':', c1 + 1);
    std::optional<double> fa, fb;
    int n = 0;
    if (c2 != std::string::npos) {
        fa = decimal_number(text.substr(0, c1));
        fb = decimal_number(text.substr(c1 + 1, c2 - c1 - 1));
        const std::string count = text.substr(c2 + 1);
        if (!count.empty() && count.size() <= 5 && count.find_first_not_of("0123456789") == std::string::npos)
            n = std::stoi(count);
    }
    if (!fa || !fb || !(*fa > 0 && *fb > *fa) || n < 2 || n > 10000)
        throw InputError(fmt::format("--stiffness '{}': {} (normal numbers: at least 2.2250738585072014e-308)", text,
                                     allowed));
    const double a = *fa, b = *fb;
    std::vector<double> k;
    for (int i = 0; i < n; ++i) k.push_back(a * std::pow(b / a, static_cast<double>(i) / (n - 1)));
    k.back() = b;
    return k;
}

}  // namespace

std::vector<Command> add_critical_map_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("critical-map", "FE rotors: undamped critical speeds against bearing stiffness "
                                                   "(forward, backward, rigid-support limit, the bearings' curves)");
    cmd->add_option("scene", o->common.scene, "scene file (TOML)")->required();
    cmd->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    cmd->add_option("--units", o->common.units, "unit of the critical speeds: rad/s, Hz or rpm; default: the scene's "
                                                "[speeds] units, else rad/s");
    cmd->add_option("--stiffness", o->stiffness, fmt::format("bearing stiffness FROM:TO:N, log spaced (N/m); default: {} to {} "
                                                             "times the shaft's 48 E I / L^3, {} values",
                                                             defaults::critical_map_stiffness_from,
                                                             defaults::critical_map_stiffness_to,
                                                             defaults::critical_map_points));
    cmd->add_option("--modes", o->modes, "critical speeds of each whirl per stiffness (the lowest)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--table", o->table, "one table: critical_map or bearing_curves");
    add_output_option(cmd, "--plot", o->common.plot, "draw the map into FILE.svg|.png");
    return {{cmd, [o](std::ostream& out) {
                 const TableFormat format = parse_format(o->common);
                 if (!o->common.units.empty()) SpeedUnit::parse(o->common.units);   // before any work
                 check_plot_path(o->common.plot);
                 CriticalSpeedMapOptions opt;
                 if (!o->stiffness.empty()) opt.stiffness = parse_stiffness(o->stiffness);
                 opt.modes = o->modes;
                 const Scene sc = load_scene(o->common.scene);
                 const SpeedUnit unit = resolve_unit(sc, o->common.units.empty() ? std::nullopt
                                                                                 : std::optional<std::string>(o->common.units));
                 const CriticalSpeedMap map = critical_map_study(sc, opt);
                 write_result(out, {critical_map_table(map, unit), bearing_curve_table(map, unit)}, format, o->table);
                 plot_if(o->common.plot, critical_map_figure(map, unit, sc.title));
             }}};
}

}  // namespace gyrokit::cli
