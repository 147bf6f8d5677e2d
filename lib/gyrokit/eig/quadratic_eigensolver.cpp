#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <gyrokit/core/error.hpp>
#include "gyrokit/eig/lapack.hpp"
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <optional>

namespace gyrokit {

using cd = std::complex<double>;

EigenMethod parse_eigen_method(const std::string& name) {
    if (name == "qz") return EigenMethod::ScaledQZ;
    if (name == "qz-classic") return EigenMethod::ClassicQZ;
    if (name == "state") return EigenMethod::StateMatrix;
    throw InputError(fmt::format("eigen method '{}' is unknown; allowed: qz, qz-classic, state", name));
}

std::string to_string(EigenMethod m) {
    switch (m) {
    case EigenMethod::ScaledQZ: return "qz";
    case EigenMethod::ClassicQZ: return "qz-classic";
    case EigenMethod::StateMatrix: break;
    }
    return "state";
}

void split_rigid_body(std::vector<Mode>& modes, std::vector<Mode>& rigid_body, const PencilAction& pencil,
                      double scale) {
    std::vector<Mode> kept;
    for (auto& m : modes) (is_rigid_body(m.lambda, m.right, pencil, scale) ? rigid_body : kept).push_back(std::move(m));
    modes = std::move(kept);
}

double QuadraticSpectrum::max_backward_error() const {
    double e = 0.0;
    for (const auto& m : modes) e = std::max(e, m.backward_error);
    return e;
}

namespace {

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
        a.norm_M = p.M.norm();
        a.norm_C = p.C.norm();
        a.norm_K = p.K.norm();
        return a;
    }
    return pencil_action(p.M, p.C, p.K,
                         [](const Eigen::MatrixXd& A, const Eigen::VectorXcd& x) -> Eigen::VectorXcd { return A * x; });
}

}  // namespace

double backward_error(const QuadraticPencil& p, cd lambda, const Eigen::VectorXcd& x) {
    return backward_error(action_of(p), lambda, x);
}

