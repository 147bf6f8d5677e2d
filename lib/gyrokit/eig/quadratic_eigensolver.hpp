// Dense solvers for the quadratic eigenproblem (lambda^2 M + lambda C + K) x = 0.
//
// Auto (default): StateMatrix from kAutoStateDofs DOFs on, kept where every pair is
//   verified (kStateVerifyTolerance) and vouched for; ScaledQZ otherwise.
// ScaledQZ: Fan-Lin-Van Dooren scaling, first companion linearization,
//   LAPACK dggev3 (multishift QZ with aggressive early deflation). Needs no
//   inverse of M, so singular M (infinite eigenvalues) and badly scaled data are
//   handled. ClassicQZ: the same with LAPACK dggev (single-shift QZ), slower on
//   large pencils (docs/benchmarks.md).
// StateMatrix: the cheaper M^{-1}-based state matrix solved by Eigen; fails on
//   singular M and loses accuracy on badly scaled problems (see docs/numerics.md).
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/core/solver_kind.hpp>
#include <gyrokit/eig/mode.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// An eigenvalue is vouched for when its error bound is at most this fraction of
// its modulus (or below the real-axis tolerance); otherwise the spectrum says so.
constexpr double kVouchTolerance = 1e-6;

// Every eigenpair the dense solver returns has a backward error at most this
// (QZ gives about 1e-15); else SolverError, never a table of noise.
constexpr double kDenseVerifyTolerance = 1e-8;

// The state-matrix pairs are refined towards this backward error (the sparse solver's
// verification); the default method (EigenMethod::Auto) keeps the state matrix's answer
// only where every pair reached it and every mode is vouched for, else it solves by QZ.
constexpr double kStateVerifyTolerance = 1e-10;

struct QuadraticSpectrum {
    std::vector<Mode> modes;      // finite eigenvalues with Im >= 0 (or real), by frequency; no rigid-body ones
    // Rigid-body eigenvalues (is_rigid_body: lambda = 0 up to rounding, a singular
    // K): listed apart, never modes. Each computed zero eigenvalue is one entry
    // (a free DOF group without damping gives two: q = a + b t).
    std::vector<Mode> rigid_body;
    int infinite_count = 0;       // infinite eigenvalues (singular M)
    double scale = 1.0;           // sqrt(|K|/|M|): the problem's natural frequency scale
    double real_tol = 0.0;        // |Im lambda| below this counts as real
    bool partial = false;         // only a window of modes (near a shift), not all
    double speed = 0.0;           // rad/s, where a sweep or a root search set it
    double speed_bound = 0.0;     // rad/s: a root search's bound on |speed - the exact root| (0: none)
    std::vector<std::string> notes;   // what the solver changed or could not vouch for (e.g. a moved shift)
    // The solver's account, as Spectra's CompInfo: a spectrum is only returned
    // when it converged and every mode passed verification (else SolverError).
    std::string method;           // "scaled QZ", "state matrix" or "ARPACK shift-invert"
    int iterations = 0;           // Arnoldi restarts (sparse); 0 for the dense solvers
    int refined = 0;              // sparse: eigenpairs whose backward error needed refinement
    double max_backward_error() const;
};

// Moves the rigid-body eigenvalues of `modes` (is_rigid_body) into `rigid_body`, order kept.
void split_rigid_body(std::vector<Mode>& modes, std::vector<Mode>& rigid_body, const PencilAction& pencil,
                      double scale);

// All finite eigenpairs of the pencil, conjugates dropped (the upper half plane
// and the real axis kept). Whirl is classified with `whirl_pairs`.
QuadraticSpectrum solve_quadratic(const QuadraticPencil& p, const EigenOptions& opt,
                                  const std::vector<std::pair<int, int>>& whirl_pairs = {});

// The finite eigenvalues alone (no vectors to verify them with): where M is
// symmetric positive definite and well conditioned, LAPACK dgeev on the state
// matrix of the Cholesky congruence of the DOF-scaled pencil; else the QZ of
// solve_quadratic (its scaling and linearization) without vectors, dggev up to
// kClassicValuesLimit DOFs and dggev3 above (the faster of the two without
// vectors). A quarter to a half of the full solve's cost (docs/numerics.md,
// "Continuation"). The upper half plane and the real axis (|Im| <= real_tol) kept.
constexpr int kClassicValuesLimit = 400;
struct EigenvalueSet {
    std::vector<std::complex<double>> values;
    double scale = 1.0;      // as QuadraticSpectrum
    double real_tol = 0.0;
};
EigenvalueSet quadratic_eigenvalues(const QuadraticPencil& p);

// Convenience: the spectrum of a system at spin speed w.
QuadraticSpectrum solve_at_speed(const GyroscopicSystem& sys, double w, const EigenOptions& opt = {});

// Relative backward error of an approximate eigenpair (Tisseur 2000), with
// Frobenius norms: |P(l) x| / ((|l|^2 |M| + |l| |C| + |K|) |x|).
double backward_error(const QuadraticPencil& p, std::complex<double> lambda, const Eigen::VectorXcd& x);

}  // namespace gyrokit
