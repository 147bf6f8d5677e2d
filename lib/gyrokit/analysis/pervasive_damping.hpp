// Pervasive damping (Hautus / Mueller test, eq. (24) of the gyrostat paper):
// the damping D does not reach a mode at speed w if some z != 0 satisfies
// z^T P(lambda) = 0 and z^T D = 0. Measured by the smallest singular value of
// [P(lambda)^T; D] (both blocks normalized) over the eigenvalues lambda of the
// system damped by D alone; it vanishes like |w - w*| at a loss, so the loss
// speed is located by golden section to near machine precision.
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/mode.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The largest residual of a loss unless asked otherwise.
constexpr double kPervasiveTolerance = 1e-8;

struct PervasiveOptions {
    // Upper limit of the residual of a loss. Below it, a residual counts as a
    // loss only at the level the eigenpair's accuracy explains: r <= 1e3 max(eta, sqrt(n) eps).
    double tolerance = kPervasiveTolerance;
    int modes = 0;   // the K lowest branches at the first speed are checked; 0 = all (dense) or
                     // the sparse solver's default window; kModesInRange: those in range of 1x
                     // the speeds (tracking_options)
    // Which solver computes the modes (choose_solver; its `modes` is replaced by
    // the field above). Dense: the full SVD of [P^T; D] refines a loss as well;
    // sparse: the residual over the left eigenvectors, in O(nonzeros).
    SolverOptions solver;
    Workers threads = 1;   // speeds of each Campbell diagram solved in parallel (run_on_workers)
};

struct DampingLoss {
    std::string damping;   // component name, or "total"
    double speed = 0;      // rad/s
    int mode = 0;          // Campbell branch id of the system damped by this set alone
    Mode lost;             // the undamped mode (Re lambda = 0 up to rounding)
    double residual = 0;
};

struct PervasiveReport {
    std::vector<std::string> checked;   // the damping sets tested
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

// Checks each damping component alone and the total damping over the speeds.
PervasiveReport pervasive_damping(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  const PervasiveOptions& opt = {});

}  // namespace gyrokit
