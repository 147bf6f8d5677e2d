#include "cli/common.hpp"

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/error.hpp>

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <thread>
#include <unistd.h>

namespace gyrokit::cli {

void add_common(CLI::App* c, Common& o, bool with_speeds) {
    c->add_option("scene", o.scene, "scene file (TOML)")->required();
    c->add_option("--format", o.format, "output format: table, csv or json")->capture_default_str();
    c->add_option("--units", o.units, "unit of speeds and frequencies on the command line and in the output: "
                                      "rad/s, Hz or rpm; default: the scene's [speeds] units, else rad/s");
    c->add_option("--method", o.method, "dense eigensolver: auto (the state matrix where verified, else scaled QZ), qz, qz-classic or "
                                        "state (M^-1 state matrix)")
        ->capture_default_str();
    if (with_speeds) c->add_option("--speeds", o.speeds, "speed range FROM:TO:N (overrides the scene's [speeds])");
}

void add_motion_option(CLI::App* c, Common& o) {
    c->add_option("--motion", o.motion,
                  "fe_rotor scenes: the DOFs built, in place of the scene's motion / dofs_per_node: lateral (4 per "
                  "node), all (6), axial or torsional (1: that motion alone)");
}

void add_solver_options(CLI::App* c, Common& o) {
    c->add_option("--solver", o.solver, "eigensolver: dense (all modes, scaled QZ), sparse (ARPACK shift-invert, a "
                                        "few modes near --target) or auto (sparse above " +
                                            std::to_string(kAutoSparseDofs) + " DOFs, above " +
                                            std::to_string(kAutoDenseInRangeDofs) +
                                            " for the modes in range); default: the scene's, else auto");
    c->add_option("--target", o.target, "frequency (in --units) the sparse search centres on; default 0: the lowest modes");
    c->add_option("--target-order", o.target_order,
                  "sparse: move the search centre with the speed, to --target + ORDER * speed (1: follow the 1x "
                  "line); default: the scene's target_order, else 0");
    c->add_option("--lanczos", o.lanczos, "Lanczos (Arnoldi) vectors of the sparse solver; 0 = automatic")
        ->capture_default_str();
    c->add_option("--jobs", o.jobs, "threads for the speeds of a sweep; 0 = all cores")->capture_default_str();
}

void add_cut_option(CLI::App* c, Common& o) {
    c->add_option("--f-cut", o.f_cut,
                  fmt::format("frequency (in --units) up to which every mode is tracked and judged (critical speeds, "
                              "stability), whatever --modes shows; default: the scene's f_cut (rad/s in [analysis]), else {} times the "
                              "highest harmonic times the top speed",
                              kBandMargin));
}

TableFormat parse_format(const Common& o) { return parse_table_format(o.format); }

bool use_sparse(const Context& c) {
    return resolve_solver_kind(c.scene.dofs(), c.study.solver.kind) == SolverKind::Sparse;
}

StudyOptions with_progress(StudyOptions s, bool quiet) {
    if (!quiet) s.progress = progress_bar("speeds");
    return s;
}

std::optional<int> given_modes(int modes) {
    if (modes == kNotGiven) return std::nullopt;
    return modes;
}

void print_diagnostics(const Diagnostics& d, std::initializer_list<Diagnostic::Topic> skip) {
    for (const Diagnostic& x : d) {
        if (std::find(skip.begin(), skip.end(), x.topic) != skip.end()) continue;
        std::cerr << (x.level == Diagnostic::Level::Warning ? "warning: " : "note: ") << spell_fields(x.text, flag_words)
                  << "\n";
    }
}

void note_extrapolation(const Context& c, double speed) {
    for (const auto& n : extrapolation_notes(c.scene.system.bearings, speed, speed)) std::cerr << "note: " << n << "\n";
}

std::string flag_words(const std::string& field) {
    static const std::pair<const char*, const char*> flags[] = {
        {"directory", "--dir"},       {"jobs", "--jobs"},     {"lanczos_vectors", "--lanczos"},
        {"method", "--method"},       {"modes", "--modes"},   {"motion", "--motion"},
        {"solver", "--solver"},       {"speeds", "--speeds"}, {"target", "--target"},
        {"target_order", "--target-order"}, {"f_cut", "--f-cut"}, {"units", "--units"}, {"rows", "--rows, or --format csv|json"},
        {"plot", "--plot FILE.svg"},        {"dt", "--dt"},         {"duration", "--duration"},
        {"max_steps", "--max-steps"},       {"speed", "--speed"},   {"run_up", "--run-up"},
        {"acceleration", "--acceleration"}, {"gravity", "--gravity"}, {"tolerance", "--tolerance"},
        {"rigid_body", "--rigid-body"}, {"input", "--input"}, {"dofs", "--dofs"}, {"probes", "--probes"},
        {"frequencies", "--frequencies"}, {"mode", "--mode"}, {"fill", "--fill"},
        {"node", "--node"}, {"start", "--start"}, {"simulate", "--simulate"}, {"averaged", "--averaged"},
        {"integrator", "--integrator"}, {"abs_tol", "--abs-tol"}, {"rel_tol", "--rel-tol"}, {"runup", "--runup"},
        {"max_speed", "--max-speed"}, {"mcs", "--mcs"}, {"operating_speed", "--operating-speed"}, {"qa", "--qa"},
        {"station", "--station"}, {"gas_density", "--gas-density"}, {"machine", "--machine"},
        {"q_ratio", "--q-ratio"}, {"intervals", "--intervals"}, {"min_speed", "--min-speed"},
        {"trip_speed", "--trip-speed"}, {"levels", "--levels"}, {"mode_shapes", "--mode-shapes"}};
    for (const auto& [name, flag] : flags)
        if (field == name) return flag;
    return "";
}

void require_dense(const Context& c, const std::string& command) {
    if (c.scene.dofs() > kDenseLimit)
        throw InputError(fmt::format("{}: gyrokit {} needs the dense model, which exists up to {} DOFs; this model "
                                     "has {}",
                                     c.scene.path, command, kDenseLimit, c.scene.dofs()));
}

Scene load_motion_scene(const Common& o) { return load_scene(o.scene, {}, o.motion); }

std::vector<std::string> split_names(const std::string& list) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (!list.empty() && start <= list.size()) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        out.push_back(list.substr(start, end - start));
        start = end + 1;
    }
    return out;
}


