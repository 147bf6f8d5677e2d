// Campbell diagram: the modes tracked across spin speed. Modes are matched
// between neighbouring speeds by eigenvalue continuity along their slopes
// d lambda / d w (the trapezoid rule on the slopes at both ends), with the
// eigenvector correlation (MAC) as a tie-breaker; where the match is ambiguous
// (a veering the step does not resolve) the speed step is bisected.
#pragma once

#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <functional>
#include <limits>
#include <optional>
#include <vector>

namespace gyrokit {

// The solver (its method, sparse window) is the SolverFactory's; these are the tracking's.
struct CampbellOptions {
    int modes = 0;            // keep the K lowest branches by frequency at the first speed (oscillating
                              // ones first, real eigenvalues after them); 0 = all.
                              // Dense: only these (and the next two) decide whether a step is ambiguous
    // rad/s: with modes = 0, the modes whose frequency stays above it over the whole
    // range are out of range (CampbellDiagram::out_of_range: named, not judged);
    // infinity: every mode. excitation_band gives the engineer's default.
    double band = std::numeric_limits<double>::infinity();
    // The band holds the K lowest modes (track, ContinuationOptions::lowest), not the excitation range.
    bool band_of_modes = false;
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
    // Dense with opt.modes = K: the branches beyond the K reported, eigenvalues only
    // (no vectors), ids K + 1 on; a dense spectrum is complete, so they cost nothing
    // more and let a stability verdict cover every mode.
    std::vector<Branch> untracked;
    // With a band (CampbellOptions::band): the branches above it at every speed,
    // eigenvalues only, ids after the reported ones. Not judged by any verdict.
    double band = std::numeric_limits<double>::infinity();
    bool band_of_modes = false;   // the band was chosen to hold the K lowest modes (CampbellOptions)
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

// The tracking options every front end uses: `modes` as asked (kModesInRange:
// every mode in the excitation band of the speeds and harmonics; 0: every mode;
// K: the K lowest at the first speed) on the solver `plan`.
CampbellOptions tracking_options(const SolverChoice& plan, int modes, const std::vector<double>& speeds,
                                 const std::vector<int>& harmonics, Workers threads = {});

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

// The Campbell diagram every front end draws: on tracking_solver; and for the K
// lowest modes of a dense solver, on the continuation in a band that holds them
// (ContinuationOptions::lowest), widened (x 2) while a reported branch leaves it or reaches
// within 10 % of its edge, and after three widenings a full solve at every speed.
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
// (CampbellDiagram::branches): its branch id and point.
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

}  // namespace gyrokit