namespace {

double natural_scale(const QuadraticPencil& p) {
    return natural_frequency_scale(p.M.diagonal(), p.K.diagonal(), p.M.norm(), p.K.norm());
}

Eigen::VectorXd dof_scaling(const QuadraticPencil& p);

// Keeps the upper half plane and the real axis, sets the error bounds, puts
// the rigid-body eigenvalues apart, classifies and sorts.
void finish(QuadraticSpectrum& s, const QuadraticPencil& p, const std::vector<std::pair<int, int>>& pairs,
            bool keep_left) {
    std::vector<Mode> kept;
    for (auto& m : s.modes) {
        if (std::abs(m.lambda) <= s.real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        if (m.lambda.imag() < -s.real_tol) continue;
        m.whirl = classify_whirl(m.lambda, m.right, pairs, s.real_tol);
        kept.push_back(std::move(m));
    }
    const PencilAction action = action_of(p);
    // Bounds on the DOF-scaled pencil (as QZ solves it): stiff supports do not inflate them.
    const Eigen::VectorXd t = dof_scaling(p);
    const Eigen::ArrayXXd tt = t * t.transpose();
    const PencilNorms scaled{(p.M.array() * tt).matrix().norm(), (p.C.array() * tt).matrix().norm(),
                             (p.K.array() * tt).matrix().norm()};
    set_error_bounds(kept, action, scaled, t);
    if (!keep_left)
        for (auto& m : kept) m.left.resize(0);
    split_rigid_body(kept, s.rigid_body, action, s.scale);
    separate_double_whirl(kept, pairs, s.real_tol, action);
    sort_by_frequency(kept);
    s.modes = std::move(kept);
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

// The scaled first companion form of a pencil: A - mu B with lambda = gamma mu, in
// the coordinates x = T^-1 x_original (t = dof_scaling), eigenvector [mu x; x].
struct Companion {
    Eigen::VectorXd t;
    double gamma = 1.0;
    Eigen::MatrixXd A, B;
};

// The scaling of the companion form: DOF scaling t, then lambda = gamma mu and the
// coefficients times delta (Fan-Lin-Van Dooren: norms about one).
struct CompanionScaling {
    Eigen::VectorXd t;
    double gamma = 1.0, delta = 1.0;
};

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

// Whether QZ's alpha / beta is an infinite eigenvalue (singular M).
bool infinite(std::complex<double> alpha, double beta) {
    return std::abs(beta) <= 100.0 * std::numeric_limits<double>::epsilon() * std::abs(alpha) || beta == 0.0;
}

// `scaling` and `scale`: a group's, the whole pencil's (solve_qz_by_groups).
QuadraticSpectrum solve_qz(const QuadraticPencil& original, bool want_left, bool classic,
                           const CompanionScaling* scaling = nullptr, double scale = 0.0) {
    const int n = static_cast<int>(original.M.rows());
    const PencilAction action = action_of(original);   // backward errors refer to the original problem
    Companion c = scaling ? companion(original, *scaling) : companion(original);
    const Eigen::VectorXd& t = c.t;
    const double gamma = c.gamma;
    GeneralizedEigen ge = lapack_dggev(std::move(c.A), std::move(c.B), want_left, classic);

    QuadraticSpectrum s;
    s.scale = scale > 0.0 ? scale : natural_scale(original);
    s.real_tol = 1e-7 * s.scale;   // about sqrt(eps) times the scale: rigid-body pairs land here
    for (int j = 0; j < 2 * n; ++j) {
        const cd alpha = ge.alpha(j);
        const double beta = ge.beta(j);
        if (infinite(alpha, beta)) {
            ++s.infinite_count;
            continue;
        }
        Mode m;
        m.lambda = gamma * alpha / beta;
        if (m.lambda.imag() < -1e-7 * std::max(std::abs(m.lambda), s.scale)) continue;  // conjugate
        // Either block of [mu x; x] gives x; keep the one with the smaller backward error.
        // Back to the original coordinates; backward errors refer to the original problem.
        const Eigen::VectorXcd top = t.asDiagonal() * ge.right.col(j).head(n);
        const Eigen::VectorXcd bottom = t.asDiagonal() * ge.right.col(j).tail(n);
        const double et = backward_error(action, m.lambda, top), eb = backward_error(action, m.lambda, bottom);
        const bool use_top = top.norm() > 0.0 && (bottom.norm() == 0.0 || et < eb);
        m.right = unit_vector(use_top ? top : bottom);
        m.backward_error = backward_error(action, m.lambda, m.right);
        if (want_left) m.left = unit_vector(t.asDiagonal() * ge.left.col(j).head(n));
        s.modes.push_back(std::move(m));
    }
    return s;
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

// solve_qz on each uncoupled group (the QZ's cost is cubic in the size: ROSS's
// 42 DOFs as groups of 28, 7 and 7 cost a third), the vectors zero outside their
// group, backward errors on the whole pencil; as solve_qz where all are coupled.
QuadraticSpectrum solve_qz_by_groups(const QuadraticPencil& p, bool want_left, bool classic) {
    const std::vector<std::vector<Eigen::Index>> groups = uncoupled_groups(p);
    if (groups.size() <= 1) return solve_qz(p, want_left, classic);
    const Eigen::Index n = p.M.rows();
    const PencilAction action = action_of(p);
    QuadraticSpectrum s;
    s.scale = natural_scale(p);
    s.real_tol = 1e-7 * s.scale;
    const CompanionScaling whole = companion_scaling(p);
    for (const std::vector<Eigen::Index>& g : groups) {
        CompanionScaling own = whole;
        own.t = Eigen::VectorXd(whole.t(g));
        QuadraticSpectrum part = solve_qz(restricted(p, g), want_left, classic, &own, s.scale);
        s.infinite_count += part.infinite_count;
        for (Mode& m : part.modes) {
            Eigen::VectorXcd x = Eigen::VectorXcd::Zero(n), y = Eigen::VectorXcd::Zero(want_left ? n : 0);
            for (size_t k = 0; k < g.size(); ++k) {
                x[g[k]] = m.right[static_cast<Eigen::Index>(k)];
                if (want_left) y[g[k]] = m.left[static_cast<Eigen::Index>(k)];
            }
            m.right = std::move(x);
            m.left = std::move(y);
            m.backward_error = backward_error(action, m.lambda, m.right);
            s.modes.push_back(std::move(m));
        }
    }
    return s;
}

// The state-matrix pairs are refined towards this backward error (the sparse
// solver's verification tolerance).
constexpr double kStateVerifyTolerance = 1e-10;
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

QuadraticSpectrum solve_state(const QuadraticPencil& p) {
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
    if (!(lu.rcond() > 1e-14) || !A.allFinite())
        throw SolverError("the state-matrix method needs an invertible M, and M is singular; "
                          "use the QZ method (" + option_field("method") + " qz)");
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
        }
    keep_double_vectors(s.modes, raw, n);
    biorthogonalize_double_left(s.modes, sp, n);
    drop_unsolving_left(s.modes, Mt, Ct, Kt, action, n);
    return s;
}

}  // namespace

QuadraticSpectrum solve_quadratic(const QuadraticPencil& p, const EigenOptions& opt,
                                  const std::vector<std::pair<int, int>>& whirl_pairs) {
    if (!p.M.allFinite() || !p.C.allFinite() || !p.K.allFinite())
        throw InputError("the pencil has a NaN or infinite coefficient");
    QuadraticSpectrum s;
    // Both methods compute left vectors: they give every eigenvalue its error bound.
    const bool qz = opt.method != EigenMethod::StateMatrix;
    s = qz ? solve_qz_by_groups(p, true, opt.method == EigenMethod::ClassicQZ) : solve_state(p);
    s.method = opt.method == EigenMethod::ScaledQZ    ? "scaled QZ"
               : opt.method == EigenMethod::ClassicQZ ? "scaled classic QZ"
                                                      : "state matrix";
    // An answer QZ cannot stand behind is no answer: every eigenvalue infinite for an
    // M that is not zero, or a pair far from any eigenpair (QZ's are about 1e-15), happen
    // only where the pencil's scales span more than double precision resolves (a speed
    // of 1e150 rad/s on a rotor whose |K| is 1e4). The state-matrix method says instead
    // which eigenvalues it cannot vouch for.
    if (qz) {
        double worst = 0.0;
        for (const Mode& m : s.modes) worst = std::max(worst, m.backward_error);
        const bool all_infinite = s.modes.empty() && s.infinite_count > 0 && p.M.norm() > 0.0;
        // How far the damping-gyroscopic term outweighs the balance of mass and stiffness
        // at the natural frequency g: beyond 1e12 (1e150 rad/s on a rotor) no scaling
        // brings the terms to one level, and a pair with a large backward error is
        // rounding, not a mode. A small term (light damping, a liquid's tiny masses)
        // is no such case: its pairs stay, with bounds that say what they are worth.
        const double g = s.scale;
        const double spread = g * p.C.norm() / (g * g * p.M.norm() + p.K.norm());
        if (all_infinite || !std::isfinite(spread) || (spread > 1e12 && !(worst <= kDenseVerifyTolerance)))
            throw SolverError(fmt::format(
                "the eigensolver cannot vouch for this pencil: {}; its coefficients span more than double precision "
                "resolves (|M| = {:.3g}, |C| = {:.3g}, |K| = {:.3g}); allowed: speeds and parameters whose pencil "
                "stays within about 1e12 of its natural scale",
                all_infinite ? fmt::format("all {} eigenvalues came out infinite", s.infinite_count)
                             : fmt::format("an eigenpair with backward error {:.2g}, above {:.0e}", worst,
                                           kDenseVerifyTolerance),
                p.M.norm(), p.C.norm(), p.K.norm()));
    }
    finish(s, p, whirl_pairs, opt.left_vectors);
    // A printed eigenvalue lies within its printed bound; one whose bound exceeds
    // 1e-6 of its modulus (and the real-axis tolerance) is not vouched for: said.
    const auto loose = std::count_if(s.modes.begin(), s.modes.end(), [&](const Mode& m) {
        return !(m.error_bound <= std::max(kVouchTolerance * std::abs(m.lambda), s.real_tol));
    });
    if (loose > 0)
        s.notes.push_back(fmt::format("{} of {} eigenvalues have an error bound above {} of their modulus: the {} "
                                      "method cannot vouch for them{}",
                                      loose, s.modes.size(), kVouchTolerance, s.method,
                                      opt.method == EigenMethod::StateMatrix ? "; use the QZ method (" + option_field("method") + " qz)"
                                                                             : " (see the error_bound column)"));
    return s;
}

namespace {

// The eigenvalues from the state matrix where M is positive definite and well
// conditioned: with T M T = L L^T (t = dof_scaling) and z = L^T x / t, the matrix
// [0, I; -L^-1 K L^-T / g^2, -L^-1 C L^-T / g] in mu = lambda / g (g the natural scale),
// whose QR without vectors costs about 60 % of the QZ's (ROSS's 42 DOFs: 1.4 against
// 2.4 ms). Empty where M is not symmetric positive definite with an estimated
// reciprocal condition above 1e-8 (then QZ): a badly conditioned M would cost the
// small eigenvalues their accuracy.
std::optional<Eigen::VectorXcd> state_matrix_values(const QuadraticPencil& original, double g,
                                                    const Eigen::VectorXd* scaling = nullptr) {
    const Eigen::Index n = original.M.rows();
    const Eigen::VectorXd t = scaling ? *scaling : dof_scaling(original);
    const Eigen::MatrixXd M = t.asDiagonal() * original.M * t.asDiagonal();
    if (!(original.M == original.M.transpose())) return std::nullopt;   // LLT reads one triangle
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success || !(llt.rcond() > 1e-8)) return std::nullopt;
    const auto congruent = [&](const Eigen::MatrixXd& X) {   // L^-1 T X T L^-T
        Eigen::MatrixXd Y = llt.matrixL().solve(t.asDiagonal() * X * t.asDiagonal());
        return Eigen::MatrixXd(llt.matrixL().solve(Y.transpose()).transpose());
    };
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -congruent(original.K) / (g * g);
    A.bottomRightCorner(n, n) = -congruent(original.C) / g;
    return Eigen::VectorXcd(g * lapack_dgeev_values(std::move(A)));
}

// Every finite eigenvalue of p to `keep`: the state matrix where M allows, else QZ.
// `scaling`: a group's, the whole pencil's (as solve_qz_by_groups).
template <class Keep>
void all_eigenvalues(const QuadraticPencil& p, double g, const Keep& keep, const CompanionScaling* scaling = nullptr) {
    if (const std::optional<Eigen::VectorXcd> values = state_matrix_values(p, g, scaling ? &scaling->t : nullptr)) {
        for (const cd l : *values) keep(l);
        return;
    }
    Companion c = scaling ? companion(p, *scaling) : companion(p);
    // Without vectors the classic QZ is the faster up to about 400 DOFs (ROSS's 42:
    // 2.4 against 4.1 ms; 100: 21 against 32 ms; 336: 0.77 against 0.81 s).
    const bool classic = p.M.rows() <= kClassicValuesLimit;
    const GeneralizedEigen ge = lapack_dggev_values(std::move(c.A), std::move(c.B), classic);
    for (Eigen::Index j = 0; j < ge.alpha.size(); ++j)
        if (!infinite(ge.alpha(j), ge.beta(j))) keep(c.gamma * ge.alpha(j) / ge.beta(j));
}

}  // namespace

EigenvalueSet quadratic_eigenvalues(const QuadraticPencil& p) {
    if (!p.M.allFinite() || !p.C.allFinite() || !p.K.allFinite())
        throw InputError("the pencil has a NaN or infinite coefficient");
    EigenvalueSet e;
    e.scale = natural_scale(p);
    e.real_tol = 1e-7 * e.scale;   // as solve_qz
    const auto keep = [&](cd l) {   // the upper half plane and the real axis, as the full solve keeps them
        if (l.imag() >= -e.real_tol) e.values.push_back(l);
    };
    // Each uncoupled group on its own (as solve_qz_by_groups), scaled by the whole's scale.
    const std::vector<std::vector<Eigen::Index>> groups = uncoupled_groups(p);
    if (groups.size() > 1) {
        const CompanionScaling whole = companion_scaling(p);
        for (const std::vector<Eigen::Index>& g : groups) {
            CompanionScaling own = whole;
            own.t = Eigen::VectorXd(whole.t(g));
            all_eigenvalues(restricted(p, g), e.scale, keep, &own);
        }
        return e;
    }
    all_eigenvalues(p, e.scale, keep);
    return e;
}

QuadraticSpectrum solve_at_speed(const GyroscopicSystem& sys, double w, const EigenOptions& opt) {
    return solve_quadratic(sys.at_speed(w), opt, sys.whirl_pairs);
}

}  // namespace gyrokit
