// Shared pieces of the gyrokit subcommands: common options, scene context,
// parsing of speeds and harmonics, plotting.
#pragma once

#include "cli/command_table.hpp"

#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/study/defaults.hpp>
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <CLI/CLI.hpp>
#include <functional>
#include <limits>
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
    std::string scene, format = "table", units, speeds, method = defaults::method, plot;
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
    // What the command line gave and the study it asks for (resolve_request: the
    // scene's [speeds] and [analysis] where an option is not given, then the defaults).
    RotorRequest request;
    StudyOptions study;
    SpeedUnit unit;               // study.unit: the scene's [speeds] units unless --units
    std::vector<double> speeds;   // study.speeds (rad/s)
};

// The request of the options every scene command shares (--units, --speeds, the
// solver options, --f-cut, --jobs), values as written (in --units where a unit applies).
RotorRequest request_of(const Common& o);
// The initial value of a count option that no one types: the option was not given.
constexpr int kNotGiven = std::numeric_limits<int>::min();
// --modes as given (a negative count is the library's to refuse); kNotGiven: unset.
std::optional<int> given_modes(int modes);
// The study with a progress bar unless `quiet`.
StudyOptions with_progress(StudyOptions s, bool quiet = false);
// Diagnostics on stderr ("note: ", "warning: "), option fields as flags; topics in
// `skip` are left out (the output already shows them).
void print_diagnostics(const Diagnostics& d, std::initializer_list<Diagnostic::Topic> skip = {});
// Notes on speed-dependent bearings used beyond their tables at one speed.
void note_extrapolation(const Context& c, double speed);
// Whether the choice is the sparse solver (without building one).
bool use_sparse(const Context& c);
// Throws InputError naming `command` when the model is above the dense limit.
void require_dense(const Context& c, const std::string& command);

// Validates the options (before any work), loads the scene and resolves `request`
// (request_of(o) with the command's own fields, e.g. --modes, --harmonics) on it.
Context open_scene(const Common& o, const RotorRequest& request, bool need_speeds);
Context open_scene(const Common& o, bool need_speeds);
TableFormat parse_format(const Common& o);

double parse_speed(const std::string& text, const std::string& option, const SpeedUnit& u);
// "x12,y12" as names (empty: none); a name that is no DOF is the library's to refuse.
std::vector<std::string> split_names(const std::string& list);
// A number spelled out completely (its range is the library's to check).
double parse_number(const std::string& text, const std::string& option);
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

// Each command group's subcommands (apps/cli/command_table.hpp lists them).
#define GYROKIT_DECLARE_COMMAND_GROUP(name) std::vector<Command> add_##name##_commands(CLI::App& app);
GYROKIT_COMMAND_GROUPS(GYROKIT_DECLARE_COMMAND_GROUP)
#undef GYROKIT_DECLARE_COMMAND_GROUP

}  // namespace gyrokit::cli
