// mesh: the mesh convergence of an FE rotor's critical speeds and frequencies.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/mesh_convergence_reports.hpp>
#include <gyrokit/study/mesh_convergence_study.hpp>

#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    double tolerance = defaults::mesh_tolerance;
    int levels = defaults::mesh_levels;
    std::string table;
};

}  // namespace

std::vector<Command> add_mesh_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("mesh", "FE rotors: mesh convergence (each section's elements doubled until every "
                                           "critical speed and frequency in range changes by less than the "
                                           "tolerance)");
    cmd->add_option("scene", o->common.scene, "scene file (TOML) with an fe_rotor [model] and [speeds]")->required();
    cmd->add_option("--format", o->common.format, "output format: table, csv or json")->capture_default_str();
    cmd->add_option("--units", o->common.units, "unit of the speeds in and out: rad/s, Hz or rpm; default: the "
                                                "scene's [speeds] units, else rad/s");
    cmd->add_option("--tolerance", o->tolerance, "the largest relative change on doubling (0.001: 0.1 %)")->capture_default_str();
    cmd->add_option("--levels", o->levels, "meshes at most: x1 to x2^(levels - 1)")->capture_default_str();
    cmd->add_option("--table", o->table, "one table: mesh_summary or mesh_quantities");
    return {{cmd, [o](std::ostream& out) {
                 const TableFormat format = parse_format(o->common);
                 if (!o->common.units.empty()) SpeedUnit::parse(o->common.units);   // before any work
                 MeshConvergenceRequest r;
                 if (!o->common.units.empty()) r.unit = o->common.units;
                 r.tolerance = o->tolerance;
                 r.levels = o->levels;
                 const Scene sc = load_scene(o->common.scene);
                 const MeshConvergenceStudy s = mesh_convergence_study(sc, r);
                 print_diagnostics(s.diagnostics);
                 write_result(out, mesh_tables(s), format, o->table);
             }}};
}

}  // namespace gyrokit::cli
