// The eigensolvers behind one interface: the dense scaled QZ (all modes) or
// ARPACK shift-invert (a few modes near a target), so that Campbell tracking,
// critical speeds and stability run on either. Solvers may keep state between
// calls (the sparse one starts ARPACK from the last speed's eigenvectors), so
// every worker makes its own from a factory. Which one a model gets:
// solver_choice.hpp; how speeds run in parallel: workers.hpp.
#pragma once

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>
#include <gyrokit/solve/workers.hpp>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct ContinuationOptions;   // analysis/continuation.hpp
struct ContinuationReport;

// What the solvers of one factory did, counted as they work: the cost of a
// study in units a reader can check (a full solve of every mode costs about
// one dense QZ; a step a few factorizations per mode; a check the eigenvalues
// alone). Counted in this process: solves in worker processes are not.
struct SolverWork {
    long full_solves = 0;        // every mode at one speed (dense QZ with vectors)
    long eigenvalue_checks = 0;  // the eigenvalues alone at one speed (continuation checks)
    long window_solves = 0;      // a window of modes by ARPACK shift-invert
    long steps = 0;              // speeds reached along the branches (verified corrections)
    long split_steps = 0;        // of them, steps taken in parts (halves down to sixteenths; counted once each)
    long local_solves = 0;       // full solves where a step did not verify (counted in full_solves too)
    long followed = 0;           // single modes followed to a speed (root searches)
    long joined = 0;             // modes joined at a check from beyond the band (inverse iteration at its eigenvalue)
    long cluster_steps = 0;      // steps (or parts) whose close modes moved as a group (Ritz pairs of their span)
};

struct WorkCounter {
    std::atomic<long> full_solves{0}, eigenvalue_checks{0}, window_solves{0}, steps{0}, split_steps{0},
        local_solves{0}, followed{0}, joined{0}, cluster_steps{0};
    SolverWork snapshot() const;
};

// Makes the solvers of one model, each worker its own, and says what else its
// solvers can do. Every factory solves a speed (operator()); the capabilities below
// are named, asked for with can_* / has_* and refused (a logic error) where absent.
class SolverFactory {
public:
    using Make = std::function<SpectrumSolver()>;
    using Centred = std::function<SpectrumSolver(double nu)>;
    using Follow = std::function<std::optional<Mode>(const Mode& from, double w, std::complex<double> predicted,
                                                      double reach)>;
    using Continue = std::function<SolverFactory(const std::vector<double>& speeds, const ContinuationOptions& opt,
                                                 ContinuationReport* report)>;
    using Walk = std::function<SpectrumSolver(int threads)>;
    using Resize = std::function<SolverFactory(int modes)>;

    SolverFactory() = default;   // no solver yet (a study's member before it runs)
    // `make` gives a new solver of every speed; `dofs` the model's size (0: not known);
    // `work` the counter its solvers share (a new one where none is given).
    explicit SolverFactory(Make make, int dofs = 0, std::shared_ptr<WorkCounter> work = nullptr);

    // A new solver (state kept between its calls: each worker makes its own).
    SpectrumSolver operator()() const;
    int dofs() const { return dofs_; }
    // What the solvers of this factory (and its copies) did.
    SolverWork work() const { return work_->snapshot(); }
    const std::shared_ptr<WorkCounter>& counter() const { return work_; }

    // ARPACK keeps its iteration state in Fortran SAVE variables, so two ARPACK runs
    // must not share a process: such solvers run in parallel in worker processes.
    bool thread_safe() const { return thread_safe_; }
    SolverFactory& not_thread_safe() { thread_safe_ = false; return *this; }

    // Window solvers: a solver whose window is centred on the frequency nu (rad/s), so
    // that a root search refines a mode on its own shift and the sweep's window cannot
    // move the result.
    bool has_centred() const { return static_cast<bool>(centred_); }
    SpectrumSolver centred(double nu) const;
    SolverFactory& with_centred(Centred c) { centred_ = std::move(c); return *this; }

    // A mode followed from a nearby speed to w by inverse iteration on the full pencil
    // (follow_mode: predicted eigenvalue, reach), for a root search along one branch at
    // the cost of a few factorizations; nothing where the step does not verify.
    bool can_follow() const { return static_cast<bool>(follow_); }
    std::optional<Mode> follow(const Mode& from, double w, std::complex<double> predicted, double reach) const;
    SolverFactory& with_follow(Follow f) { follow_ = std::move(f); return *this; }

