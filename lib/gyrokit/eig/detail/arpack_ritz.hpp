// The shift-invert Arnoldi iteration of the sparse eigensolver on ARPACK's reverse
// communication (dnaupd/dneupd for a real shift, znaupd/zneupd for a complex one).
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <arpack/arpackdef.h>

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

namespace gyrokit::detail {

// A converged Ritz pair of the shift-invert operator: theta and its state vector.
struct Ritz {
    std::complex<double> theta;
    Eigen::VectorXcd z;
};

struct ArnoldiSize {
    a_int N, nev, ncv;
    // The values that must converge when not all do: those of the wanted modes
    // (real shift: with their conjugates), without the margin at the window's edge.
    a_int wanted;
};

// P(sigma) is singular or too nearly so for shift-invert (the shift sits on
// an eigenvalue: sigma = 0 with rigid-body modes); the caller moves the shift.
struct SingularShift {
    std::string why;
};

// The converged Ritz pairs of the shift-invert operator at opt.shift: real Arnoldi for
// a real shift (conjugate pairs together, at a fraction of the cost of complex
// arithmetic), complex Arnoldi otherwise. t is the DOF scaling for the condition
// estimate of P(shift); throws SingularShift if P(shift) is too nearly singular,
// SolverError if ARPACK fails or the wanted values do not converge.
std::vector<Ritz> arnoldi_ritz_pairs(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                                     const Eigen::VectorXd& t, int& iterations);

}  // namespace gyrokit::detail
