#include <gyrokit/eig/mode.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/parallel.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

namespace gyrokit {

std::string to_string(Whirl w) {
    switch (w) {
        case Whirl::Forward: return "forward";
        case Whirl::Backward: return "backward";
        case Whirl::Real: return "real";
        case Whirl::Planar: return "planar";
        case Whirl::None: return "none";
        case Whirl::Undefined: break;
    }
    return "undefined";
}

std::string to_string(Stability s) {
    switch (s) {
        case Stability::Stable: return "stable";
        case Stability::Unstable: return "unstable";
        case Stability::Neutral: break;
    }
    return "neutral";
}

Stability Mode::stability() const {
    if (lambda.real() > error_bound) return Stability::Unstable;
    if (lambda.real() < -error_bound) return Stability::Stable;
    return Stability::Neutral;
}

double natural_frequency_scale(const Eigen::VectorXd& m_diag, const Eigen::VectorXd& k_diag, double norm_M,
                               double norm_K) {
    std::vector<double> ratios;
    for (Eigen::Index i = 0; i < m_diag.size() && i < k_diag.size(); ++i) {
        const double m = std::abs(m_diag(i)), k = std::abs(k_diag(i));
        if (m > 0.0 && k > 0.0 && std::isfinite(k / m)) ratios.push_back(k / m);
    }
    double g = 0.0;
    if (!ratios.empty()) {
        const auto mid = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
        std::nth_element(ratios.begin(), mid, ratios.end());
        g = std::sqrt(*mid);
    } else if (norm_M > 0.0 && norm_K > 0.0) {
        g = std::sqrt(norm_K / norm_M);
    }
    return std::isfinite(g) && g > 0.0 ? g : 1.0;
}

bool is_rigid_body(std::complex<double> lambda, const Eigen::VectorXcd& x, const PencilAction& pencil,
                   double scale) {
    if (!(std::abs(lambda) <= kRigidBodyTolerance * scale)) return false;
    Eigen::VectorXcd Mx, Cx, Kx;
    pencil.apply(x, Mx, Cx, Kx);
    if (!pencil.apply_abs_K) return Kx.norm() <= kRigidBodyTolerance * pencil.norm_K * x.norm();
    Eigen::VectorXd absKx;
    pencil.apply_abs_K(x.cwiseAbs(), absKx);
    return Kx.norm() <= kRigidBodyTolerance * absKx.norm();
}

std::pair<int, double> frequency_rank(const Mode& m) {
    return m.whirl == Whirl::Real ? std::pair{1, std::abs(m.lambda)} : std::pair{0, m.lambda.imag()};
}

void sort_by_frequency(std::vector<Mode>& modes) {
    std::stable_sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
        if (frequency_rank(a) != frequency_rank(b)) return frequency_rank(a) < frequency_rank(b);
        return a.lambda.real() < b.lambda.real();
    });
    // Real eigenvalues whose moduli agree to kTieTolerance (a pair +-a: one stable, one
    // divergent) by real part, not by the rounding of their moduli.
    const auto tied = [](const Mode& a, const Mode& b) {
        return std::abs(std::abs(a.lambda) - std::abs(b.lambda)) <= kTieTolerance * std::abs(b.lambda);
    };
    for (size_t i = 0; i < modes.size();) {
        size_t j = i + 1;
        if (modes[i].whirl == Whirl::Real)
            while (j < modes.size() && modes[j].whirl == Whirl::Real && tied(modes[j - 1], modes[j])) ++j;
        if (j - i > 1)
            std::stable_sort(modes.begin() + static_cast<std::ptrdiff_t>(i), modes.begin() + static_cast<std::ptrdiff_t>(j),
                             [](const Mode& a, const Mode& b) { return a.lambda.real() < b.lambda.real(); });
        i = j;
    }
}

double Mode::real_part() const {
    // An unknown bound (no left vector) vouches for nothing: the real part is shown as computed.
    return stability() == Stability::Neutral && std::isfinite(error_bound) ? 0.0 : lambda.real();
}

