// static: deflection, internal forces and reactions of an FE rotor at standstill.
#include "cli/common.hpp"
#include <gyrokit/core/number_text.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/static_reports.hpp>
#include <gyrokit/study/static_study.hpp>

#include <fmt/format.h>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string gravity = fmt::format("{}", defaults::gravity);
    std::vector<std::string> loads;
    std::string table;
};

// --load NODE:FX:FY[:MX:MY] (N, N m).
StaticLoad parse_load(const std::string& text) {
    std::vector<double> v;
    int node = -1;
    std::size_t start = 0;
    try {
        for (int k = 0; start <= text.size(); ++k) {
            const std::size_t end = std::min(text.find(':', start), text.size());
            const std::string item = text.substr(start, end - start);
            std::size_t pos = 0;
            if (k == 0) {
                node = std::stoi(item, &pos);
                if (pos != item.size()) throw std::invalid_argument(item);
            } else {
                const std::optional<double> x = decimal_number(item);
                if (!x) throw std::invalid_argument(item);
                v.push_back(*x);
            }
            start = end + 1;
        }
    } catch (const std::exception&) {
        v.clear();
    }
    if (node < 0 || (v.size() != 2 && v.size() != 4))
        throw InputError(fmt::format("--load '{}': allowed: NODE:FX:FY or NODE:FX:FY:MX:MY (node number, N, N m)", text));
    v.resize(4, 0.0);
    return {node, v[0], v[1], v[2], v[3]};
}

}  // namespace

std::vector<Command> add_static_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("static", "FE rotors at standstill: deflection, shear force, bending moment and "
                                             "reactions under gravity and point loads");
    cmd->add_option("scene", o->common.scene, "scene file (TOML)")->required();
    cmd->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    cmd->add_option("--gravity", o->gravity, "gravity along -y (m/s^2; 0: no weight)")->capture_default_str();
    cmd->add_option("--load", o->loads, "a point load NODE:FX:FY[:MX:MY] (N, N m); repeat for more");
    cmd->add_option("--table", o->table, "one table: static, deflection, internal_forces or reactions (a CSV holds one; "
                                         "default: the deflection)");
    add_output_option(cmd, "--plot", o->common.plot, "draw deflection, slope, shear force and bending moment along the shaft into FILE.svg|.png");
    add_motion_option(cmd, o->common);
    return {{cmd, [o](std::ostream& out) {
                 const TableFormat format = parse_format(o->common);
                 check_plot_path(o->common.plot);
                 StaticOptions opt;
                 opt.gravity = parse_decimal(o->gravity, "--gravity", fmt::format("a number from 0 to {:g} (m/s^2)", kMaxGravity));
                 for (const std::string& l : o->loads) opt.loads.push_back(parse_load(l));
                 const Scene sc = load_motion_scene(o->common);
                 const StaticResult s = static_study(sc, opt);
                 const LengthUnit length = sc.length_unit();
                 std::vector<Table> tables = static_tables(s, length);
                 // A person reads the summary and the reactions first; the element ends on request.
                 if (format == TableFormat::Text && o->table.empty()) tables = {tables[1], tables[2], tables[0]};
                 write_result(out, tables, format, o->table);
                 plot_if(o->common.plot, static_figure(s, sc.title, length));
             }}};
}

}  // namespace gyrokit::cli