RotorRequest request_of(const Common& o) {
    RotorRequest r;
    if (!o.units.empty()) r.unit = o.units;
    // FROM:TO:N in the request's unit, converted by the library with every other value.
    if (!o.speeds.empty()) r.speeds = SpeedRange::parse(o.speeds, "--speeds").points();
    if (!o.solver.empty()) r.solver = o.solver;
    r.method = o.method;
    if (!o.target.empty()) r.target = parse_number(o.target, "--target");
    if (!o.target_order.empty()) r.target_order = parse_number(o.target_order, "--target-order");
    if (!o.f_cut.empty()) r.f_cut = parse_number(o.f_cut, "--f-cut");
    r.lanczos = o.lanczos;
    r.jobs = o.jobs;
    return r;
}

Context open_scene(const Common& o, bool need_speeds) { return open_scene(o, request_of(o), need_speeds); }

Context open_scene(const Common& o, const RotorRequest& request, bool need_speeds) {
    Context c;
    c.format = parse_format(o);
    check_plot_path(o.plot);
    if (request.unit) SpeedUnit::parse(*request.unit);   // a wrong unit before the scene is read
    c.scene = load_motion_scene(o);
    c.request = request;
    std::vector<std::string> notes;
    c.study = resolve_request(c.scene, request, need_speeds ? SpeedsNeeded::Yes : SpeedsNeeded::No, &notes);
    // The command line's own process may run a sweep's solvers in worker processes
    // where they are not thread-safe (a library caller's process is not forked).
    c.study.workers.kind = WorkerKind::Auto;
    for (const auto& n : notes) std::cerr << "note: " << spell_fields(n, flag_words) << "\n";
    c.unit = c.study.unit;
    c.speeds = c.study.speeds;
    return c;
}

}  // namespace gyrokit::cli
