// The pencil's scales, action and uncoupled DOF groups: what every dense stage
// (QZ, state matrix, eigenvalues alone, error bounds) measures the pencil by.
#include "gyrokit/eig/detail/dense_stages.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <memory>

namespace gyrokit::dense {

// The pencil's action: sparse where the matrices are (a finite-element pencil,
// a few entries per row: the residuals of hundreds of modes cost a fraction of
// the dense products), dense otherwise. The sparse copies live in the action.
PencilAction action_of(const QuadraticPencil& p) {
    const Eigen::Index n = p.M.rows();
    const auto nonzeros = [](const Eigen::MatrixXd& A) { return (A.array() != 0.0).count(); };
    if (n >= 32 && nonzeros(p.M) + nonzeros(p.C) + nonzeros(p.K) < n * n / 2) {
        const auto s = std::make_shared<const SparsePencil>(to_sparse(p));
        PencilAction a;
        a.apply = [s](const Eigen::VectorXcd& x, Eigen::VectorXcd& Mx, Eigen::VectorXcd& Cx, Eigen::VectorXcd& Kx) {
            Mx = real_times(s->M, x);
            Cx = real_times(s->C, x);
            Kx = real_times(s->K, x);
        };
        a.apply_abs_K = [s](const Eigen::VectorXd& v, Eigen::VectorXd& absKv) { absKv = s->K.cwiseAbs() * v; };
        a.apply_abs = [s](const Eigen::VectorXd& v, Eigen::VectorXd& Mv, Eigen::VectorXd& Cv, Eigen::VectorXd& Kv) {
            Mv = s->M.cwiseAbs() * v;
            Cv = s->C.cwiseAbs() * v;
            Kv = s->K.cwiseAbs() * v;
        };
        a.row_terms = pencil_row_terms(s->M, s->C, s->K);
        a.norm_M = p.M.norm();
        a.norm_C = p.C.norm();
        a.norm_K = p.K.norm();
        return a;
    }
    return pencil_action(p.M, p.C, p.K,
                         [](const Eigen::MatrixXd& A, const Eigen::VectorXcd& x) -> Eigen::VectorXcd { return A * x; });
}

double natural_scale(const QuadraticPencil& p) {
    return natural_frequency_scale(p.M.diagonal(), p.K.diagonal(), p.M.norm(), p.K.norm());
}

// Diagonal congruence z = T w with t_i = 1/sqrt(W_ii), W = g^2|M| + g|C| + |K|:
// undoes badly scaled units (metres next to micrometres) without changing the
// eigenvalues; the structure (symmetry, skew-symmetry) is kept.
Eigen::VectorXd dof_scaling(const QuadraticPencil& p) {
    const double g = natural_scale(p);
    Eigen::VectorXd t(p.M.rows());
    for (Eigen::Index i = 0; i < t.size(); ++i) {
        const double w = g * g * std::abs(p.M(i, i)) + g * std::abs(p.C(i, i)) + std::abs(p.K(i, i));
        t(i) = (w > 0.0 && std::isfinite(w)) ? 1.0 / std::sqrt(w) : 1.0;
    }
    return t / t.maxCoeff();
}

PencilNorms scaled_norms(const QuadraticPencil& p, const Eigen::VectorXd& t) {
    const Eigen::ArrayXXd tt = t * t.transpose();
    return {(p.M.array() * tt).matrix().norm(), (p.C.array() * tt).matrix().norm(), (p.K.array() * tt).matrix().norm()};
}

CompanionScaling companion_scaling(const QuadraticPencil& original) {
    CompanionScaling c;
    c.t = dof_scaling(original);
    const Eigen::VectorXd& t = c.t;
    const double nm = (t.asDiagonal() * original.M * t.asDiagonal()).norm(),
                 nc = (t.asDiagonal() * original.C * t.asDiagonal()).norm(),
                 nk = (t.asDiagonal() * original.K * t.asDiagonal()).norm();
    if (!(nm > 0.0))
        throw SolverError("the mass matrix M is zero (or not finite): a vibration problem needs mass; "
                          "allowed: M with at least one nonzero entry");
    c.gamma = (nk > 0.0) ? std::sqrt(nk / nm) : (nc > 0.0 ? nc / nm : 1.0);
    c.delta = 2.0 / (nk + nc * c.gamma + nm * c.gamma * c.gamma * (nk > 0.0 ? 0.0 : 1.0));
    return c;
}

// The companion form in a given scaling (a group of a pencil takes the whole's: the
// blocks of the whole's companion form, so that its rounding, down to the split of a
// rigid-body zero, is the whole's).
Companion companion(const QuadraticPencil& original, const CompanionScaling& scaling) {
    const Eigen::Index n = original.M.rows();
    Companion c;
    c.t = scaling.t;
    const Eigen::VectorXd& t = c.t;
    const QuadraticPencil p{t.asDiagonal() * original.M * t.asDiagonal(), t.asDiagonal() * original.C * t.asDiagonal(),
                            t.asDiagonal() * original.K * t.asDiagonal()};
    const double gamma = scaling.gamma, delta = scaling.delta;
    c.gamma = gamma;
    c.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    c.B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    c.A.topLeftCorner(n, n) = -(gamma * delta) * p.C;
    c.A.topRightCorner(n, n) = -delta * p.K;
    c.A.bottomLeftCorner(n, n).setIdentity();
    c.B.topLeftCorner(n, n) = (gamma * gamma * delta) * p.M;
    c.B.bottomRightCorner(n, n).setIdentity();
    return c;
}

Companion companion(const QuadraticPencil& original) { return companion(original, companion_scaling(original)); }

int infinite_limit(const QuadraticPencil& p) {
    const Eigen::Index n = p.M.rows();
    Eigen::VectorXd d(n);
    for (Eigen::Index i = 0; i < n; ++i) d(i) = p.M(i, i) != 0.0 ? 1.0 / std::sqrt(std::abs(p.M(i, i))) : 1.0;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(d.asDiagonal() * p.M * d.asDiagonal());
    qr.setThreshold(1e-12);   // a singular M is singular exactly (massless DOFs), not to rounding
    return static_cast<int>(n - qr.rank());
}

bool infinite(std::complex<double> alpha, double beta) {
    return std::abs(beta) <= 100.0 * std::numeric_limits<double>::epsilon() * std::abs(alpha) || beta == 0.0;
}

// The DOFs in groups that the pencil does not couple: the connected components of
// M's, C's and K's entries, each in increasing order (one group where all are
// coupled). A model with 6 DOFs per node whose axial and torsional DOFs couple with
// no lateral one (ROSS) has three. Empty where a group has no mass: such a pencil is
// solved whole.
std::vector<std::vector<Eigen::Index>> uncoupled_groups(const QuadraticPencil& p) {
    const Eigen::Index n = p.M.rows();
    std::vector<Eigen::Index> root(static_cast<size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) root[static_cast<size_t>(i)] = i;
    const auto find = [&](Eigen::Index i) {
        while (root[static_cast<size_t>(i)] != i) i = root[static_cast<size_t>(i)] = root[static_cast<size_t>(root[static_cast<size_t>(i)])];
        return i;
    };
    for (const Eigen::MatrixXd* A : {&p.M, &p.C, &p.K})
        for (Eigen::Index j = 0; j < n; ++j)
            for (Eigen::Index i = 0; i < n; ++i)
                if ((*A)(i, j) != 0.0) {
                    const Eigen::Index a = find(i), b = find(j);
                    if (a != b) root[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
                }
    std::vector<std::vector<Eigen::Index>> groups;
    std::vector<Eigen::Index> group_of(static_cast<size_t>(n), -1);
    for (Eigen::Index i = 0; i < n; ++i) {
        Eigen::Index& g = group_of[static_cast<size_t>(find(i))];
        if (g < 0) g = static_cast<Eigen::Index>(groups.size()), groups.emplace_back();
        groups[static_cast<size_t>(g)].push_back(i);
    }
    for (const auto& g : groups) {
        bool mass = false;
        for (const Eigen::Index i : g)
            for (const Eigen::Index j : g) mass = mass || p.M(i, j) != 0.0;
        if (!mass) return {};
    }
    return groups;
}

QuadraticPencil restricted(const QuadraticPencil& p, const std::vector<Eigen::Index>& g) {
    const auto sub = [&](const Eigen::MatrixXd& A) { return Eigen::MatrixXd(A(g, g)); };
    return {sub(p.M), sub(p.C), sub(p.K)};
}

}  // namespace gyrokit::dense
