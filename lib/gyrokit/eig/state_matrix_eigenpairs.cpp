// Stage 1 of the dense solve by the state matrix: dgeev of the scaled state matrix
// (cheaper than QZ, M must be invertible), then every pair that is not at rounding
// level on the quadratic refined there, as the sparse solver verifies its pairs.
#include "gyrokit/eig/detail/dense_stages.hpp"

#include <gyrokit/core/error.hpp>
#include "gyrokit/eig/lapack.hpp"
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <Eigen/LU>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gyrokit::dense {

using cd = std::complex<double>;

namespace {

// A pair straight from the state matrix whose right and left vectors both have
// backward errors below this on the quadratic is kept as it is.
constexpr double kStateRoundingLevel = 1e-14;

// Two vectors of one double eigenvalue turned to one direction: the later keeps
// its own vector and eigenvalue (and dgeev's left vector where there is one).
void keep_double_vectors(std::vector<Mode>& modes, const std::vector<Mode>& raw, int n) {
    for (size_t i = 0; i < modes.size(); ++i)
        for (size_t k = 0; k < i; ++k)
            if (std::abs(modes[i].lambda - modes[k].lambda) <= 1e-8 * std::abs(modes[i].lambda) &&
                mac(modes[i].right, modes[k].right) > 0.999 && raw[i].backward_error <= kStateVerifyTolerance) {
                modes[i].lambda = raw[i].lambda;
                modes[i].right = raw[i].right;
                modes[i].backward_error = raw[i].backward_error;
                if (raw[i].left.size() == n) modes[i].left = raw[i].left;   // dgeev's, where it gave one
                break;
            }
}

// A double eigenvalue (an isotropic rotor at standstill): its left vectors from
// separate refinements are any two of its left plane, so y^H P' x may nearly
// vanish and inflate the condition number. Turned biorthogonal to the right
// vectors (Y^H P'(lambda) X = I), as QZ's are, they give the bounds QZ gives.
void biorthogonalize_double_left(std::vector<Mode>& modes, const SparsePencil& sp, int n) {
    std::vector<bool> done(modes.size(), false);
    for (size_t i = 0; i < modes.size(); ++i) {
        if (done[i] || modes[i].left.size() != n) continue;
        std::vector<size_t> group{i};
        for (size_t k = i + 1; k < modes.size(); ++k)
            if (!done[k] && modes[k].left.size() == n &&
                std::abs(modes[k].lambda - modes[i].lambda) <= 1e-6 * std::abs(modes[i].lambda))
                group.push_back(k);
        for (size_t k : group) done[k] = true;
        if (group.size() < 2) continue;
        const Eigen::Index k = static_cast<Eigen::Index>(group.size());
        Eigen::MatrixXcd X(n, k), Y(n, k);
        for (Eigen::Index c = 0; c < k; ++c) {
            X.col(c) = modes[group[static_cast<size_t>(c)]].right;
            Y.col(c) = modes[group[static_cast<size_t>(c)]].left;
        }
        const cd l = modes[i].lambda;
        Eigen::MatrixXcd dX(n, k);   // P'(lambda) X
        for (Eigen::Index c = 0; c < k; ++c)
            dX.col(c) = (2.0 * l) * real_times(sp.M, X.col(c)) + real_times(sp.C, X.col(c));
        const Eigen::MatrixXcd D = Y.adjoint() * dX;
        const Eigen::FullPivLU<Eigen::MatrixXcd> dlu(D);
        if (!dlu.isInvertible()) continue;
        const Eigen::MatrixXcd Yb = Y * dlu.inverse().adjoint();
        for (Eigen::Index c = 0; c < k; ++c) modes[group[static_cast<size_t>(c)]].left = unit_vector(Yb.col(c));
    }
}

// A left vector that does not solve y^H P(lambda) = 0 gives no bound (infinite): dropped.
void drop_unsolving_left(std::vector<Mode>& modes, const Eigen::SparseMatrix<double>& Mt,
                         const Eigen::SparseMatrix<double>& Ct, const Eigen::SparseMatrix<double>& Kt,
                         const PencilAction& action, int n) {
    for (Mode& m : modes) {
        if (m.left.size() != n) continue;
        const cd l = std::conj(m.lambda);
        const Eigen::VectorXcd r = (l * l) * real_times(Mt, m.left) + l * real_times(Ct, m.left) + real_times(Kt, m.left);
        const double a = std::abs(m.lambda);
        if (!(r.norm() <= 1e-8 * (a * a * action.norm_M + a * action.norm_C + action.norm_K))) m.left.resize(0);
    }
}

// A refined pair of a real eigenvalue made real (the eigenvalue's real part, the
// vectors' real parts once unit_vector turned their largest entry real), kept only if
// it is still verified: next to an exceptional point dgeev's two real values may
// belong to a complex pair.
void make_real(Mode& m, const PencilAction& action, int n) {
    Mode r = m;
    r.lambda = cd(m.lambda.real(), 0.0);
    r.right = unit_vector(Eigen::VectorXcd(unit_vector(m.right).real().cast<cd>()));
    if (m.left.size() == n) r.left = unit_vector(Eigen::VectorXcd(unit_vector(m.left).real().cast<cd>()));
    r.backward_error = backward_error(action, r.lambda, r.right);
    if (r.backward_error <= kStateVerifyTolerance) m = std::move(r);
}

}  // namespace

QuadraticSpectrum state_matrix_eigenpairs(const QuadraticPencil& p) {
    const int n = static_cast<int>(p.M.rows());
    const PencilAction action = action_of(p);
    // Scaled as for QZ: DOF scaling T and the time scale g (lambda = g mu), so that
    // the state matrix of a fine FE model is not dominated by its highest modes.
    const Eigen::VectorXd t = dof_scaling(p);
    const double g = natural_scale(p);
    const Eigen::MatrixXd Ms = (g * g) * (t.asDiagonal() * p.M * t.asDiagonal());
    const Eigen::MatrixXd Cs = g * (t.asDiagonal() * p.C * t.asDiagonal());
    const Eigen::MatrixXd Ks = t.asDiagonal() * p.K * t.asDiagonal();
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Ms);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -lu.solve(Ks);
    A.bottomRightCorner(n, n) = -lu.solve(Cs);
    // A zero pivot can pass the condition estimate and leave infinities instead.
    if (!(lu.rcond() > 1e-14) || !A.allFinite()) {
        if (infinite_limit(p) > 0)
            throw SolverError("the state-matrix method needs an invertible M, and M is singular; "
                              "use the QZ method (" + option_field("method") + " qz)");
        // M itself is invertible: the scaling by stiffness leaves a DOF's mass at rounding.
        double ratio = 0.0;
        for (int i = 0; i < n; ++i)
            if (p.M(i, i) != 0.0) ratio = std::max(ratio, std::abs(p.K(i, i) / p.M(i, i)));
        throw SolverError(fmt::format(
            "the state-matrix method cannot resolve this pencil: M is invertible, but a DOF's stiffness over its "
            "mass ({:.3g} 1/s^2, a natural frequency of {:.3g} rad/s) is beyond double precision against the "
            "pencil's natural scale ({:.3g} rad/s), so the scaled M is singular to rounding (reciprocal "
            "condition {:.2g}); use the QZ method ({} qz), which solves such modes apart",
            ratio, std::sqrt(ratio), g, lu.rcond(), option_field("method")));
    }
    // A sparse (banded FE) pencil refines every pair with a cheap sparse LU, which also
    // gives its left vector; a dense one takes the left vectors from dgeev (a quarter
    // more QR time) and factorizes only where a pair is not at rounding level: n dense
    // LUs would cost O(n^4).
    const auto nonzeros = [](const Eigen::MatrixXd& X) { return (X.array() != 0.0).count(); };
    const bool sparse_pencil = nonzeros(p.M) + nonzeros(p.C) + nonzeros(p.K) < Eigen::Index(n) * n / 2;
    const GeneralizedEigen ev = lapack_dgeev(std::move(A), !sparse_pencil);   // right [x; mu x], left [u1; u2]
    const SparsePencil sp{p.M.sparseView(), p.C.sparseView(), p.K.sparseView()};
    const PencilAction sa = sparse_pencil_action(sp);
    QuadraticSpectrum s;
    s.scale = natural_scale(p);
    s.real_tol = 1e-7 * s.scale;
    std::vector<bool> raw_real;   // per mode: dgeev gave it a real eigenvalue
    for (int j = 0; j < 2 * n; ++j) {
        Mode m;
        m.lambda = g * ev.alpha(j);
        if (m.lambda.imag() < -1e-7 * std::max(std::abs(m.lambda), s.scale)) continue;
        // The better half (the top where |mu| > 1 loses to rounding less), unscaled.
        const Eigen::VectorXcd top = t.asDiagonal() * ev.right.col(j).head(n);
        const Eigen::VectorXcd bottom = t.asDiagonal() * ev.right.col(j).tail(n);
        const double et = backward_error(sa, m.lambda, top), eb = backward_error(sa, m.lambda, bottom);
        m.right = unit_vector(et <= eb ? top : bottom);
        m.backward_error = std::min(et, eb);
        // The quadratic's left vector from the state matrix's u = [u1; u2]: y = T M~^-T u2
        // (u^H A = mu u^H gives (M~^-T u2)^H P~(mu) = 0, and P~ = T P T).
        if (!sparse_pencil) {
            const Eigen::VectorXcd u2 = ev.left.col(j).tail(n);
            Eigen::VectorXcd y(n);
            y.real() = lu.transpose().solve(Eigen::VectorXd(u2.real()));
            y.imag() = lu.transpose().solve(Eigen::VectorXd(u2.imag()));
            m.left = unit_vector(t.asDiagonal() * y);
        }
        s.modes.push_back(std::move(m));
        raw_real.push_back(ev.alpha(j).imag() == 0.0);
    }
    // Pairs that are not at rounding level on the quadratic itself (the right or the left
    // vector) are refined there (one sparse LU of P near lambda: inverse iteration, the
    // two-sided Rayleigh quotient, a new left vector), as the sparse solver verifies its
    // pairs; the others need no factorization. The error bounds follow from both vectors.
    const Eigen::SparseMatrix<double> Mt = sp.M.transpose(), Ct = sp.C.transpose(), Kt = sp.K.transpose();
    const auto left_error = [&](const Mode& m) {
        const cd l = std::conj(m.lambda);
        const Eigen::VectorXcd r =
            (l * l) * real_times(Mt, m.left) + l * real_times(Ct, m.left) + real_times(Kt, m.left);
        const double a = std::abs(m.lambda);
        return r.norm() / ((a * a * sa.norm_M + a * sa.norm_C + sa.norm_K) * m.left.norm());
    };
    std::vector<Mode> raw = s.modes;
    for (Mode& m : s.modes)
        if (m.left.size() != n || !(m.backward_error <= kStateRoundingLevel) ||
            !(left_error(m) <= kStateRoundingLevel)) {
            // Aimed at the level QZ reaches: the bounds then match QZ's.
            refine_eigenpair(sp, sa, m, 1e-6 * kStateVerifyTolerance, s.scale);
            ++s.refined;
            // dgeev's real eigenvalue of the real state matrix (an overdamped mode) stays
            // real: the exact eigenvalue of a real pencil near a simple real one is real,
            // and the refinement's complex arithmetic only adds rounding to its imaginary
            // part (which would list it among the oscillating modes, as QZ does not).
            if (raw_real[static_cast<size_t>(&m - s.modes.data())]) make_real(m, sa, n);
        }
    keep_double_vectors(s.modes, raw, n);
    biorthogonalize_double_left(s.modes, sp, n);
    drop_unsolving_left(s.modes, Mt, Ct, Kt, action, n);
    return s;
}

}  // namespace gyrokit::dense
