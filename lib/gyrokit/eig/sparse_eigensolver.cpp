#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/detail/arpack_ritz.hpp>
#include <gyrokit/eig/detail/pencil_lu.hpp>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>

namespace gyrokit {

// One pass over A's columns (compressed): its entries read once for both the
// real and the imaginary part.
Eigen::VectorXcd real_times(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x) {
    // On the real and imaginary parts (the same sums in the same order as complex
    // arithmetic, at half its cost: no checks of the products for NaN).
    Eigen::VectorXcd y = Eigen::VectorXcd::Zero(A.rows());
    double* yr = reinterpret_cast<double*>(y.data());
    const double* xr = reinterpret_cast<const double*>(x.data());
    for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
        const double re = xr[2 * j], im = xr[2 * j + 1];
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
            const Eigen::Index i = it.index();
            yr[2 * i] += it.value() * re;
            yr[2 * i + 1] += it.value() * im;
        }
    }
    return y;
}

std::complex<double> real_bilinear(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& y,
                                   const Eigen::VectorXcd& x) {
    // Column by column: x_j times (y^H A)_j, in real arithmetic.
    const double* yr = reinterpret_cast<const double*>(y.data());
    const double* xr = reinterpret_cast<const double*>(x.data());
    double re = 0.0, im = 0.0;
    for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
        double cr = 0.0, ci = 0.0;   // (y^H A)_j = sum conj(y_i) A_ij
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
            const Eigen::Index i = it.index();
            cr += it.value() * yr[2 * i];
            ci -= it.value() * yr[2 * i + 1];
        }
        re += cr * xr[2 * j] - ci * xr[2 * j + 1];
        im += cr * xr[2 * j + 1] + ci * xr[2 * j];
    }
    return {re, im};
}

Eigen::VectorXcd real_transpose_times(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x) {
    Eigen::VectorXcd y(A.cols());
    for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
        std::complex<double> s = 0.0;
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) s += it.value() * x[it.index()];
        y[j] = s;
    }
    return y;
}

PencilAction sparse_pencil_action(const SparsePencil& p) { return pencil_action(p.M, p.C, p.K, real_times); }

Eigen::VectorXd fixed_random_vector(Eigen::Index n) {
    // splitmix64 from a fixed seed: 53 bits per entry, mapped to [-1, 1].
    Eigen::VectorXd v(n);
    std::uint64_t x = 0x9E3779B97F4A7C15ULL;
    for (Eigen::Index i = 0; i < n; ++i) {
        x += 0x9E3779B97F4A7C15ULL;
        std::uint64_t z = x;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        z ^= z >> 31;
        v[i] = 2.0 * (static_cast<double>(z >> 11) * 0x1.0p-53) - 1.0;
    }
    return v;
}

Eigen::VectorXd sparse_dof_scaling(const SparsePencil& p, double scale) {
    Eigen::VectorXd t(p.M.rows());
    for (Eigen::Index i = 0; i < t.size(); ++i) {
        const double w = scale * scale * std::abs(p.M.coeff(i, i)) + scale * std::abs(p.C.coeff(i, i)) +
                         std::abs(p.K.coeff(i, i));
        t(i) = (w > 0.0 && std::isfinite(w)) ? 1.0 / std::sqrt(w) : 1.0;
    }
    return t;
}

PencilNorms scaled_norms(const SparsePencil& p, const Eigen::VectorXd& t) {
    const auto norm = [&t](const SparseMatrix& A) {
        double sum = 0.0;
        for (Eigen::Index k = 0; k < A.outerSize(); ++k)
            for (SparseMatrix::InnerIterator it(A, k); it; ++it) {
                const double v = t(it.row()) * it.value() * t(it.col());
                sum += v * v;
            }
        return std::sqrt(sum);
    };
    return {norm(p.M), norm(p.C), norm(p.K)};
}

using cd = std::complex<double>;
using SpC = Eigen::SparseMatrix<cd>;

namespace {

PencilAction action_of(const SparsePencil& p) { return sparse_pencil_action(p); }

}  // namespace

double backward_error(const SparsePencil& p, cd lambda, const Eigen::VectorXcd& x) {
    return backward_error(action_of(p), lambda, x);
}

