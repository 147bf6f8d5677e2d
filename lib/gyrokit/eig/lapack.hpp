// Thin wrappers of the LAPACK generalized eigensolvers (QZ) used by gyrokit.
#pragma once

#include <Eigen/Dense>

namespace gyrokit {

// Eigenvalues alpha(j)/beta(j) of A v = lambda B v, with right (and optionally
// left: u^H A = lambda u^H B) eigenvectors as complex columns.
struct GeneralizedEigen {
    Eigen::VectorXcd alpha;
    Eigen::VectorXd beta;       // real for dggev
    Eigen::VectorXcd beta_c;    // complex for zggev
    Eigen::MatrixXcd right, left;
};

// Real pencil: dggev3 (multishift QZ with aggressive early deflation, blocked
// Hessenberg-triangular reduction) by default, dggev (the classic single-shift
// QZ) with `classic`. Throws SolverError if QZ fails.
GeneralizedEigen lapack_dggev(Eigen::MatrixXd A, Eigen::MatrixXd B, bool want_left, bool classic = false);
// The eigenvalues alone (no vectors: QZ without accumulating its transformations),
// as lapack_dggev; right and left stay empty.
GeneralizedEigen lapack_dggev_values(Eigen::MatrixXd A, Eigen::MatrixXd B, bool classic = false);
// Standard eigenproblem A v = lambda v (dgeev: balancing, Hessenberg QR): alpha holds
// the eigenvalues (beta is empty), right and optionally left (u^H A = lambda u^H)
// eigenvectors. Throws SolverError if QR fails.
GeneralizedEigen lapack_dgeev(Eigen::MatrixXd A, bool want_left = false);
// The eigenvalues alone of A v = lambda v (dgeev without vectors).
Eigen::VectorXcd lapack_dgeev_values(Eigen::MatrixXd A);
// Complex pencil (zggev), right eigenvectors only.
GeneralizedEigen lapack_zggev(Eigen::MatrixXcd A, Eigen::MatrixXcd B);

}  // namespace gyrokit
