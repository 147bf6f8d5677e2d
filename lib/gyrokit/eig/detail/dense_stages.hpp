// The stages of the dense quadratic solve (eig/quadratic_eigensolver.cpp reads them
// top to bottom): the pencil's scales and action, its uncoupled DOF groups, and the
// two ways to its raw eigenpairs (QZ of the scaled companion form, or the scaled
// state matrix refined on the quadratic). Internal to eig/.
#pragma once
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <complex>
#include <vector>

namespace gyrokit::dense {

// The pencil's action for residuals: sparse where the matrices are (a finite-element
// pencil), dense otherwise. Backward errors always refer to the original pencil.
PencilAction action_of(const QuadraticPencil& p);

// The natural frequency scale g (natural_frequency_scale of the diagonals and norms).
double natural_scale(const QuadraticPencil& p);

// Diagonal congruence z = T w with t_i = 1/sqrt(W_ii), W = g^2|M| + g|C| + |K|,
// normalised to max t = 1: undoes badly scaled units without changing eigenvalues.
Eigen::VectorXd dof_scaling(const QuadraticPencil& p);

// The norms of the DOF-scaled pencil T M T, T C T, T K T: the error bounds refer to
// them (as QZ solves it), so stiff supports do not inflate the bounds.
PencilNorms scaled_norms(const QuadraticPencil& p, const Eigen::VectorXd& t);

// The scaling of the companion form: DOF scaling t, then lambda = gamma mu and the
// coefficients times delta (Fan-Lin-Van Dooren: norms about one).
struct CompanionScaling {
    Eigen::VectorXd t;
    double gamma = 1.0, delta = 1.0;
};
CompanionScaling companion_scaling(const QuadraticPencil& original);

// The scaled first companion form A - mu B (lambda = gamma mu) in the coordinates
// x = T^-1 x_original, eigenvector [mu x; x].
struct Companion {
    Eigen::VectorXd t;
    double gamma = 1.0;
    Eigen::MatrixXd A, B;
};
// In a given scaling: a group of a pencil takes the whole's, so that its rounding,
// down to the split of a rigid-body zero, is the whole's.
Companion companion(const QuadraticPencil& original, const CompanionScaling& scaling);
Companion companion(const QuadraticPencil& original);

// How many of the companion form's 2n eigenvalues are infinite at least: one for
// each dimension of M's null space (two where that DOF has no damping either), none
// where M is invertible. M's rank is taken in its own diagonal scaling, so that
// units and a stiff support (1e20 N/m beside kilograms) do not make it singular.
int infinite_limit(const QuadraticPencil& p);

// Whether QZ's alpha / beta is an infinite eigenvalue (beta at rounding level).
bool infinite(std::complex<double> alpha, double beta);

// The eigenvalues QZ put at infinity beyond that least count (a DOF whose mass is
// below rounding against its stiffness: 1e20 N/m beside kilograms): up to `lost`
// largest eigenvalues of the pencil, found as the smallest of the reversed pencil
// nu^2 K + nu C + M (nu = 1/lambda; same vectors), in the upper half plane (a
// complex pair counts 2 toward `lost`, a real eigenvalue 1). A nu at rounding level
// is a true infinite eigenvalue (M's null space): not taken. Backward errors on p.
std::vector<Mode> largest_by_reversal(const QuadraticPencil& p, int lost, bool want_left, bool classic);

// The DOFs in groups the pencil does not couple (connected components of M's, C's
// and K's entries), each increasing; empty where a group has no mass (then the
// pencil is solved whole).
std::vector<std::vector<Eigen::Index>> uncoupled_groups(const QuadraticPencil& p);
QuadraticPencil restricted(const QuadraticPencil& p, const std::vector<Eigen::Index>& group);

// Stage 1, QZ: every finite eigenpair of the upper half plane (and the real axis),
// right and (want_left) left vectors, backward errors on the whole pencil; each
// uncoupled group solved on its own. `classic`: dggev instead of dggev3.
QuadraticSpectrum qz_eigenpairs(const QuadraticPencil& p, bool want_left, bool classic);

// Stage 1, state matrix: the same from dgeev of the scaled state matrix, every pair
// not at rounding level refined on the quadratic (its left vector too). SolverError
// where M is singular.
QuadraticSpectrum state_matrix_eigenpairs(const QuadraticPencil& p);

}  // namespace gyrokit::dense
