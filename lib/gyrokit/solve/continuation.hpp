// Continuation of the modes in a frequency band over a speed range: a full dense
// solve at the first speed, steps along the branches at the others, the eigenvalues
// alone at check speeds to see that no mode came into the band unseen, every
// reported pair refined and verified on the full model. docs/numerics.md
// ("Continuation") gives the rules.
#pragma once

#include <gyrokit/solve/spectrum_solver.hpp>

#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace gyrokit {

struct ContinuationOptions {
    double band = 0;            // rad/s: the modes kept (frequency <= band; a real eigenvalue |lambda| <= band)
    // > 0: the band is widened to hold this many lowest modes: at least band_margin
    // times the largest frequency (|lambda| of a real eigenvalue) among the lowest
    // by frequency_rank at the anchors and checks (ContinuationReport::band; a mode
    // tied with the last of them lies inside the margin, one far above it is not
    // followed for nothing); `band` (0 allowed then) is the least it is.
    int lowest = 0;
    double band_margin = 1.25;
    // Full solves (anchors) at the first speed and, if > 0, at every this many speeds
    // of the grid and the last.
    int anchor_stride = 0;
    // The eigenvalues alone (QZ without vectors) at every this many speeds and the
    // last, where there is no anchor: the modes continued there must account for every
    // eigenvalue within twice the band, else the speed is solved in full.
    int check_stride = 25;
    double tolerance = 1e-10;   // a pair is kept if the backward errors of its right and left vectors are below
    // The basis is used only if its dimension is at most this fraction of the DOFs:
    // the projected QZ costs about (r/n)^3 of the full one, and the refinement and
    // verification of each pair come on top (measured by gyrokit-bench-campbell).
    double max_basis_fraction = 0.75;
    bool along_branches = true;  // step 1 below (false: the projected pencil first, for tests and benchmarks)
    EigenOptions eig;           // the full solves' method; left_vectors: keep them in the modes
    Workers workers = 1;        // the anchors' and checks' solves; a sweep's steps correct their modes on these threads
};

// What the continuation did, for the notes and the benchmark.
struct ContinuationReport {
    // The projected pencil (only with along_branches false): false where the basis
    // would not pay or is not built (the steps along the branches come first).
    bool used = false;
    int basis = 0;              // dimension of the reduced basis (0: not built)
    int dofs = 0;
    double band = 0;            // the band used (rad/s)
    std::vector<double> anchors;   // speeds solved in full (continued from, and the basis)
    std::vector<double> checks;    // speeds whose eigenvalues check the continued modes
};

// A solver (SolverFactory) for any speed in or near `speeds` that returns the
// modes within the band, tried in this order:
// 1. Along the branches: from the nearest speed this solver (or an anchor) has
//    solved, each mode within twice the band is predicted along its slope and
//    corrected by inverse iteration on the full P(lambda); the step is taken if
//    every pair verifies (backward errors of the right and left vectors <=
//    opt.tolerance), stays within 0.3 of its distance to the nearest other
//    prediction, and no two pairs land on one mode. A step that fails is taken
//    as two half steps (each halved again where it fails: a sixteenth at most).
//    At a check speed (every check_stride-th and the last) the continued modes
//    must also account for every eigenvalue within twice the band there (QZ
//    without vectors, computed at construction).
// 2. Only with along_branches false: the projected pencil Q^T P(w) Q, Q an
//    orthonormal real basis of the right and left vectors (real and imaginary
//    parts) of every mode within twice the band at the anchors; each eigenpair
//    within the band lifted to the full model, refined and verified as above.
//    Skipped if the basis would exceed max_basis_fraction of the DOFs
//    (report->used = false) and at check speeds.
// 3. A full solve (the next steps continue from it).
// Every mode gets its error bound, whirl and slope as from the dense solver;
// spectra hold every mode within the band (not marked partial: the band is not a
// moving window), `method` names the path. At an anchor speed
// the full solve's modes in the band are returned. A grid speed is always reached
// from the anchor at or below it through the grid speeds between (a solver that
// starts mid-grid walks there first), so the answers do not depend on how the grid
// is shared among workers: the same bits on one worker or several.
SolverFactory continuation_solver(std::shared_ptr<const GyroscopicSystem> model, const std::vector<double>& speeds,
                                  const ContinuationOptions& opt, ContinuationReport* report = nullptr);

// One mode followed to speed w (a root search along one branch): `from`, a
// verified mode of a nearby speed, started at `predicted` and corrected by
// inverse iteration on the full P(lambda) at w (up to three factorizations, as
// step 1 above). Kept if its right and left vectors verify to `tolerance`, it lies
// within `reach` of the prediction and its shape has MAC >= 0.9 with `from`'s;
// then with whirl and error bound as from the solvers, and no slope (NaN: a root
// search measures the mode where it chooses). Nothing otherwise.
std::optional<Mode> follow_mode(const std::function<SparsePencil(double)>& pencil,
                                const std::vector<std::pair<int, int>>& whirl_pairs, const Mode& from, double w,
                                std::complex<double> predicted, double reach, double tolerance = 1e-10);

// Step 1 above alone, for window (sparse) solvers: the modes of `from`, a
// verified spectrum at speed from.speed with left vectors and slopes, predicted
// along their slopes and corrected at w, each kept if it verifies, stays within
// 0.3 of its distance to the nearest other prediction and keeps MAC >= 0.9 with
// its shape at from.speed (a mode outside the window cannot be seen, so the shape
// tells a jump onto it), in halves (down to sixteenths) where the whole step fails
// (as step 1 above; the modes at w then keep MAC >= 0.9 with distinct modes of
// `from`). With left vectors and slopes; nothing if any mode fails.
// The modes are corrected on `threads` threads (the same result on any number).
std::optional<QuadraticSpectrum> continue_window(const std::function<SparsePencil(double)>& pencil,
                                                 const std::vector<std::pair<int, int>>& whirl_pairs,
                                                 const QuadraticSpectrum& from, double w, double tolerance = 1e-10,
                                                 int threads = 1);

// Whether a mode lies within the band: an oscillating one by its frequency, a
// real (overdamped) one by its modulus, a divergent one (real, positive) always.
bool within_band(const Mode& m, double band, double real_tol);

}  // namespace gyrokit
