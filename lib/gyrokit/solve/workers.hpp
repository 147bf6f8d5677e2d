// Parallel work over speeds (or any indexed tasks): threads or forked worker
// processes, each with its own solver from a factory, and the one rule that
// turns a requested job count into workers.
#pragma once

#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <functional>
#include <string>
#include <vector>

namespace gyrokit {

class SolverFactory;

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

// The parallelism rule of every front end: `jobs` 0 means every core; more than
// the cores is capped to them (more workers only add processes, memory and
// temporary files), with a note in `notes` that names the option field `jobs`;
// negative is an InputError.
int worker_count(int jobs, std::vector<std::string>* notes = nullptr);

using SpectrumSolver = std::function<QuadraticSpectrum(double w)>;

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

}  // namespace gyrokit
