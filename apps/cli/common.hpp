// Shared pieces of the gyrokit subcommands: common options, scene context,
// parsing of speeds and harmonics, plotting.
#pragma once

#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/scene.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/study/defaults.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace gyrokit::cli {

// A subcommand: its CLI11 node and what runs when it was chosen.
struct Command {
    CLI::App* app;
    std::function<void(std::ostream&)> run;
};

// The command line's words for the library's option fields (Error::message,
// notes): modes -> "--modes", lanczos_vectors -> "--lanczos", ...
// --probes NODE@ANGLE,...: a displacement probe at each node (x cos + y sin, the angle in
// degrees from +x towards +y), named as written ("12@45").
std::vector<Probe> parse_probes(const std::string& text, const GyroscopicSystem& sys);

std::string flag_words(const std::string& field);

// Options every scene command shares.
struct Common {
    std::string scene, format = "table", units = defaults::unit, speeds, method = defaults::method, plot;
    // Solver choice (eig, campbell, critical, stability, response).
    std::string solver, target, target_order;
    std::string f_cut;    // campbell, critical, stability, response: the modes judged
    int lanczos = defaults::lanczos, jobs = defaults::jobs;
    std::string motion;   // FE rotors: the DOF set in place of the scene's
};

void add_common(CLI::App* c, Common& o, bool with_speeds);
// --motion: an FE rotor's DOF set (lateral, all, axial, torsional) in place of the scene's.
void add_motion_option(CLI::App* c, Common& o);
// The scene with --motion applied.
Scene load_motion_scene(const Common& o);
// --solver, --target, --target-order, --lanczos, --jobs.
void add_solver_options(CLI::App* c, Common& o);
// --f-cut: the frequency up to which the tracked modes are judged.
void add_cut_option(CLI::App* c, Common& o);

struct Context {
    Scene scene;
    TableFormat format;
    SpeedUnit unit;
    std::vector<double> speeds;
    // The scene's [analysis] solver options with --solver, --target,
    // --target-order, --lanczos and --method in their place.
    SolverOptions solver;
    std::optional<double> f_cut;   // rad/s: the scene's f_cut or --f-cut
    int jobs = 1;
};

// The library's solver choice (choose_solver) for `modes` modes (0: all, or the
// sparse default); its notes go to stderr.
SolverChoice plan_solver(const Context& c, int modes);
// The study of a command: the scene's options with the flags in their place,
// `modes` as wanted_modes gives it, a progress bar unless `quiet`.
StudyOptions study_of(const Context& c, int modes, const std::vector<int>& harmonics, bool quiet = false);
// --modes given (>= 0), else the scene's [analysis] modes.
int wanted_modes(const Context& c, int modes);
// Diagnostics on stderr ("note: ", "warning: "), option fields as flags; topics in
// `skip` are left out (the output already shows them).
void print_diagnostics(const Diagnostics& d, std::initializer_list<Diagnostic::Topic> skip = {});
// Notes on speed-dependent bearings used beyond their tables at one speed.
void note_extrapolation(const Context& c, double speed);
// Whether the choice is the sparse solver (without building one).
bool use_sparse(const Context& c);
// Throws InputError naming `command` when the model is above the dense limit.
void require_dense(const Context& c, const std::string& command);

// Validates the options (before any work) and loads the scene.
Context open_scene(const Common& o, bool need_speeds);
TableFormat parse_format(const Common& o);

double parse_speed(const std::string& text, const std::string& option, const SpeedUnit& u);
// A dimensionless multiple of the speed (>= 0), e.g. --target-order.
double parse_order(const std::string& text, const std::string& option);
// Whole numbers in [1, 1000] separated by commas (harmonics, mode numbers); empty: `fallback`.
std::vector<int> parse_harmonics(const std::string& text, const std::vector<int>& fallback,
                                 const std::string& option = "--harmonics");
// An option naming a file the command writes (a folder of files: `folder`): in the
// help's "Output files" group, which the run claims before any work (claim_outputs).
constexpr const char* kOutputGroup = "Output files";
CLI::Option* add_output_option(CLI::App* c, const std::string& name, std::string& value, const std::string& help,
                               bool folder = false);
// Every file option of the chosen command given a value, claimed in the current run:
// none may be an input of the run or another output of it (core/run_files.hpp).
void claim_outputs(const CLI::App& command);
// Throws InputError unless the extension is .svg or .png (empty: no plot).
void check_plot_path(const std::string& path, const std::string& option = "--plot");
// The figure into `path` (empty: nothing), named `option` in errors.
void plot_if(const std::string& path, const Figure& f, const std::string& option = "--plot");
// write_result, and a note on stderr naming the tables a CSV left out.
void write_result(std::ostream& out, const std::vector<Table>& ts, TableFormat f, const std::string& table);
// A progress bar on stderr when stderr is a terminal; otherwise nothing.
std::function<void(size_t, size_t)> progress_bar(const std::string& what);
// The same bar for a fraction of a time span (an ODE run), in percent.
std::function<void(double)> fraction_bar(const std::string& what);

// The commands of the rotor analyses at one speed: eig, model, modes, export.
std::vector<Command> add_spectrum_commands(CLI::App& app);
// Over speed: campbell, critical, stability, pervasive.
std::vector<Command> add_tracking_commands(CLI::App& app);
// The unbalance response: response.
std::vector<Command> add_response_commands(CLI::App& app);

// The auto-balancer command: balancer (synchronous states, --simulate).
std::vector<Command> add_balancer_commands(CLI::App& app);

// The liquid-filled rotor command: fluid.
std::vector<Command> add_fluid_commands(CLI::App& app);

// The design study: screen (sweep file, --jobs, --shard, --resume, --merge).
std::vector<Command> add_screen_commands(CLI::App& app);

// Frequency response functions at a fixed spin speed: frf.
std::vector<Command> add_frf_commands(CLI::App& app);

// Transient response by time integration: transient.
std::vector<Command> add_transient_commands(CLI::App& app);

// FE rotors: critical-map (undamped critical speeds against bearing stiffness).
std::vector<Command> add_critical_map_commands(CLI::App& app);

// FE rotors at standstill: static.
std::vector<Command> add_static_commands(CLI::App& app);

// The table of defaults: defaults.
std::vector<Command> add_defaults_commands(CLI::App& app);

// The Sommerfeld effect: sommerfeld (stationary speed curves, limit speeds, folds; --runup).
std::vector<Command> add_sommerfeld_commands(CLI::App& app);

}  // namespace gyrokit::cli