double Mode::damping_ratio() const {
    const double a = std::abs(lambda);
    return a == 0.0 ? 0.0 : 0.0 - real_part() / a;   // 0.0 - x: no negative zero in the output
}

double Mode::log_decrement() const {
    const double re = real_part();
    if (lambda.imag() > 0.0) return 0.0 - 2.0 * kPi * re / lambda.imag();   // no negative zero
    if (re == 0.0) return 0.0;
    return re < 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

Whirl classify_whirl(std::complex<double> lambda, const Eigen::VectorXcd& vector,
                     const std::vector<std::pair<int, int>>& pairs, double real_tol) {
    if (std::abs(lambda.imag()) <= real_tol) return Whirl::Real;
    if (pairs.empty()) return Whirl::Undefined;
    // Squared moduli below (no square root per entry); a vector whose squares would
    // underflow or overflow (entries beyond 1e+-154) is scaled to its largest entry first.
    const double top = vector.cwiseAbs2().maxCoeff();
    Eigen::VectorXcd rescaled;
    if (!(top >= std::numeric_limits<double>::min() && top <= std::numeric_limits<double>::max())) {
        const double largest = vector.cwiseAbs().maxCoeff();
        if (!(largest > 0.0) || !std::isfinite(largest)) return Whirl::None;
        rescaled = vector / largest;
    }
    const Eigen::VectorXcd& x = rescaled.size() > 0 ? rescaled : vector;
    double turn = 0.0, largest_turn = 0.0, largest_pair = 0.0, largest_pair_dof = 0.0;
    for (const auto& [u, v] : pairs) {
        const double t = (x(u) * std::conj(x(v))).imag();
        turn += t;
        largest_turn = std::max(largest_turn, std::abs(t));
        largest_pair = std::max(largest_pair, 0.5 * (std::norm(x(u)) + std::norm(x(v))));
        largest_pair_dof = std::max({largest_pair_dof, std::norm(x(u)), std::norm(x(v))});
    }
    // The largest pair DOF against the largest DOF.
    const double all = rescaled.size() > 0 ? x.cwiseAbs2().maxCoeff() : top;
    if (largest_pair_dof <= kWhirlTolerance * kWhirlTolerance * all) return Whirl::None;
    if (largest_turn <= kWhirlTolerance * largest_pair) return Whirl::Planar;
    if (lambda.imag() < 0.0) turn = -turn;  // the conjugate pair turns the other way
    return turn >= 0.0 ? Whirl::Forward : Whirl::Backward;
}

namespace {

// H x for the Hermitian form x^H H x = sum over the pairs of Im(x_u conj(x_v)).
Eigen::VectorXcd whirl_form(const Eigen::VectorXcd& x, const std::vector<std::pair<int, int>>& pairs) {
    const std::complex<double> half_i(0.0, 0.5);
    Eigen::VectorXcd y = Eigen::VectorXcd::Zero(x.size());
    for (const auto& [u, v] : pairs) {
        y(u) += half_i * x(v);
        y(v) -= half_i * x(u);
    }
    return y;
}

// What the separation needs to know of an eigenpair: its residual on the
// mode's own scale, its backward error, and its Rayleigh-quotient refinement.
struct PairCheck {
    double local = 0.0, normwise = 0.0;
    std::complex<double> refined;
};

PairCheck check(const PencilAction& p, std::complex<double> l, const Eigen::VectorXcd& x) {
    Eigen::VectorXcd Mx, Cx, Kx;
    p.apply(x, Mx, Cx, Kx);
    const Eigen::VectorXcd r = (l * l) * Mx + l * Cx + Kx;
    const double a = std::abs(l), own = a * a * Mx.norm() + a * Cx.norm() + Kx.norm();
    const double whole = (a * a * p.norm_M + a * p.norm_C + p.norm_K) * x.norm();
    const std::complex<double> slope = x.dot((2.0 * l) * Mx + Cx);
    PairCheck c;
    c.local = own > 0.0 ? r.norm() / own : 0.0;
    c.normwise = whole > 0.0 ? r.norm() / whole : 0.0;
    c.refined = std::abs(slope) > 0.0 ? l - x.dot(r) / slope : l;
    return c;
}

// Turns modes a and b (the lower one first) into their most backward and most
// forward combination if they are a double eigenvalue to working accuracy.
void separate_pair(Mode& a, Mode& b, const std::vector<std::pair<int, int>>& pairs, const PencilAction& pencil) {
    const PairCheck ca = check(pencil, a.lambda, a.right), cb = check(pencil, b.lambda, b.right);
    if (!(std::abs(ca.refined - cb.refined) <= 1e-10 * std::abs(ca.refined))) return;   // split
    Eigen::MatrixXcd V(a.right.size(), 2);
    V.col(0) = a.right;
    V.col(1) = b.right;
    const Eigen::Matrix2cd G = V.adjoint() * V;
    if (G.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() < 1e-6 * G.trace().real()) return;   // one direction
    Eigen::MatrixXcd HV(V.rows(), 2);
    HV.col(0) = whirl_form(V.col(0), pairs);
    HV.col(1) = whirl_form(V.col(1), pairs);
    Eigen::Matrix2cd A = V.adjoint() * HV;
    A = 0.5 * (A + A.adjoint()).eval();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2cd> es(A, G);
    if (es.info() != Eigen::Success) return;
    const Eigen::Vector2d mu = es.eigenvalues();   // ascending: backward, forward
    if (!(mu(1) - mu(0) > 1e-8)) return;           // no whirl content to separate
    const Eigen::VectorXcd backward = unit_vector(V * es.eigenvectors().col(0));
    const Eigen::VectorXcd forward = unit_vector(V * es.eigenvectors().col(1));
    const PairCheck na = check(pencil, a.lambda, backward), nb = check(pencil, b.lambda, forward);
    const double eps = std::numeric_limits<double>::epsilon();
    if (!(std::max(na.local, nb.local) <= 10.0 * std::max({ca.local, cb.local, eps}))) return;
    a.right = backward;
    b.right = forward;
    a.backward_error = na.normwise;
    b.backward_error = nb.normwise;
}

// Lists the lower first: by frequency, then by real part.
bool lower(const Mode& a, const Mode& b) {
    return a.lambda.imag() != b.lambda.imag() ? a.lambda.imag() < b.lambda.imag() : a.lambda.real() < b.lambda.real();
}

}  // namespace

double backward_error(const PencilAction& p, std::complex<double> lambda, const Eigen::VectorXcd& x) {
    return check(p, lambda, x).normwise;
}

Eigen::VectorXcd unit_vector(const Eigen::VectorXcd& v) {
    if (v.size() == 0) return v;
    // The first entry within kTieTolerance of the largest: a tie is not left to rounding.
    // Squared moduli (no square root per entry), moduli where the squares would underflow.
    Eigen::Index k = 0;
    if (const double top = v.cwiseAbs2().maxCoeff(); top >= std::numeric_limits<double>::min()) {
        const double tie = (1.0 - kTieTolerance) * (1.0 - kTieTolerance);
        while (k + 1 < v.size() && std::norm(v(k)) < tie * top) ++k;
    } else {
        const double largest = v.cwiseAbs().maxCoeff();
        while (k + 1 < v.size() && std::abs(v(k)) < (1.0 - kTieTolerance) * largest) ++k;
    }
    const double size = std::abs(v(k));
    if (!(size > 0.0) || !std::isfinite(size)) return v;
    // Entry k made real and positive and of modulus 1 first, so that the norm neither
    // underflows nor overflows.
    const Eigen::VectorXcd w = (v * (std::conj(v(k)) / size)) / size;
    return w / w.norm();
}

void separate_double_whirl(std::vector<Mode>& modes, const std::vector<std::pair<int, int>>& pairs,
                           double real_tol, const PencilAction& pencil) {
    if (pairs.empty()) return;
    const std::size_t n = modes.size();
    const auto oscillating = [&](std::size_t i) { return std::abs(modes[i].lambda.imag()) > real_tol; };
    const auto close = [&](std::size_t i, std::size_t j) {
        return std::abs(modes[i].lambda - modes[j].lambda) <= 1e-6 * std::abs(modes[i].lambda);
    };
    const auto neighbours = [&](std::size_t i, std::size_t& last) {
        std::size_t count = 0;
        for (std::size_t j = 0; j < n; ++j)
            if (j != i && oscillating(j) && close(i, j)) {
                last = j;
                ++count;
            }
        return count;
    };
    for (std::size_t i = 0; i < n; ++i) {
        if (!oscillating(i)) continue;
        // Exactly one other oscillating mode that close, and i its only one: a double, not a cluster.
        std::size_t partner = n, back = n;
        if (neighbours(i, partner) != 1 || partner < i || neighbours(partner, back) != 1) continue;
        // The lower first; on an exact tie the one listed first (i < partner).
        Mode& a = lower(modes[partner], modes[i]) ? modes[partner] : modes[i];
        Mode& b = &a == &modes[i] ? modes[partner] : modes[i];
        separate_pair(a, b, pairs, pencil);
        a.whirl = classify_whirl(a.lambda, a.right, pairs, real_tol);
        b.whirl = classify_whirl(b.lambda, b.right, pairs, real_tol);
    }
}

namespace {

// Mode i's cluster (below): the right and left vectors, original coordinates, and
// what the bound needs of their products: D = Y^H P'(l) X and mode i's residual r.
struct Cluster {
    Eigen::MatrixXcd x, y;
    Eigen::MatrixXcd D;
    Eigen::VectorXcd r;
    Eigen::Index self = 0;   // mode i's column
};

// The first-order bound of mode i (set_error_bounds) in the coordinates x = T^-1 x_original
// of the pencil T P T, whose norms are `norms` (t = 1: the original pencil). The unit
// vectors there are x_j / t s_j with s_j = 1 / |x_j / t| (y likewise), and since
// T P T (x / t) = t (P x): Y^H P'(l) X = diag(s_y) D diag(s_x) and P(l) x_i = s_i t r,
// |X|'s square the largest eigenvalue of diag(s_x) X^H T^-2 X diag(s_x).
double error_bound_in(const Cluster& c, std::complex<double> l, const PencilNorms& norms, const Eigen::VectorXd& t) {
    const Eigen::Index k = c.x.cols();
    const Eigen::ArrayXd w = t.array().inverse().square();
    Eigen::VectorXd sx(k), sy(k);
    for (Eigen::Index j = 0; j < k; ++j) {
        sx(j) = 1.0 / std::sqrt((c.x.col(j).array().abs2() * w).sum());
        sy(j) = 1.0 / std::sqrt((c.y.col(j).array().abs2() * w).sum());
    }
    const double a = std::abs(l), whole = a * a * norms.M + a * norms.C + norms.K;
    const double eta = whole > 0.0 ? sx(c.self) * (c.r.array() * t.array()).matrix().norm() / whole : 0.0;
    const Eigen::MatrixXcd S = sy.asDiagonal() * c.D * sx.asDiagonal();
    // The largest singular value of the unit columns (1 for one column).
    const auto largest = [&](const Eigen::MatrixXcd& V, const Eigen::VectorXd& s) {
        if (k == 1) return 1.0;
        const Eigen::MatrixXcd gram = s.asDiagonal() * (V.adjoint() * (w.matrix().asDiagonal() * V)) * s.asDiagonal();
        return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd>(gram, Eigen::EigenvaluesOnly).eigenvalues()(k - 1));
    };
    const double smin = k == 1 ? std::abs(S(0, 0)) : Eigen::JacobiSVD<Eigen::MatrixXcd>(S).singularValues()(k - 1);
    const double eps = std::numeric_limits<double>::epsilon();
    return smin > 0.0 && std::isfinite(eta)
               ? 10.0 * std::max(eta, eps) * whole * largest(c.x, sx) * largest(c.y, sy) / smin
               : std::numeric_limits<double>::infinity();
}

// Mode i's cluster: every mode with a left vector within 1e-6 relative of its
// eigenvalue (a double eigenvalue's plane, whose computed bases need not pair up).
Cluster cluster_of(const std::vector<Mode>& modes, size_t i, const PencilAction& pencil) {
    const Mode& m = modes[i];
    const std::complex<double> l = m.lambda;
    std::vector<size_t> members;
    for (size_t j = 0; j < modes.size(); ++j)
        if (modes[j].left.size() == m.right.size() && std::abs(modes[j].lambda - l) <= 1e-6 * std::abs(l))
            members.push_back(j);
    const Eigen::Index n = m.right.size(), k = static_cast<Eigen::Index>(members.size());
    Cluster c{Eigen::MatrixXcd(n, k), Eigen::MatrixXcd(n, k), Eigen::MatrixXcd(k, k), Eigen::VectorXcd()};
    for (Eigen::Index j = 0; j < k; ++j) {
        const Mode& o = modes[members[static_cast<size_t>(j)]];
        c.x.col(j) = o.right;
        c.y.col(j) = o.left;
    }
    Eigen::VectorXcd Mx, Cx, Kx;
    for (Eigen::Index j = 0; j < k; ++j) {
        pencil.apply(c.x.col(j), Mx, Cx, Kx);
        c.D.col(j) = c.y.adjoint() * ((2.0 * l) * Mx + Cx);
        if (members[static_cast<size_t>(j)] == i) {
            c.self = j;
            c.r = (l * l) * Mx + l * Cx + Kx;
        }
    }
    return c;
}

// Whether mode i's cluster (cluster_of) is itself alone.
bool alone(const std::vector<Mode>& modes, size_t i) {
    const std::complex<double> l = modes[i].lambda;
    for (size_t j = 0; j < modes.size(); ++j)
        if (j != i && modes[j].left.size() == modes[i].right.size() && std::abs(modes[j].lambda - l) <= 1e-6 * std::abs(l))
            return false;
    return true;
}

// The componentwise first-order bound of a lone mode (Tisseur 2000): (lambda, x) is an
// exact eigenpair of a pencil whose every entry moved by at most the relative amount
//   omega = max_i |r_i| / (E |x|)_i,   E = |l|^2 |M| + |l| |C| + |K|,
// and such a perturbation moves the eigenvalue by at most omega |y|^T E |x| / |y^H P'(l) x|
// to first order. The computed r carries rounding up to (terms + 3) eps (E |x|)_i per
// entry (terms: the row's products), which omega adds; twice the sum covers the second
// order of a lone eigenvalue, eps |l| its own rounding. Entries are perturbed relative to
// themselves, so the bound does not grow with the stiffest entry of K as the normwise
// one does (a fine mesh, a stiff support): only the rows a mode moves count. Infinite
// where a row with no scale has a residual, or the action cannot take |M|, |C|, |K|.
double componentwise_bound(const Mode& m, const Eigen::VectorXcd& r, std::complex<double> D,
                           const PencilAction& pencil) {
    const double inf = std::numeric_limits<double>::infinity();
    if (!pencil.apply_abs || !(std::abs(D) > 0.0)) return inf;
    const double a = std::abs(m.lambda), eps = std::numeric_limits<double>::epsilon();
    Eigen::VectorXd Ma, Ca, Ka;
    pencil.apply_abs(m.right.cwiseAbs(), Ma, Ca, Ka);
    const Eigen::VectorXd scale = (a * a) * Ma + a * Ca + Ka;
    double omega = 0.0;
    for (Eigen::Index i = 0; i < r.size(); ++i) {
        const double ri = std::abs(r[i]);
        if (ri == 0.0) continue;
        if (!(scale[i] > 0.0) || !std::isfinite(ri / scale[i])) return inf;
        omega = std::max(omega, ri / scale[i]);
    }
    const double gamma = (pencil.row_terms + 3.0) * eps;
    const double kappa = m.left.cwiseAbs().dot(scale) / std::abs(D);
    const double b = 2.0 * (omega + gamma) * kappa + eps * a;
    return std::isfinite(b) ? b : inf;
}

// error_bound_in for a cluster of one, both pencils at once, as sums (the bounds of
// every mode at every step of a continuation come this way).
double lone_bound(const Mode& m, const PencilAction& pencil, const PencilNorms& original, const PencilNorms& scaled,
                  const Eigen::VectorXd& t) {
    const std::complex<double> l = m.lambda;
    Eigen::VectorXcd Mx, Cx, Kx;
    pencil.apply(m.right, Mx, Cx, Kx);
    const Eigen::VectorXcd r = (l * l) * Mx + l * Cx + Kx;
    const std::complex<double> D = m.left.dot((2.0 * l) * Mx + Cx);   // y^H P'(l) x
    double xx = 0.0, yy = 0.0, rr = 0.0, xw = 0.0, yw = 0.0, rt = 0.0;   // plain and weighted squares
    for (Eigen::Index j = 0; j < r.size(); ++j) {
        const double w = 1.0 / (t[j] * t[j]);
        const double ax = std::norm(m.right[j]), ay = std::norm(m.left[j]), ar = std::norm(r[j]);
        xx += ax, yy += ay, rr += ar;
        xw += ax * w, yw += ay * w, rt += ar * t[j] * t[j];
    }
    const double a = std::abs(l), eps = std::numeric_limits<double>::epsilon();
    const auto bound = [&](const PencilNorms& n, double x2, double y2, double r2) {
        const double whole = a * a * n.M + a * n.C + n.K;
        const double sx = 1.0 / std::sqrt(x2), sy = 1.0 / std::sqrt(y2);
        const double eta = whole > 0.0 ? sx * std::sqrt(r2) / whole : 0.0;
        const double smin = std::abs(sy * D * sx);
        return smin > 0.0 && std::isfinite(eta) ? 10.0 * std::max(eta, eps) * whole / smin
                                                : std::numeric_limits<double>::infinity();
    };
    return std::min({bound(original, xx, yy, rr), bound(scaled, xw, yw, rt), componentwise_bound(m, r, D, pencil)});
}

}  // namespace