namespace {

// One round's end for x (unit norm), whose products M x, C x, K x are given, and
// the left vector y at l: the two-sided Rayleigh quotient (Newton) update
// l - y^H P(l) x / y^H P'(l) x and the backward error of x there, in two passes of
// real arithmetic (complex arithmetic checks every product for NaN, and the
// expressions would each make a pass and a vector).
std::pair<cd, double> newton_update(cd l, const Eigen::VectorXcd& y, const Eigen::VectorXcd& Mx,
                                    const Eigen::VectorXcd& Cx, const Eigen::VectorXcd& Kx, const PencilAction& action) {
    const Eigen::Index n = y.size();
    const double* yv = reinterpret_cast<const double*>(y.data());
    const double* mv = reinterpret_cast<const double*>(Mx.data());
    const double* cv = reinterpret_cast<const double*>(Cx.data());
    const double* kv = reinterpret_cast<const double*>(Kx.data());
    const auto pass = [&](cd at, const auto& use) {
        const double ar = at.real(), ai = at.imag(), sr = ar * ar - ai * ai, si = 2.0 * ar * ai;
        for (Eigen::Index i = 0; i < n; ++i) {
            const double mr = mv[2 * i], mi = mv[2 * i + 1], cr = cv[2 * i], ci = cv[2 * i + 1];
            const double rr = sr * mr - si * mi + ar * cr - ai * ci + kv[2 * i];        // P(at) x
            const double ri = sr * mi + si * mr + ar * ci + ai * cr + kv[2 * i + 1];
            use(i, rr, ri, 2.0 * (ar * mr - ai * mi) + cr, 2.0 * (ar * mi + ai * mr) + ci);   // and P'(at) x
        }
    };
    double nr = 0.0, ni = 0.0, dr = 0.0, di = 0.0;
    pass(l, [&](Eigen::Index i, double rr, double ri, double pr, double pi) {
        const double yr = yv[2 * i], yi = yv[2 * i + 1];
        nr += yr * rr + yi * ri;
        ni += yr * ri - yi * rr;
        dr += yr * pr + yi * pi;
        di += yr * pi - yi * pr;
    });
    const cd den(dr, di);
    const cd next = std::abs(den) > 0.0 ? l - cd(nr, ni) / den : l;
    double sum = 0.0;
    pass(next, [&](Eigen::Index, double rr, double ri, double, double) { sum += rr * rr + ri * ri; });
    const double a = std::abs(next), whole = a * a * action.norm_M + a * action.norm_C + action.norm_K;
    return {next, whole > 0.0 ? std::sqrt(sum) / whole : 0.0};
}

}  // namespace

