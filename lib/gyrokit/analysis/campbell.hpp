// Campbell diagram: the modes tracked across spin speed. Modes are matched
// between neighbouring speeds by eigenvalue continuity along their slopes
// d lambda / d w (the trapezoid rule on the slopes at both ends), with the
// eigenvector correlation (MAC) as a tie-breaker; where the match is ambiguous
// (a veering the step does not resolve) the speed step is bisected.
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <functional>
#include <limits>
#include <optional>
#include <vector>

namespace gyrokit {

// The solver (its method, sparse window) is the SolverFactory's; these are the tracking's.
struct CampbellOptions {
    int modes = 0;            // show the K lowest branches by frequency at the first speed (oscillating
                              // ones first, real eigenvalues after them); 0 = all. With a band the
                              // others up to it are judged too (CampbellDiagram::untracked)
    // rad/s, f_cut: the modes whose frequency stays above it over the whole range are
    // out of range (CampbellDiagram::out_of_range: named, not judged); infinity: every
    // mode. excitation_band gives the engineer's default.
    double band = std::numeric_limits<double>::infinity();
    // The band holds the K lowest modes (track, ContinuationOptions::lowest), not the excitation range.
    bool band_of_modes = false;
    bool band_asked = false;  // the band is an f_cut the caller gave, not excitation_band's default
    int window = 0;           // a window solver's size (modes beyond it are its edge); 0: `modes`
    bool widen_window = true; // a window solver's window widened to hold the band (track)
    int max_refine = 8;       // bisection levels allowed between two grid speeds
    double mac_min = 0.9;     // a match with a lower MAC is ambiguous
    Workers threads = 1;      // grid speeds solved in parallel: this many threads or worker processes
    // Called after each grid speed with (done, total); e.g. a progress bar.
    std::function<void(size_t, size_t)> progress;
};

struct BranchPoint {
    double speed;
    Mode mode;
};

// One tracked mode: its points in increasing speed.
struct Branch {
    int id = 0;   // 1-based, in order of frequency at the first speed
    std::vector<BranchPoint> points;
};

struct CampbellDiagram {
    std::vector<double> speeds;     // grid plus inserted refinement speeds
    std::vector<Branch> branches;
    int inserted_speeds = 0;        // speeds added by refinement
    int ambiguous_steps = 0;        // steps still ambiguous at the refinement limit
    double max_backward_error = 0;
    int rigid_body = 0;             // most rigid-body eigenvalues at one speed (not tracked)
    // The solver gave a window of modes (a sparse solver, a continuation), not all:
    // verdicts cover the tracked modes only.
    bool partial = false;
    std::vector<std::string> notes; // the solvers' notes, each once
    // With opt.modes = K: the branches beyond the K shown, ids K + 1 on. With a band
    // (f_cut; the modes in range), those up to it, with their vectors: critical
    // speeds, stability changes and verdicts cover them, whatever K is. Without one
    // (every mode at every speed), all the others by eigenvalue alone (a stability
    // verdict over every mode).
    std::vector<Branch> untracked;
    // With a band (CampbellOptions::band): the branches above it at every speed,
    // eigenvalues only, ids after the reported ones. Not judged by any verdict.
    double band = std::numeric_limits<double>::infinity();
    bool band_of_modes = false;   // the band was chosen to hold the K lowest modes (CampbellOptions)
    bool band_asked = false;      // f_cut as the caller gave it (CampbellOptions)
    // A window solver (partial) widened to hold the band: at the first, middle and last
    // speed its window reached beyond 1.5 times the band, so its verdicts cover every
    // mode up to the band as a dense diagram's do.
    bool window_holds_band = false;
    std::vector<Branch> out_of_range;
};

// How far above the highest excitation a mode still counts as in range: API 684
// asks for separation margins up to 26 % above the operating range; a further
// margin keeps the modes that approach it from above within reach.
constexpr double kBandMargin = 1.5;

// The frequency band the speeds and harmonics can excite (rad/s): kBandMargin
// times the highest harmonic times the highest speed; infinity for a top speed
// of 0 (no excitation to measure a range by: every mode).
double excitation_band(const std::vector<double>& speeds, const std::vector<int>& harmonics);

// The cut-off of the judged modes (rad/s): f_cut as asked (InputError naming f_cut
// unless it is finite and > 0), else excitation_band of the speeds and harmonics.
double judged_band(std::optional<double> f_cut, const std::vector<double>& speeds, const std::vector<int>& harmonics);

// The tracking options every front end uses: `modes` as asked (kModesInRange:
// every mode up to f_cut shown; 0: every mode, shown and judged; K: the K lowest at
// the first speed shown, every mode up to f_cut judged) on the solver `plan`;
// f_cut as judged_band gives it.
CampbellOptions tracking_options(const SolverChoice& plan, int modes, const std::vector<double>& speeds,
                                 const std::vector<int>& harmonics, Workers threads = {},
                                 std::optional<double> f_cut = std::nullopt);

// The solver a tracking over `speeds` with `co` stands on, and the critical
// speeds and stability thresholds after it: with a band (the modes in range) and
// a dense solver, the continuation (continuation_solver); else `make`.
SolverFactory tracking_solver(const SolverFactory& make, const CampbellOptions& co, const std::vector<double>& speeds);

// A tracking and the solver it stood on (for the critical speeds and stability
// thresholds after it).
struct Tracking {
    SolverFactory solver;
    CampbellDiagram diagram;
};

// The Campbell diagram every front end draws: on tracking_solver, that is for a
// dense solver with a band one continuation over the modes up to f_cut, widened
// (ContinuationOptions::lowest) to hold the K shown where K is given.
Tracking track(const SolverFactory& make, CampbellOptions co, const std::vector<double>& speeds);

// Dense: every mode of the system, by the scaled QZ (another method:
// campbell(dense_solver(sys, eig), speeds, opt)).
CampbellDiagram campbell(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                         const CampbellOptions& opt = {});

// Any solver (e.g. sparse_solver: a window of modes near a target). Modes that
// enter or leave a window start or end branches; only the lowest opt.modes
// decide whether a step is ambiguous.
CampbellDiagram campbell(const SolverFactory& solver, const std::vector<double>& speeds,
                         const CampbellOptions& opt = {});

// The least damped oscillating point among the branches the diagram shows
// (CampbellDiagram::branches; the summary names it): its branch id and point.
struct LeastDamped {
    int branch = 0;
    BranchPoint point;
};
std::optional<LeastDamped> least_damped(const CampbellDiagram& cd);

// Matching cost between two modes (0 = identical shape and eigenvalue).
double match_cost(const Mode& a, std::complex<double> predicted, const Mode& b);

// The mode of `spectrum` that continues `branch` at speed w, which lies between
// branch points i and i + 1: the best match to the nearer point, with the
// eigenvalue predicted by linear interpolation.
const Mode& continue_branch(const Branch& branch, size_t i, double w, const QuadraticSpectrum& spectrum);

// The distance from a branch point's eigenvalue to the nearest other one the
// diagram knows at that speed (another branch, out of range or not, or the
// conjugate): how far a mode followed from it may move (SolverFactory::follow).
double eigenvalue_gap(const CampbellDiagram& cd, const Branch& own, const BranchPoint& at);

}  // namespace gyrokit
