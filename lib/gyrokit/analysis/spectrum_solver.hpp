// Which eigensolver computes a model's spectrum at a speed: the dense scaled
// QZ (all modes) or ARPACK shift-invert (a few modes near a target), behind one
// interface so that Campbell tracking, critical speeds and stability run on
// either. Solvers may keep state between calls (the sparse one starts ARPACK
// from the last speed's eigenvectors), so every thread makes its own from a
// factory.
#pragma once

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// How parallel work runs, apart from what is solved: `count` workers as
// threads or as forked worker processes (results through temporary files, a
// crashed worker reported as WorkerDied). Auto: processes for a solver that is
// not thread safe (ARPACK: its iterations would wait on each other), else
// threads. Threads is always correct (ARPACK iterations are serialized within a
// process) and is the choice inside a host that must not fork (an interpreter);
// Processes also for thread-safe solvers. Converts from a plain count.
enum class WorkerKind { Auto, Threads, Processes };
struct Workers {
    int count = 1;
    WorkerKind kind = WorkerKind::Auto;
    Workers(int n = 1, WorkerKind k = WorkerKind::Auto) : count(n), kind(k) {}
};

using SpectrumSolver = std::function<QuadraticSpectrum(double w)>;

struct SolverFactory {
    std::function<SpectrumSolver()> make;
    // ARPACK keeps its iteration state in Fortran SAVE variables, so two
    // ARPACK runs must not share a process: such solvers run in parallel in
    // worker processes instead of threads.
    bool thread_safe = true;
    // A window of modes (sparse solvers): a solver whose window is centred on the
    // frequency nu (rad/s), so that a root search refines a mode on its own shift and
    // the sweep's window cannot move the result. Empty for solvers of every mode.
    std::function<SpectrumSolver(double nu)> centred;
    // Window solvers: a mode followed from a nearby speed to w by inverse iteration
    // on the full pencil (follow_mode: predicted eigenvalue, reach), for a root
    // search along one branch at the cost of a few factorizations instead of a
    // window; nothing where the step does not verify (then the window is solved).
    std::function<std::optional<Mode>(const Mode& from, double w, std::complex<double> predicted, double reach)>
        follow;
    // Dense solvers: the continuation (continuation_solver) over `speeds` for the
    // modes within `band`. Empty for the others.
    std::function<SolverFactory(const std::vector<double>& speeds, double band, Workers workers)> continued;
    SpectrumSolver operator()() const { return make(); }
};

// All modes by dense scaled QZ (or the state matrix, per `eig`). The solvers
// share one copy of the validated system (a temporary argument is safe).
SolverFactory dense_solver(const GyroscopicSystem& sys, const EigenOptions& eig = {});

// `opt.modes` modes nearest the shift by ARPACK shift-invert on the pencils
// `pencil(w)`. With `reuse`, each call after the first starts the Arnoldi
// iteration from the previous speed's eigenvectors (fewer restarts when the
// speed step is small).
SolverFactory sparse_solver(std::function<SparsePencil(double)> pencil, std::vector<std::pair<int, int>> whirl_pairs,
                            const SparseEigenOptions& opt, bool reuse = true);
// The system's sparse pencils (one shared copy of the validated system).
SolverFactory sparse_solver(const GyroscopicSystem& sys, const SparseEigenOptions& opt, bool reuse = true);

// The solver choice every analysis makes the same way.
enum class SolverKind { Auto, Dense, Sparse };
SolverKind parse_solver_kind(const std::string& name);   // "auto" | "dense" | "sparse"
std::string to_string(SolverKind k);

// Auto: the sparse solver above this many DOFs, the dense one up to it.
constexpr int kAutoSparseDofs = 200;
// Auto for the modes in range (kModesInRange): the dense solver up to this many
// DOFs. Its continuation tracks every mode in range, where a sparse window holds
// a fixed number that need not reach the band; measured on data/compressor336.toml
// (stability, 151 speeds, 2 threads: dense 5.7 s, every mode in range; a sparse
// window 1.0 s) and on the same rotor in 168 elements (672 DOFs: 32 s and 2.4 s).
constexpr int kAutoDenseInRangeDofs = 400;
// The dense solver refuses models above this many DOFs (its 2n x 2n QZ needs
// O(n^2) memory and O(n^3) time: minutes and gigabytes beyond it).
constexpr int kDenseLimit = 3000;
// Modes the sparse solver computes when none are asked for.
constexpr int kDefaultSparseModes = 6;

// `modes` not given: the modes in the range the speeds excite (tracking_options);
// to a solver it means every mode (dense) or kDefaultSparseModes (sparse).
constexpr int kModesInRange = -1;

// The fields carry the names of the scene's [analysis] keys (and the CLI's options).
struct SolverOptions {
    SolverKind kind = SolverKind::Auto;   // solver
    EigenOptions eig;                     // dense: scaled QZ or state matrix
    int modes = 0;                        // modes wanted; 0: all (dense) or kDefaultSparseModes (sparse);
                                          // kModesInRange: as 0, the tracking keeps those in range
    std::optional<double> target;         // rad/s: the sparse search centre (default 0: the lowest modes)
    double target_order = 0.0;            // the centre moves as target + target_order * speed
    int lanczos_vectors = 0;              // sparse: Arnoldi vectors, 0 = automatic
    bool reuse = true;                    // sparse: start each speed from the last one's vectors
};

struct SolverChoice {
    SolverKind kind = SolverKind::Dense;  // Dense or Sparse, never Auto
    int modes = 0;                        // the number of modes (sparse: the window size; dense: as asked)
    SolverFactory make;
    std::vector<std::string> notes;       // e.g. the default number of sparse modes
};
// Auto resolved by size: kAutoSparseDofs, or kAutoDenseInRangeDofs where `modes`
// is kModesInRange.
SolverKind resolve_solver_kind(int dofs, SolverKind requested, int modes = 0);
// Validates the options (InputError naming the field) and the system, and makes the solver.
SolverChoice choose_solver(const GyroscopicSystem& sys, const SolverOptions& opt);


// The spectra at all speeds on `workers` (contiguous blocks of speeds, so that
// reuse works within a block). `progress(done, total)` is called from the
// workers, one call at a time.
std::vector<QuadraticSpectrum> solve_speeds(const SolverFactory& make, const std::vector<double>& speeds,
                                            Workers workers = {},
                                            const std::function<void(size_t, size_t)>& progress = {});

// The general form: task(solve, i) for i = 0 .. n-1, each worker with its own
// solver from `make` and a contiguous block of i; the results in the order of i.
// An error in any task is rethrown with its type and message.
using WorkerTask = std::function<QuadraticSpectrum(SpectrumSolver& solve, size_t i)>;
std::vector<QuadraticSpectrum> run_on_workers(const SolverFactory& make, size_t n, Workers workers,
                                              const WorkerTask& task,
                                              const std::function<void(size_t, size_t)>& progress = {});

// A worker process was killed by a signal (a crash) while solving task `task`.
struct WorkerDied : Error {
    WorkerDied(long long task_index, int signal_number);
    long long task;
    int signal;
};

// Each mode's slope d lambda / d w (Mode::slope) from its right and left vectors
// and the pencils pencil(w), pencil(w +- h) (central differences, h = 1e-4
// max(w, scale); forward ones where w - h < 0). Both solvers of a model set it.
void set_slopes(std::vector<Mode>& modes, const std::function<SparsePencil(double)>& pencil, double w,
                double scale);

// The ARPACK result as a spectrum of the dense interface.
QuadraticSpectrum to_spectrum(SparseSpectrum s, const SparsePencil& p);

}  // namespace gyrokit