void set_error_bounds(std::vector<Mode>& modes, const PencilAction& pencil, const PencilNorms& scaled,
                      const Eigen::VectorXd& t, int threads) {
    const Eigen::VectorXd one = Eigen::VectorXd::Ones(t.size());
    const PencilNorms original{pencil.norm_M, pencil.norm_C, pencil.norm_K};
    std::vector<double> bound(modes.size(), std::numeric_limits<double>::infinity());
    // The bounds first (each reads every mode), then stored.
    for_each_index(modes.size(), threads, [&](size_t i) {
        const Mode& m = modes[i];
        if (m.left.size() != m.right.size() || !std::isfinite(std::abs(m.lambda))) return;
        // Both are bounds on the same eigenvalue: the tighter one is kept.
        if (alone(modes, i)) {
            bound[i] = lone_bound(m, pencil, original, scaled, t);
            return;
        }
        const Cluster c = cluster_of(modes, i, pencil);
        bound[i] = std::min(error_bound_in(c, m.lambda, original, one), error_bound_in(c, m.lambda, scaled, t));
    });
    for (size_t i = 0; i < modes.size(); ++i) modes[i].error_bound = bound[i];
}

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
    const double na = a.squaredNorm(), nb = b.squaredNorm();
    if (na == 0.0 || nb == 0.0) return 0.0;
    return std::norm(a.dot(b)) / (na * nb);
}

}  // namespace gyrokit
