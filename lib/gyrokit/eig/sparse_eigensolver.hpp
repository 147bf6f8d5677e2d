// Sparse quadratic eigensolver: ARPACK (Arnoldi) in shift-invert mode
// on the first companion pencil A - lambda B, A = [-C -K; I 0], B = [M 0; 0 I].
// The operator (A - sigma B)^{-1} B needs only a sparse LU of the n x n matrix
// P(sigma) = sigma^2 M + sigma C + K, factorized once per call:
//   w2 = -P(sigma)^{-1} (M v1 + (C + sigma M) v2),  w1 = v2 + sigma w2.
// Eigenvalues of the operator theta give lambda = sigma + 1/theta.
// A real shift keeps the operator real: real Arnoldi (dnaupd) on a real LU,
// conjugate pairs found together; a complex shift uses complex Arnoldi (znaupd).
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/mode.hpp>

#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

namespace gyrokit {

struct SparseEigenOptions {
    int modes = 6;                          // eigenvalues with Im >= 0 wanted (conjugates not counted)
    std::complex<double> shift{0.0, 0.0};   // sigma: the search centre (i nu for modes near frequency nu)
    // In a sweep (sparse_solver), the centre moves with the speed w:
    // sigma(w) = shift + i * shift_order * w, so the window follows the line
    // nu + k w of the Campbell diagram (k = 1: the modes near the 1x line).
    double shift_order = 0.0;
    int lanczos_vectors = 0;                // ARPACK ncv; 0 = max(2 nev + 1, 30), capped at 2n
    int max_iterations = 3000;
    double tolerance = 0.0;                 // ARPACK relative Ritz tolerance; 0 = machine precision
    Eigen::VectorXcd start;                 // start vector of length 2n (e.g. the last speed's modes); empty: random
    // Every returned eigenpair is verified: its backward error must not exceed
    // this after refinement (inverse iteration on P(lambda)), else SolverError.
    double verify_tolerance = 1e-10;
    int reserve = 0;                        // extra eigenvalues asked of ARPACK (rigid-body ones expected in the window)
    bool left_vectors = false;              // keep the left vectors in the modes (always computed, for the error bounds)
};

struct SparseSpectrum {
    std::vector<Mode> modes;        // the wanted modes nearest the shift, by frequency, verified
    std::vector<Mode> rigid_body;   // rigid-body eigenvalues found in the window (not modes)
    int iterations = 0;             // Arnoldi restarts used
    int converged = 0;              // Ritz values converged
    std::complex<double> shift;     // the shift used (moved off a singular P(sigma))
    int refined = 0;                // eigenpairs whose backward error needed refinement
    double max_raw_backward_error = 0;   // largest backward error before verification
    std::vector<std::string> notes;
};

// Real sparse matrix times complex vector, without a complex copy of the matrix.
Eigen::VectorXcd real_times(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x);
// A^T x, without a transposed copy of A.
Eigen::VectorXcd real_transpose_times(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x);
// y^H A x for real sparse A, without forming A x.
std::complex<double> real_bilinear(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& y,
                                   const Eigen::VectorXcd& x);

// The action of a sparse pencil (its matrices referenced: they must outlive it).
PencilAction sparse_pencil_action(const SparsePencil& p);

// The solvers' DOF scaling t_i = 1/sqrt(g^2 |M_ii| + g |C_ii| + |K_ii|), g the
// natural frequency scale (1 where that is zero or not finite).
Eigen::VectorXd sparse_dof_scaling(const SparsePencil& p, double scale);

// The Frobenius norms of T M T, T C T and T K T (T = diag(t)), without forming them.
PencilNorms scaled_norms(const SparsePencil& p, const Eigen::VectorXd& t);

// A fixed pseudo-random vector of length n with entries in [-1, 1], the same on
// every call, in every process and on every machine: ARPACK's own start (LAPACK's
// dlarnv with a seed it carries from call to call) and std::rand would make a
// result depend on what was solved before it.
Eigen::VectorXd fixed_random_vector(Eigen::Index n);

// Inverse iteration on P(lambda) from an approximate eigenpair (m.lambda,
// m.right), with one sparse LU of P at a point 1e-12 |lambda| off the eigenvalue
// (so that it is not singular to rounding, yet resolves pairs split by 1e-10):
// always finds the left vector; refines the right vector and the eigenvalue
// (two-sided Rayleigh quotient) only if the pair's backward error exceeds
// `accurate`, since inverse iteration from two vectors of a double eigenvalue's
// plane may turn both to one direction. The left iteration starts from m.left
// where it is a nonzero finite vector, else from m.right. Sets m.lambda, right, left and
// backward_error; returns the backward error before refinement. `scale` is the
// pencil's natural frequency scale. `predicted`: the pair is a prediction (a mode
// of a nearby speed), known not to be accurate: it is refined without its backward
// error first (returned as infinity), its first left solve plain inverse iteration.
double refine_eigenpair(const SparsePencil& p, const PencilAction& action, Mode& m, double accurate, double scale,
                        bool predicted = false);

// Eigenvalues near the shift sigma = opt.shift. If P(sigma) is singular or
// nearly so (rigid-body modes at sigma = 0 with a singular K), the shift is
// moved to sigma - 1e-5 g (then 1e-4 g, 1e-3 g; g = sqrt(|K|/|M|)) and a note
// says so. Rigid-body eigenvalues in the window are returned apart and the
// window widened so that `opt.modes` modes remain. Each eigenpair is refined
// by inverse iteration on P(lambda) and verified (verify_tolerance), and gets
// its left vector and error bound. Throws InputError if no shift works and
// SolverError if ARPACK does not converge or a pair fails verification,
// saying what to change.
SparseSpectrum solve_quadratic_sparse(const SparsePencil& p, const SparseEigenOptions& opt,
                                      const std::vector<std::pair<int, int>>& whirl_pairs = {});

// Relative backward error (Frobenius norms) of an eigenpair of the sparse pencil.
double backward_error(const SparsePencil& p, std::complex<double> lambda, const Eigen::VectorXcd& x);

}  // namespace gyrokit