double refine_eigenpair(const SparsePencil& p, const PencilAction& action, Mode& m, double accurate, double scale,
                        bool predicted) {
    // The backward error of (l, x) from x's products M x, C x, K x (backward_error's
    // formula, without multiplying again).
    const auto error_of = [&](cd l, const Eigen::VectorXcd& Mx, const Eigen::VectorXcd& Cx, const Eigen::VectorXcd& Kx,
                              double xnorm) {
        const Eigen::VectorXcd r = (l * l) * Mx + l * Cx + Kx;
        const double a = std::abs(l), whole = (a * a * action.norm_M + a * action.norm_C + action.norm_K) * xnorm;
        return whole > 0.0 ? r.norm() / whole : 0.0;
    };
    Eigen::VectorXcd Mx, Cx, Kx;
    double raw = std::numeric_limits<double>::infinity();
    if (!predicted) {
        action.apply(m.right, Mx, Cx, Kx);
        raw = error_of(m.lambda, Mx, Cx, Kx, m.right.norm());
    }
    const cd off = 1e-12 * std::max(std::abs(m.lambda), kRigidBodyTolerance * scale) * std::polar(1.0, kPi / 4);
    detail::PencilLU lu;
    if (!lu.compute(p, m.lambda + off)) return raw;   // no left vector: an infinite error bound
    // The left iteration starts from the mode's left vector where it has one (a
    // continued mode's, of the last speed), else from the right vector.
    const bool has_left = m.left.size() == m.right.size() && m.left.allFinite() && m.left.norm() > 0.0;
    Eigen::VectorXcd x = m.right, y = has_left ? m.left : m.right;
    Eigen::VectorXcd Mxn, Cxn, Kxn;
    cd lambda = m.lambda;
    double eta = raw;
    const bool update = raw > accurate;
    for (int step = 0; step < 4; ++step) {
        // Left: y <- P^{-H} P'(l)^H y, with P'(l)^H = 2 conj(l) M^T + C^T for real M, C;
        // right: x <- P^{-1} P'(l) x (both solves in one pass).
        // A predicted pair's first left solve takes the left vector itself (plain inverse
        // iteration): its products with the pencil would serve only that round.
        const bool plain = predicted && step == 0;
        const Eigen::VectorXcd left_rhs =
            plain ? y : Eigen::VectorXcd((2.0 * std::conj(lambda)) * real_transpose_times(p.M, y) +
                                         real_transpose_times(p.C, y));
        Eigen::VectorXcd xn, yn;
        if (update)
            lu.solve_both(plain ? Eigen::VectorXcd((2.0 * lambda) * real_times(p.M, x) + real_times(p.C, x))
                                : Eigen::VectorXcd((2.0 * lambda) * Mx + Cx),
                          left_rhs, xn, yn);
        else
            yn = lu.adjoint_solve(left_rhs);
        if (!yn.allFinite() || yn.norm() == 0.0) break;
        y = yn.normalized();
        if (!update) {
            if (step == 1) break;   // two steps give the left vector
            continue;
        }
        if (!xn.allFinite() || xn.norm() == 0.0) break;
        xn.normalize();
        action.apply(xn, Mxn, Cxn, Kxn);
        const auto [next, e] = newton_update(lambda, y, Mxn, Cxn, Kxn, action);
        if (!(e < eta)) break;
        x = xn;
        Mx.swap(Mxn);
        Cx.swap(Cxn);
        Kx.swap(Kxn);
        lambda = next;
        eta = e;
        if (eta <= accurate) break;
    }
    m.lambda = lambda;
    m.right = unit_vector(x);
    m.left = unit_vector(y);
    m.backward_error = eta;
    return raw;
}

