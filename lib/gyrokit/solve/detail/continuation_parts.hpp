// The continuation's parts, internal to analysis/ (continuation.hpp gives the
// whole): the steps along the branches (continuation_steps.cpp), the anchors and
// checks (continuation_anchors.cpp), the projected pencil
// (continuation_projection.cpp), and the walk over the grid that ties them
// together (continuation.cpp).
#pragma once

#include <gyrokit/solve/continuation.hpp>

#include <complex>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace gyrokit::continuation_detail {

using cd = std::complex<double>;

// --- the steps along the branches (continuation_steps.cpp) ---

PencilAction action_of(const SparsePencil& p);
// Relative backward error of a left vector: |P(l)^H y| / ((|l|^2 |M| + |l| |C| + |K|) |y|).
double left_backward_error(const SparsePencil& p, const PencilAction& a, cd l, const Eigen::VectorXcd& y);

// A solved speed to continue from: the modes within twice the band (with their
// slopes) and the rigid-body eigenpairs.
struct Solved {
    double w = 0.0;
    std::vector<Mode> track;
    std::vector<Mode> rigid;
    // The smallest modulus of the modes beyond the tracked ones at the last full
    // solve: a corrected mode must not slide onto one of them either.
    double beyond = std::numeric_limits<double>::infinity();
    // Where w was reached by a step: the speed before and each tracked mode's slope
    // there (NaN: unknown), whose change gives its branch's curvature.
    double before = std::numeric_limits<double>::quiet_NaN();
    std::vector<cd> slope_before;
};

// What a continued solve needs of the model and the options: the continuation's
// own (frame_of) or a window solver's (continue_window).
struct Frame {
    std::function<SparsePencil(double)> pencil;
    const std::vector<std::pair<int, int>>* whirl_pairs = nullptr;
    double tolerance = 1e-10;
    double band = std::numeric_limits<double>::infinity();
    bool keep_left = true;
    double min_mac = 0.0;   // > 0: each corrected mode keeps at least this MAC with its shape before the step
    int threads = 1;        // the modes of a step are corrected in parallel
    // Second-order predictions (Solved::slope_before): the continuation's own steps. A
    // window's (continue_window) stay first order: their modes feed the Hautus test,
    // which measures the left vectors against the right ones' backward error, and a
    // first round that already reaches the right's target leaves the left vector one
    // plain round from its start.
    bool second_order = false;
    // A failed step's modes tried again as groups (branch_solve's clusters): the
    // continuation's own steps. A window's keep each mode's shape (min_mac) and fall
    // back to a window solve, whose vectors of a double pair the Hautus test reads.
    bool clusters = false;
    WorkCounter* work = nullptr;   // counts the steps taken in parts and the modes joined (the continuation's)
};

// The common end of the continued solves: whirl, rigid-body split, error bounds,
// order and (unless the caller sets them) slopes of the verified pairs.
QuadraticSpectrum finish(const Frame& fr, const SparsePencil& p, const PencilAction& action, QuadraticSpectrum out,
                         std::vector<Mode> modes, double w, bool slopes = true);
QuadraticSpectrum empty_spectrum(const SparsePencil& p, const PencilAction& action, double w);
// A pair refined on the full model: verified right and left vectors, conjugated
// into the upper half plane, exactly real where it is real to the tolerance.
bool verified(const SparsePencil& p, const PencilAction& action, Mode& m, double tolerance, double real_tol);
// Mode m started at `predicted` and corrected on the full pencil (refined to 1e-3 of
// the tolerance where three factorizations get there), then verified.
bool corrected(const SparsePencil& p, const PencilAction& action, Mode& m, cd predicted, double tolerance,
               double scale, double real_tol, bool stepped = true);
// Two refined pairs on one mode: a mode is missing.
bool lands_on_another(const std::vector<Mode>& modes, const Mode& m);
// The mode at speed w whose eigenvalue is `lambda` (known from the eigenvalues alone):
// inverse iteration at it from a fixed start vector, verified, with its slope; none
// where it does not converge to lambda (within 1e-6 of its modulus) or lands on a
// mode of `at`.
std::optional<Mode> joined_mode(const Frame& fr, const Solved& at, double w, cd lambda);
// A start of a correction: the predicted eigenvalue, a start vector (the mode's own
// or a Ritz vector) and the tracked mode it continues (-1: a Ritz pair of a cluster,
// whose modes may be one more or one fewer than before, at an exceptional point).
struct Seed {
    cd predicted;
    Mode start;
    long origin = -1;
};

