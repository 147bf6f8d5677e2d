// Sparse quadratic eigensolver: ARPACK (Arnoldi) in shift-invert mode
// on the first companion pencil A - lambda B, A = [-C -K; I 0], B = [M 0; 0 I].
// The operator (A - sigma B)^{-1} B needs only a sparse LU of the n x n matrix
// P(sigma) = sigma^2 M + sigma C + K, factorized once per call:
//   w2 = -P(sigma)^{-1} (M v1 + (C + sigma M) v2),  w1 = v2 + sigma w2.
// Eigenvalues of the operator theta give lambda = sigma + 1/theta.
// A real shift keeps the operator real: real Arnoldi (dnaupd) on a real LU,
// conjugate pairs found together; a complex shift uses complex Arnoldi (znaupd).
#pragma once

#include "core/sparse_system.hpp"
#include "eig/mode.hpp"

#include <Eigen/Sparse>
#include <complex>
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
};

struct SparseSpectrum {
    std::vector<Mode> modes;   // the wanted modes nearest the shift, by frequency
    int iterations = 0;        // Arnoldi restarts used
    int converged = 0;         // Ritz values converged
};

// Throws InputError if P(sigma) is singular (the shift is an eigenvalue) and
// SolverError if ARPACK does not converge, saying what to change.
SparseSpectrum solve_quadratic_sparse(const SparsePencil& p, const SparseEigenOptions& opt,
                                      const std::vector<std::pair<int, int>>& whirl_pairs = {});

// Relative backward error (Frobenius norms) of an eigenpair of the sparse pencil.
double backward_error(const SparsePencil& p, std::complex<double> lambda, const Eigen::VectorXcd& x);

}  // namespace gyrokit