namespace {

using detail::ArnoldiSize;
using detail::Ritz;

// The Arnoldi sizes for the wanted modes plus `reserve` places.
ArnoldiSize arnoldi_size(int n, const SparseEigenOptions& opt, int reserve) {
    // Conjugates come along with a real shift, so ask for twice the wanted count.
    ArnoldiSize sz;
    sz.N = 2 * n;
    sz.nev = std::min<a_int>(2 * opt.modes + 2 + reserve, sz.N - 2);
    // A real shift brings each mode's conjugate along; a complex one counts modes.
    sz.wanted = std::min<a_int>((opt.shift.imag() == 0.0 ? 2 : 1) * opt.modes + reserve, sz.nev);
    sz.ncv = opt.lanczos_vectors > 0 ? opt.lanczos_vectors : std::max<a_int>(2 * sz.nev + 1, 30);
    sz.ncv = std::min<a_int>(sz.ncv, sz.N);
    if (sz.ncv <= sz.nev + 1)
        throw InputError(fmt::format("{} {}: must exceed 2 * modes + 3 = {}", option_field("lanczos_vectors"),
                                         sz.ncv, sz.nev + 1));
    return sz;
}

// The Ritz pairs at the requested shift, or at the shift moved off a singular P(sigma)
// in steps of the natural scale; out.shift is the shift used.
std::vector<Ritz> ritz_at_regular_shift(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                                        const Eigen::VectorXd& t, double scale, int reserve, int attempt,
                                        SparseSpectrum& out) {
    SparseEigenOptions o = opt;
    std::string why;
    const double moves[] = {0.0, 1e-5, 1e-4, 1e-3};
    for (double move : moves) {
        o.shift = opt.shift - cd(move * scale, 0.0);
        // Rigid-body eigenvalues in the window (at a singular shift, or seen at the
        // last speed) form Jordan blocks whose Ritz values converge only to about
        // sqrt(eps): ARPACK would restart to its limit. Every wanted pair is
        // refined below, so a looser Ritz tolerance loses nothing.
        if (move > 0.0 || reserve > 0) o.tolerance = std::max(opt.tolerance, 1e-9);
        try {
            std::vector<Ritz> ritz = detail::arnoldi_ritz_pairs(p, o, sz, t, out.iterations);
            out.shift = o.shift;
            if (o.shift != opt.shift && attempt == 0)
                out.notes.push_back(fmt::format("the shift ({:.6g}, {:.6g}) was moved to ({:.6g}, {:.6g}): P(shift) "
                                                "is singular there ({}), e.g. rigid-body modes at 0",
                                                opt.shift.real(), opt.shift.imag(), o.shift.real(), o.shift.imag(),
                                                why));
            return ritz;
        } catch (const detail::SingularShift& e) {
            if (why.empty()) why = e.why;
        }
    }
    throw InputError(fmt::format("P(shift) is singular at the shift ({}, {}) and at shifts moved by up to "
                                 "1e-3 of the model's frequency scale {:.6g} rad/s ({}); choose another target",
                                 opt.shift.real(), opt.shift.imag(), scale, why));
}

// The modes of the Ritz pairs (upper half-plane), rigid-body ones apart, each with the
// better half of its state vector.
void modes_of_ritz(const std::vector<Ritz>& ritz, int n, const PencilAction& action, double scale, double real_tol,
                   SparseSpectrum& out) {
    for (const Ritz& r : ritz) {
        if (std::abs(r.theta) == 0.0) continue;
        Mode m;
        m.lambda = out.shift + 1.0 / r.theta;
        if (m.lambda.imag() < -real_tol) continue;   // the conjugate of a kept mode
        if (std::abs(m.lambda.imag()) <= real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        const Eigen::VectorXcd top = r.z.head(n), bottom = r.z.tail(n);
        // The backward error does not depend on the vector's scale: the better half's is the mode's.
        const double et = backward_error(action, m.lambda, top), eb = backward_error(action, m.lambda, bottom);
        m.right = unit_vector(et < eb ? top : bottom);
        m.backward_error = std::min(et, eb);
        if (is_rigid_body(m.lambda, m.right, action, scale)) {
            m.whirl = Whirl::Real;
            out.rigid_body.push_back(std::move(m));
            continue;
        }
        out.modes.push_back(std::move(m));
    }
}

// Keeps the wanted count nearest the requested shift.
void keep_nearest(const SparseEigenOptions& opt, SparseSpectrum& out) {
    std::sort(out.modes.begin(), out.modes.end(), [&](const Mode& a, const Mode& b) {
        return std::abs(a.lambda - opt.shift) < std::abs(b.lambda - opt.shift);
    });
    if (static_cast<int>(out.modes.size()) > opt.modes) {
        // A window edge through a double eigenvalue (an axisymmetric rotor at
        // standstill): which half is nearer the shift is rounding, so both are kept.
        // One more at most: a double eigenvalue has two halves (a cluster is left as cut).
        size_t keep = static_cast<size_t>(opt.modes);
        if (std::abs(out.modes[keep].lambda - out.modes[keep - 1].lambda) <=
                1e-6 * std::abs(out.modes[keep - 1].lambda) &&
            out.modes[keep].lambda != out.modes[keep - 1].lambda)
            ++keep;
        if (keep > static_cast<size_t>(opt.modes))
            out.notes.push_back(fmt::format("the window's edge cuts a double eigenvalue at {:.6g} rad/s: both halves "
                                            "are kept ({} modes)",
                                            out.modes[keep - 1].lambda.imag(), keep));
        out.modes.resize(keep);
    }
}

// Verification: refines every pair, and rejects one that stays above the tolerance.
void refine_and_verify(const SparsePencil& p, const PencilAction& action, const SparseEigenOptions& opt,
                       double scale, double real_tol, const std::vector<std::pair<int, int>>& whirl_pairs,
                       SparseSpectrum& out) {
    const double accurate = 1e-3 * opt.verify_tolerance;
    const std::vector<Mode> arnoldi = out.modes;
    for (Mode& m : out.modes) {
        const double raw = refine_eigenpair(p, action, m, accurate, scale);
        out.max_raw_backward_error = std::max(out.max_raw_backward_error, raw);
        if (raw > accurate) ++out.refined;
    }
    // Two vectors of one double eigenvalue turned to one direction by the
    // refinement: the pair keeps its Arnoldi vectors (verified below).
    for (size_t i = 0; i < out.modes.size(); ++i)
        for (size_t j = i + 1; j < out.modes.size(); ++j)
            if (std::abs(out.modes[i].lambda - out.modes[j].lambda) <= 1e-6 * std::abs(out.modes[i].lambda) &&
                mac(out.modes[i].right, out.modes[j].right) > 0.99)
                for (size_t k : {i, j}) {
                    out.modes[k].right = arnoldi[k].right;
                    out.modes[k].lambda = arnoldi[k].lambda;
                    out.modes[k].backward_error = arnoldi[k].backward_error;
                }
    for (Mode& m : out.modes) {
        if (!(m.backward_error <= opt.verify_tolerance))
            throw SolverError(fmt::format("the sparse eigenpair near lambda = ({:.6g}, {:.6g}) keeps a backward error "
                                          "of {:.1e} after refinement, above the verification tolerance {:.1e}; "
                                          "raise the Lanczos vectors or move the target closer",
                                          m.lambda.real(), m.lambda.imag(), m.backward_error, opt.verify_tolerance));
        if (std::abs(m.lambda.imag()) <= real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        m.whirl = classify_whirl(m.lambda, m.right, whirl_pairs, real_tol);
    }
}

}  // namespace

SparseSpectrum solve_quadratic_sparse(const SparsePencil& p, const SparseEigenOptions& opt,
                                      const std::vector<std::pair<int, int>>& whirl_pairs) {
    const int n = static_cast<int>(p.M.rows());
    if (n < 2) throw InputError("the sparse eigensolver needs at least 2 DOFs; use the dense solver");
    if (opt.modes < 1 || 2 * opt.modes + 2 > 2 * n - 1)
        throw InputError(fmt::format("{} {}: allowed for this model with {} DOFs: 1 to {}", option_field("modes"),
                                     opt.modes, n, std::max(1, n - 2)));
    if (!(opt.verify_tolerance > 0.0 && opt.verify_tolerance < 1.0))
        throw InputError(fmt::format("verify_tolerance {}: allowed: 0 < tolerance < 1", opt.verify_tolerance));
    const PencilAction action = action_of(p);
    const double scale = natural_frequency_scale(p.M.diagonal(), p.K.diagonal(), action.norm_M, action.norm_K);
    const double real_tol = 1e-7 * scale;
    // DOF scaling for the condition estimate of P(sigma) (as the dense solver scales).
    const Eigen::VectorXd t = sparse_dof_scaling(p, scale);

    SparseSpectrum out;
    int reserve = std::max(0, opt.reserve);
    std::vector<Ritz> ritz;
    for (int attempt = 0;; ++attempt) {
        const ArnoldiSize sz = arnoldi_size(n, opt, reserve);
        ritz = ritz_at_regular_shift(p, opt, sz, t, scale, reserve, attempt, out);
        // Rigid-body eigenvalues take places in the window: ask for that many more once.
        int rigid = 0, kept = 0;
        for (const Ritz& r : ritz) {
            if (std::abs(r.theta) == 0.0) continue;
            const cd l = out.shift + 1.0 / r.theta;
            if (l.imag() < -real_tol) continue;
            (is_rigid_body(l, r.z.tail(n), action, scale) ? rigid : kept) += 1;
        }
        if (kept >= opt.modes || rigid == 0 || attempt > 0 || sz.nev == sz.N - 2) break;
        reserve += rigid + 2;
    }

    out.converged = static_cast<int>(ritz.size());
    modes_of_ritz(ritz, n, action, scale, real_tol, out);
    keep_nearest(opt, out);
    refine_and_verify(p, action, opt, scale, real_tol, whirl_pairs, out);
    // Double eigenvalues turned into their backward and forward modes (after the
    // refinement, which may rotate a pair's vectors in their plane).
    separate_double_whirl(out.modes, whirl_pairs, real_tol, action);
    // Bounds also on the DOF-scaled pencil t P t (as the dense solver's): stiff supports do not inflate them.
    set_error_bounds(out.modes, action, scaled_norms(p, t), t);
    if (!opt.left_vectors)
        for (Mode& m : out.modes) m.left.resize(0);
    sort_by_frequency(out.modes);
    return out;
}

}  // namespace gyrokit