// The distance between two eigenvalues, the conjugate's included.
double pair_distance(cd a, cd b);

// The modes of a failed step that move as a group: each failed mode with its nearest
// neighbour, or alone where its own conjugate is nearer (continuation_clusters.cpp).
std::vector<std::vector<size_t>> clusters_of(const std::vector<Mode>& track, const std::vector<size_t>& failed,
                                             double real_tol);

// The Ritz pairs of a cluster at the pencil p as seeds; none where the span or the choice fails.
std::optional<std::vector<Seed>> cluster_seeds(const SparsePencil& p, const std::vector<Mode>& track,
                                               const std::vector<size_t>& members, double real_tol);

// Step 1: every mode of `from` predicted along its slope and corrected at w. Given
// `cluster_failed` (the modes a plain step failed on, listed in `failed`), each of
// them with its nearest neighbour (or alone, as a complex pair about to meet on the
// real axis) is a cluster whose modes come from the Ritz pairs of its span: their
// count may change (two real eigenvalues that meet become one complex pair).
std::optional<QuadraticSpectrum> branch_solve(const Frame& fr, const Solved& from, double w, Solved& next,
                                              const std::vector<size_t>* cluster_failed = nullptr,
                                              std::vector<size_t>* failed = nullptr);
// Step 1 (plain, then clustered) with the step halved where it fails, up to `halvings` times (a sixteenth:
// near an exceptional point or a close crossing a shorter step often verifies
// where the whole did not, at a few corrections instead of a full solve).
std::optional<QuadraticSpectrum> branch_steps(const Frame& fr, const Solved& from, double w, Solved& next,
                                              int halvings = 4);

// --- the grid's shared state (continuation.cpp) ---

struct Shared {
    std::shared_ptr<const GyroscopicSystem> model;
    ContinuationOptions opt;
    std::vector<double> grid;                       // the speeds, increasing
    Eigen::MatrixXd Q;                              // n x r, orthonormal columns (empty: not used)
    std::map<double, QuadraticSpectrum> anchors;   // the full solves, kept to the band
    std::map<double, Solved> anchor_tracks;
    std::map<double, QuadraticSpectrum> checks;    // eigenvalues alone (modes without vectors)
    std::shared_ptr<WorkCounter> work;              // the factory's
};

// What a full solve (with the slopes of its modes) leaves to continue from.
Solved track_of(const QuadraticSpectrum& s, const Shared& sh, double w);
// The modes of a full solve (with their slopes) within the band.
QuadraticSpectrum keep_band(QuadraticSpectrum s, const Shared& sh);
QuadraticSpectrum full_solve(const Shared& sh, double w, Solved* track = nullptr);
// The continuation's own frame for its steps.
Frame frame_of(const Shared& sh, int threads = 1);

// --- the anchors and checks (continuation_anchors.cpp) ---

// The full solves at the anchors and the eigenvalues alone at the checks (of
// sh.grid, per sh.opt), the band widened to hold the lowest modes where asked, the
// projection basis; into sh and rep.
void solve_anchors(Shared& sh, ContinuationReport& rep);
// The eigenvalues at speed w alone, as a spectrum of modes without vectors.
QuadraticSpectrum eigenvalues_only(const GyroscopicSystem& sys, double w);
// Whether the modes continued to a check speed account for its eigenvalues within
// twice the band (those beyond the band joined to `at` by joined_mode); the
// unmatched eigenvalues' smallest modulus becomes `at.beyond`.
bool accounts(Solved& at, const QuadraticSpectrum& check, double band, const Frame& fr);

// --- the projected pencil (continuation_projection.cpp) ---

// The reduced solve at w, or nothing where a pair fails verification.
std::optional<QuadraticSpectrum> reduced_solve(const Shared& sh, double w);

}  // namespace gyrokit::continuation_detail
