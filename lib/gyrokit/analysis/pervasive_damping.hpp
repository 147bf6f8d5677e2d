// Pervasive damping (Hautus / Mueller test, eq. (24) of the gyrostat paper):
// the damping D does not reach a mode at speed w if some z != 0 satisfies
// z^T P(lambda) = 0 and z^T D = 0. Measured by the smallest singular value of
// [P(lambda)^T; D] (both blocks normalized) over the eigenvalues lambda of the
// undamped system (z^T P_D(lambda) = 0 with z^T D = 0 is z^T P_0(lambda) = 0 with
// z^T D = 0: one tracking for every set); it vanishes like |w - w*| at a loss, so
// the loss speed is located by golden section to near machine precision.
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/mode.hpp>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// The largest residual of a loss unless asked otherwise.
constexpr double kPervasiveTolerance = 1e-8;

struct PervasiveOptions {
    // Upper limit of the residual of a loss. Below it, a residual counts as a
    // loss only at the level the eigenpair's accuracy explains: r <= 1e3 max(eta, sqrt(n) eps).
    double tolerance = kPervasiveTolerance;
    // As for a Campbell diagram (tracking_options): kModesInRange and K check every mode
    // up to f_cut (K sets the sparse window); 0 every mode (dense) or the sparse
    // solver's default window.
    int modes = 0;
    std::optional<double> f_cut;   // the judged modes' cut-off (rad/s); default 1.5 x the top speed
    // Which solver computes the modes (choose_solver; its `modes` is replaced by
    // the field above). Dense: the full SVD of [P^T; D] refines a loss as well;
    // sparse: the residual over the left eigenvectors, in O(nonzeros).
    SolverOptions solver;
    Workers threads = 1;   // speeds of each Campbell diagram solved in parallel (run_on_workers)
};

struct DampingLoss {
    std::string damping;   // component name, or "total"
    double speed = 0;      // rad/s
    int mode = 0;          // Campbell branch id of the undamped system (whose mode it leaves unreached)
    Mode lost;             // the undamped mode (Re lambda = 0 up to rounding)
    double residual = 0;
};

// What was checked, and the losses found: a set pervades every checked mode at
// every checked speed where it has no loss.
struct PervasiveReport {
    std::vector<std::string> checked;   // the damping sets tested (each component alone, then "total")
    int speeds = 0;                     // grid speeds, from `from` to `to` (rad/s)
    double from = 0.0, to = 0.0;
    int modes = 0;                      // branches of the undamped system checked
    double band = std::numeric_limits<double>::infinity();   // f_cut (rad/s): modes up to it; inf: every mode
    bool partial = false;               // a sparse window that may miss modes up to f_cut (see notes)
    std::vector<std::string> notes;     // the tracking's
    std::vector<DampingLoss> losses;
};

// sigma_min([P(lambda)^T / |P|; D / |D|]) for an eigenvalue lambda of the pencil.
double pervasion_residual(const QuadraticPencil& p, const Eigen::MatrixXd& D, std::complex<double> lambda);
// The same minimum over z = conj(Y) c, Y the left eigenvectors (n x k, y^H P = 0;
// k = 2 for a double eigenvalue): a 2n x k SVD, for the grid scan.
double pervasion_residual(const QuadraticPencil& p, const Eigen::MatrixXd& D, std::complex<double> lambda,
                          const Eigen::MatrixXcd& Y);

// The same over the left vectors of a sparse pencil, in O(nonzeros) per vector.
double pervasion_residual(const SparsePencil& p, const SparseMatrix& D, std::complex<double> lambda,
                          const Eigen::MatrixXcd& Y);

// Checks each damping component alone and the total damping over the speeds, on
// the left vectors of the undamped system's modes (one tracking for every set: a
// loss of D is an undamped mode whose left vector D does not see).
PervasiveReport pervasive_damping(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  const PervasiveOptions& opt = {});

}  // namespace gyrokit