    // Dense solvers: the continuation (continuation_solver) over `speeds` with options
    // `opt` (their eig replaced by this solver's).
    bool can_continue() const { return static_cast<bool>(continued_); }
    SolverFactory continued(const std::vector<double>& speeds, const ContinuationOptions& opt,
                            ContinuationReport* report) const;
    SolverFactory& with_continuation(Continue c) { continued_ = std::move(c); return *this; }

    // Solvers that continue from speed to speed: a solver whose steps use `threads`
    // threads inside. solve_speeds walks a grid with one such solver, in order, instead
    // of sharing it among workers (a worker starting mid-grid would pay a full solve there).
    // Window solvers: how many modes a window holds (0: every mode), and the same
    // solver with a window of `modes` modes (sharing this one's work counter).
    int window() const { return window_; }
    bool can_resize() const { return static_cast<bool>(resize_); }
    SolverFactory resized(int modes) const;
    SolverFactory& with_window(int modes, Resize r) { window_ = modes; resize_ = std::move(r); return *this; }

    // The model's pencil at a speed (what a result's sharp bound is measured on).
    using Pencil = std::function<SparsePencil(double w)>;
    bool has_pencil() const { return static_cast<bool>(pencil_); }
    SparsePencil pencil(double w) const;
    SolverFactory& with_pencil(Pencil p) { pencil_ = std::move(p); return *this; }

    bool walks() const { return static_cast<bool>(walk_); }
    SpectrumSolver walk(int threads) const;
    SolverFactory& with_walk(Walk w) { walk_ = std::move(w); return *this; }
    SolverFactory& without_walk() { walk_ = nullptr; return *this; }

private:
    Make make_;
    int dofs_ = 0;
    std::shared_ptr<WorkCounter> work_ = std::make_shared<WorkCounter>();
    bool thread_safe_ = true;
    Centred centred_;
    Follow follow_;
    Continue continued_;
    Walk walk_;
    Pencil pencil_;
    int window_ = 0;
    Resize resize_;
};

// The dense solver refuses models above this many DOFs (its 2n x 2n QZ needs
// O(n^2) memory and O(n^3) time: minutes and gigabytes beyond it).
constexpr int kDenseLimit = 3000;

// All modes by dense scaled QZ (or the state matrix, per `eig`). The solvers
// share one copy of the validated system (a temporary argument is safe).
SolverFactory dense_solver(const GyroscopicSystem& sys, const EigenOptions& eig = {});

// `opt.modes` modes nearest the shift by ARPACK shift-invert on the pencils
// `pencil(w)`. With `reuse` and a fixed shift (shift_order 0), each call after
// the first continues the last speed's modes along their branches
// (continue_window) and solves the window afresh only where a step fails, its
// Arnoldi iteration started from the last window's eigenvectors; such a factory
// has `walk` (sweeps solve its speeds in order).
SolverFactory sparse_solver(std::function<SparsePencil(double)> pencil, std::vector<std::pair<int, int>> whirl_pairs,
                            const SparseEigenOptions& opt, bool reuse = true, int dofs = 0);
// The system's sparse pencils (one shared copy of the validated system).
SolverFactory sparse_solver(const GyroscopicSystem& sys, const SparseEigenOptions& opt, bool reuse = true);

// Each mode's slope d lambda / d w (Mode::slope) from its right and left vectors
// and the pencils pencil(w), pencil(w +- h) (central differences, h = 1e-4
// max(w, scale); forward ones where w - h < 0). Both solvers of a model set it;
// the modes on `threads` threads. The two modes of a double eigenvalue (an
// isotropic rotor at standstill) get the slopes of its first-order split where
// their vectors are the directions it splits in (as the whirl separation leaves
// them), else NaN; a mode among three or more equal ones gets NaN. `at_w`:
// pencil(w), where the caller has it at hand.
void set_slopes(std::vector<Mode>& modes, const std::function<SparsePencil(double)>& pencil, double w,
                double scale, int threads = 1, const SparsePencil* at_w = nullptr);

// The ARPACK result as a spectrum of the dense interface.
QuadraticSpectrum to_spectrum(SparseSpectrum s, const SparsePencil& p);

}  // namespace gyrokit
