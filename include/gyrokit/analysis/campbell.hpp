// Campbell diagram: the modes tracked across spin speed. Modes are matched
// between neighbouring speeds by eigenvector correlation (MAC) plus eigenvalue
// continuity; where the match is ambiguous (crossing, veering) the speed step
// is bisected.
#pragma once

#include <gyrokit/analysis/spectrum_solver.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <functional>
#include <vector>

namespace gyrokit {

struct CampbellOptions {
    EigenOptions eig;
    int modes = 0;            // keep the K lowest branches by frequency at the first speed (oscillating
                              // ones first, real eigenvalues after them); 0 = all.
                              // Dense: only these (and the next two) decide whether a step is ambiguous
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
    std::vector<std::string> notes; // the solvers' notes, each once
    // Dense with opt.modes = K: the branches beyond the K reported, eigenvalues only
    // (no vectors), ids K + 1 on; a dense spectrum is complete, so they cost nothing
    // more and let a stability verdict cover every mode.
    std::vector<Branch> untracked;
};

// Dense: every mode of the system, solved with opt.eig.
CampbellDiagram campbell(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                         const CampbellOptions& opt = {});

// Any solver (e.g. sparse_solver: a window of modes near a target). Modes that
// enter or leave a window start or end branches; only the lowest opt.modes
// decide whether a step is ambiguous.
CampbellDiagram campbell(const SolverFactory& solver, const std::vector<double>& speeds,
                         const CampbellOptions& opt = {});

// Matching cost between two modes (0 = identical shape and eigenvalue).
double match_cost(const Mode& a, std::complex<double> predicted, const Mode& b);

// The mode of `spectrum` that continues `branch` at speed w, which lies between
// branch points i and i + 1: the best match to the nearer point, with the
// eigenvalue predicted by linear interpolation.
const Mode& continue_branch(const Branch& branch, size_t i, double w, const QuadraticSpectrum& spectrum);

}  // namespace gyrokit
