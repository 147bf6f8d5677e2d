#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <Eigen/SparseLU>
#include <algorithm>
#include <arpack/arpack.hpp>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <mutex>

namespace gyrokit {

Eigen::VectorXcd real_times(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x) {
    const Eigen::VectorXd re = A * x.real(), im = A * x.imag();
    Eigen::VectorXcd y(re.size());
    y.real() = re;
    y.imag() = im;
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


using cd = std::complex<double>;
using SpC = Eigen::SparseMatrix<cd>;

namespace {

PencilAction action_of(const SparsePencil& p) { return sparse_pencil_action(p); }

}  // namespace

double backward_error(const SparsePencil& p, cd lambda, const Eigen::VectorXcd& x) {
    return backward_error(action_of(p), lambda, x);
}

namespace {

// A converged Ritz pair of the shift-invert operator: theta and its state vector.
struct Ritz {
    cd theta;
    Eigen::VectorXcd z;
};

struct ArnoldiSize {
    a_int N, nev, ncv;
    // The values that must converge when not all do: those of the wanted modes
    // (real shift: with their conjugates), without the margin at the window's edge.
    a_int wanted;
};

// Restart budgets: a quick one, then the full one. The window's margin values may
// sit in a dense cluster (a train of equal spans): the wanted values then converge
// in a few restarts and the margin only after hundreds. Once the wanted ones have
// converged and no other Ritz value can be nearer the shift, they are the result.
constexpr int kQuickRestarts = 20;
std::vector<a_int> restart_budgets(int max_iterations) {
    if (max_iterations <= kQuickRestarts) return {max_iterations};
    return {kQuickRestarts, max_iterations};
}

// After a stop at the restart limit: `converged` holds the wanted count of values
// with the largest |theta| (nearest the shift), and every other Ritz value of the
// Arnoldi matrix (`ritz`, with error estimates `bounds`) lies farther from the
// shift than the farthest of them, by more than its estimate.
// Values that `counts` rejects (conjugates below the real axis for a complex
// shift) do not count towards `wanted`.
template <class Counts>
bool wanted_complete(std::vector<cd> converged, const std::vector<cd>& ritz, const std::vector<double>& bounds,
                     a_int wanted, const Counts& counts) {
    if (wanted < 1) return false;
    std::sort(converged.begin(), converged.end(), [](cd a, cd b) { return std::abs(a) > std::abs(b); });
    double edge = -1.0;
    a_int seen = 0;
    for (const cd c : converged)
        if (counts(c) && ++seen == wanted) {
            edge = std::abs(c);
            break;
        }
    if (edge < 0.0) return false;
    // Each converged value accounts for one Ritz value only: the two halves of a
    // double eigenvalue are two values, and an unconverged half must be checked.
    // The estimate is ARPACK's residual bound, not an error bound for this
    // non-normal operator: a margin of ten times it.
    std::vector<bool> used(converged.size(), false);
    for (size_t k = 0; k < ritz.size(); ++k) {
        bool found = false;
        for (size_t c = 0; c < converged.size() && !found; ++c)
            if (!used[c] && std::abs(converged[c] - ritz[k]) <= 1e-8 * std::abs(converged[c])) found = used[c] = true;
        if (!found && !(std::abs(ritz[k]) + 10.0 * std::abs(bounds[k]) < (1.0 - 1e-8) * edge)) return false;
    }
    return true;
}

// P(sigma) is singular or too nearly so for shift-invert (the shift sits on
// an eigenvalue: sigma = 0 with rigid-body modes); the caller moves the shift.
struct SingularShift {
    std::string why;
};

// Reciprocal condition estimate of T P T (T the DOF scaling t_i = 1/sqrt(W_ii),
// W = g^2|M| + g|C| + |K|), from two steps of inverse iteration with the LU.
template <class Scalar, class LU>
double rcond_estimate(const LU& lu, const Eigen::SparseMatrix<Scalar>& P, const Eigen::VectorXd& t) {
    using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    double norm2 = 0.0;
    for (int k = 0; k < P.outerSize(); ++k)
        for (typename Eigen::SparseMatrix<Scalar>::InnerIterator it(P, k); it; ++it)
            norm2 += std::norm(t(it.row()) * it.value() * t(it.col()));
    Vec z(P.rows());
    for (Eigen::Index i = 0; i < z.size(); ++i) z(i) = Scalar(1.0 + static_cast<double>(i % 7) / 7.0);
    double grow = 0.0;
    for (int step = 0; step < 2; ++step) {
        z /= z.norm();
        const Vec tz = t.cwiseInverse().asDiagonal() * z;
        z = t.cwiseInverse().asDiagonal() * Vec(lu.solve(tz));
        if (!z.allFinite()) return 0.0;
        grow = z.norm();
    }
    return grow > 0.0 ? 1.0 / (std::sqrt(norm2) * grow) : 0.0;
}

// The sparse LU of P(sigma) = sigma^2 M + sigma C + K in the arithmetic of sigma.
// Throws SingularShift if it fails or P(sigma) is singular to working accuracy.
template <class Scalar>
void factorize(Eigen::SparseLU<Eigen::SparseMatrix<Scalar>, Eigen::COLAMDOrdering<int>>& lu, const SparsePencil& p,
               Scalar s, const Eigen::VectorXd& t) {
    const Eigen::SparseMatrix<Scalar> P =
        (s * s) * p.M.cast<Scalar>() + s * p.C.cast<Scalar>() + p.K.cast<Scalar>();
    lu.compute(P);
    if (lu.info() != Eigen::Success) throw SingularShift{lu.lastErrorMessage()};
    const double rc = rcond_estimate(lu, P, t);
    if (!(rc >= 1e-12)) throw SingularShift{fmt::format("reciprocal condition {:.1e}", rc)};
}

// y = (A - sigma B)^{-1} B x on the companion pencil: with x = [v1; v2],
// w2 = -P(sigma)^{-1} (M v1 + (C + sigma M) v2), y = [v2 + sigma w2; w2].
template <class Scalar, class LU>
void apply_operator(const LU& lu, const Eigen::SparseMatrix<Scalar>& M, const Eigen::SparseMatrix<Scalar>& CsM,
                    Scalar s, const Scalar* x, Scalar* y, int n) {
    using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    const Eigen::Map<const Vec> v1(x, n), v2(x + n, n);
    const Vec w2 = -lu.solve(M * v1 + CsM * v2);
    Eigen::Map<Vec>(y, n) = v2 + s * w2;
    Eigen::Map<Vec>(y + n, n) = w2;
}

// Stopped at the restart limit with `converged` of the wanted values: a result only
// if they are complete (wanted_complete), else this error.
SolverError not_converged(const SparseEigenOptions& opt, const ArnoldiSize& sz, a_int converged) {
    return SolverError(fmt::format("ARPACK reached {} restarts with {} of {} Ritz values converged; raise the number "
                                   "of Lanczos vectors ({} {}) or move the target closer to the wanted "
                                   "modes",
                                   opt.max_iterations, converged, sz.nev, option_field("lanczos_vectors"), sz.ncv));
}

void check_arnoldi(const char* routine, a_int info, const ArnoldiSize& sz) {
    // info 1 (the restart limit) is decided by the caller: every value converged
    // (a defective rigid-body block can keep ARPACK restarting), or the wanted
    // ones complete (a cluster at the margin); each pair is verified afterwards.
    if (info != 0 && info != 1)
        throw SolverError(fmt::format("ARPACK {} failed with info = {}; raise {} {}", routine, info,
                                      option_field("lanczos_vectors"), sz.ncv));
}

// Complex shift: complex Arnoldi (znaupd) on the complex operator.
// ARPACK keeps its iteration state in Fortran SAVE variables between the
// reverse-communication calls: two iterations in one process must not overlap
// (threads of a design study, scripts). Parallel speeds run in worker processes.
std::mutex& arpack_mutex() {
    static std::mutex m;
    return m;
}

std::vector<Ritz> ritz_complex(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                               const Eigen::VectorXd& t, int& iterations) {
    const int n = static_cast<int>(p.M.rows());
    const cd s = opt.shift;
    Eigen::SparseLU<SpC, Eigen::COLAMDOrdering<int>> lu;
    factorize(lu, p, s, t);
    const SpC Mc = p.M.cast<cd>(), CsM = p.C.cast<cd>() + s * p.M.cast<cd>();
    const std::lock_guard<std::mutex> one_at_a_time(arpack_mutex());
    const a_int N = sz.N, nev = sz.nev, ncv = sz.ncv, lworkl = 3 * ncv * ncv + 5 * ncv;
    const std::vector<a_int> budgets = restart_budgets(opt.max_iterations);
    for (size_t stage = 0; stage < budgets.size(); ++stage) {
        const bool last = stage + 1 == budgets.size();
        std::vector<cd> resid(static_cast<size_t>(N)), V(static_cast<size_t>(N * ncv)),
            workd(3 * static_cast<size_t>(N)), workl(static_cast<size_t>(lworkl));
        std::vector<double> rwork(static_cast<size_t>(ncv));
        a_int iparam[11] = {1, 0, budgets[stage], 1, 0, 0, 1, 0, 0, 0, 0};   // exact shifts, mode 1 on OP
        a_int ipntr[14] = {};
        a_int ido = 0, info = 0;
        // ARPACK starts from resid (info = 1): the caller's start, else a fixed one.
        if (opt.start.size() == N && opt.start.allFinite() && opt.start.norm() > 0)
            Eigen::Map<Eigen::VectorXcd>(resid.data(), N) = opt.start;
        else
            Eigen::Map<Eigen::VectorXcd>(resid.data(), N) = fixed_random_vector(N).cast<cd>();
        info = 1;
        while (true) {
            throw_if_interrupted();
            arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance,
                          resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl,
                          rwork.data(), info);
            if (ido != -1 && ido != 1) break;
            apply_operator(lu, Mc, CsM, s, workd.data() + ipntr[0] - 1, workd.data() + ipntr[1] - 1, n);
        }
        check_arnoldi("znaupd", info, sz);
        if (info == 1 && iparam[4] < 1) {
            if (!last) continue;
            throw not_converged(opt, sz, iparam[4]);
        }
        // The Ritz values of the Arnoldi matrix and their estimates, for wanted_complete.
        std::vector<cd> ritz(static_cast<size_t>(ncv));
        std::vector<double> bounds(static_cast<size_t>(ncv));
        for (a_int k = 0; k < ncv; ++k) {
            ritz[static_cast<size_t>(k)] = workl[static_cast<size_t>(ipntr[5] - 1 + k)];
            bounds[static_cast<size_t>(k)] = std::abs(workl[static_cast<size_t>(ipntr[7] - 1 + k)]);
        }

        std::vector<cd> d(static_cast<size_t>(nev + 1)), Z(static_cast<size_t>(N * nev)),
            workev(2 * static_cast<size_t>(ncv));
        std::vector<a_int> select(static_cast<size_t>(ncv));
        a_int info2 = 0;
        arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), d.data(), Z.data(), N, cd(0.0), workev.data(),
                      arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance, resid.data(),
                      ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl, rwork.data(), info2);
        if (info2 != 0) throw SolverError(fmt::format("ARPACK zneupd failed with info = {}", info2));
        iterations = static_cast<int>(iparam[2]);
        const a_int found = std::min<a_int>(iparam[4], nev);
        // Upper half-plane eigenvalues count (the modes); their conjugates do not.
        const auto upper = [&](cd theta) {
            const cd l = s + 1.0 / theta;
            return l.imag() >= -1e-7 * std::abs(l);
        };
        if (info == 1 && found < nev && !wanted_complete({d.begin(), d.begin() + found}, ritz, bounds, sz.wanted, upper)) {
            if (!last) continue;
            throw not_converged(opt, sz, iparam[4]);
        }
        std::vector<Ritz> out;
        for (a_int j = 0; j < found; ++j)
            out.push_back({d[static_cast<size_t>(j)], Eigen::Map<const Eigen::VectorXcd>(Z.data() + j * N, N)});
        return out;
    }
    return {};
}

// Real shift: the operator is real, so real Arnoldi (dnaupd) on a real LU
// finds the same eigenvalues, conjugate pairs together, at a fraction of the
// cost of complex arithmetic.
std::vector<Ritz> ritz_real(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                            const Eigen::VectorXd& t, int& iterations) {
    using SpD = Eigen::SparseMatrix<double>;
    const int n = static_cast<int>(p.M.rows());
    const double s = opt.shift.real();
    Eigen::SparseLU<SpD, Eigen::COLAMDOrdering<int>> lu;
    factorize(lu, p, s, t);
    const SpD CsM = p.C + s * p.M;
    const std::lock_guard<std::mutex> one_at_a_time(arpack_mutex());
    const a_int N = sz.N, nev = sz.nev, ncv = sz.ncv, lworkl = 3 * ncv * ncv + 6 * ncv;
    const std::vector<a_int> budgets = restart_budgets(opt.max_iterations);
    for (size_t stage = 0; stage < budgets.size(); ++stage) {
        const bool last = stage + 1 == budgets.size();
        std::vector<double> resid(static_cast<size_t>(N)), V(static_cast<size_t>(N * ncv)),
            workd(3 * static_cast<size_t>(N)), workl(static_cast<size_t>(lworkl));
        a_int iparam[11] = {1, 0, budgets[stage], 1, 0, 0, 1, 0, 0, 0, 0};   // exact shifts, mode 1 on OP
        a_int ipntr[14] = {};
        a_int ido = 0, info = 0;
        if (opt.start.size() == N && opt.start.allFinite() && opt.start.norm() > 0)
            // A real start spanning the same directions as the complex one.
            Eigen::Map<Eigen::VectorXd>(resid.data(), N) = opt.start.real() + opt.start.imag();
        else
            Eigen::Map<Eigen::VectorXd>(resid.data(), N) = fixed_random_vector(N);
        info = 1;
        while (true) {
            throw_if_interrupted();
            arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance,
                          resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl, info);
            if (ido != -1 && ido != 1) break;
            apply_operator(lu, p.M, CsM, s, workd.data() + ipntr[0] - 1, workd.data() + ipntr[1] - 1, n);
        }
        check_arnoldi("dnaupd", info, sz);
        if (info == 1 && iparam[4] < 1) {
            if (!last) continue;
            throw not_converged(opt, sz, iparam[4]);
        }
        // The Ritz values of the Arnoldi matrix and their estimates, for wanted_complete.
        std::vector<cd> ritz(static_cast<size_t>(ncv));
        std::vector<double> bounds(static_cast<size_t>(ncv));
        for (a_int k = 0; k < ncv; ++k) {
            ritz[static_cast<size_t>(k)] = cd(workl[static_cast<size_t>(ipntr[5] - 1 + k)],
                                              workl[static_cast<size_t>(ipntr[6] - 1 + k)]);
            bounds[static_cast<size_t>(k)] = workl[static_cast<size_t>(ipntr[7] - 1 + k)];
        }

        // dneupd may return one value more than nev (a conjugate pair across the edge).
        std::vector<double> dr(static_cast<size_t>(nev + 1)), di(static_cast<size_t>(nev + 1)),
            Z(static_cast<size_t>(N * (nev + 1))), workev(3 * static_cast<size_t>(ncv));
        std::vector<a_int> select(static_cast<size_t>(ncv));
        a_int info2 = 0;
        arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), dr.data(), di.data(), Z.data(), N, 0.0, 0.0,
                      workev.data(), arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance,
                      resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl, info2);
        if (info2 != 0) throw SolverError(fmt::format("ARPACK dneupd failed with info = {}", info2));
        iterations = static_cast<int>(iparam[2]);
        const a_int found = std::min<a_int>(iparam[4], nev + 1);
        if (info == 1 && found < nev) {
            std::vector<cd> converged;
            for (a_int j = 0; j < found; ++j) converged.emplace_back(dr[static_cast<size_t>(j)], di[static_cast<size_t>(j)]);
            if (!wanted_complete(converged, ritz, bounds, sz.wanted, [](cd) { return true; })) {
                if (!last) continue;
                throw not_converged(opt, sz, iparam[4]);
            }
        }
        std::vector<Ritz> out;
        for (a_int j = 0; j < found; ++j) {
            const Eigen::Map<const Eigen::VectorXd> re(Z.data() + j * N, N);
            const cd theta(dr[static_cast<size_t>(j)], di[static_cast<size_t>(j)]);
            if (theta.imag() == 0.0) {
                out.push_back({theta, re.cast<cd>()});
            } else if (theta.imag() > 0.0 && j + 1 < found) {
                // A pair: columns j and j + 1 hold the real and imaginary part of
                // the vector of the value with positive imaginary part.
                const Eigen::Map<const Eigen::VectorXd> im(Z.data() + (j + 1) * N, N);
                Eigen::VectorXcd z(N);
                z.real() = re;
                z.imag() = im;
                out.push_back({theta, z});
                out.push_back({std::conj(theta), z.conjugate()});
                ++j;
            }
        }
        return out;
    }
    return {};
}

}  // namespace

double refine_eigenpair(const SparsePencil& p, const PencilAction& action, Mode& m, double accurate, double scale) {
    const double raw = backward_error(action, m.lambda, m.right);
    const cd off = 1e-12 * std::max(std::abs(m.lambda), kRigidBodyTolerance * scale) * std::polar(1.0, M_PI / 4);
    const cd at = m.lambda + off;
    const SpC P = (at * at) * p.M.cast<cd>() + at * p.C.cast<cd>() + p.K.cast<cd>();
    Eigen::SparseLU<SpC, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(P);
    if (lu.info() != Eigen::Success) return raw;   // no left vector: an infinite error bound
    const SpC Mt = p.M.transpose().cast<cd>(), Ct = p.C.transpose().cast<cd>();
    Eigen::VectorXcd x = m.right, y = m.right;
    Eigen::VectorXcd Mx, Cx, Kx;
    cd lambda = m.lambda;
    double eta = raw;
    const bool update = raw > accurate;
    for (int step = 0; step < 4; ++step) {
        // Left: y <- P^{-H} P'(l)^H y, with P'(l)^H = 2 conj(l) M^T + C^T for real M, C.
        Eigen::VectorXcd yn = lu.adjoint().solve(Eigen::VectorXcd((2.0 * std::conj(lambda)) * (Mt * y) + Ct * y));
        if (!yn.allFinite() || yn.norm() == 0.0) break;
        y = yn.normalized();
        if (!update) {
            if (step == 1) break;   // two steps give the left vector
            continue;
        }
        action.apply(x, Mx, Cx, Kx);
        Eigen::VectorXcd xn = lu.solve(Eigen::VectorXcd((2.0 * lambda) * Mx + Cx));
        if (!xn.allFinite() || xn.norm() == 0.0) break;
        xn.normalize();
        action.apply(xn, Mx, Cx, Kx);
        const Eigen::VectorXcd r = (lambda * lambda) * Mx + lambda * Cx + Kx;
        const cd slope = y.dot((2.0 * lambda) * Mx + Cx);
        const cd next = std::abs(slope) > 0.0 ? lambda - y.dot(r) / slope : lambda;
        const double e = backward_error(action, next, xn);
        if (!(e < eta)) break;
        x = xn;
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
        // The shift, moved off a singular P(sigma) in steps of the natural scale.
        SparseEigenOptions o = opt;
        std::string why;
        const double moves[] = {0.0, 1e-5, 1e-4, 1e-3};
        bool done = false;
        for (double move : moves) {
            o.shift = opt.shift - cd(move * scale, 0.0);
            // Rigid-body eigenvalues in the window (at a singular shift, or seen at the
            // last speed) form Jordan blocks whose Ritz values converge only to about
            // sqrt(eps): ARPACK would restart to its limit. Every wanted pair is
            // refined below, so a looser Ritz tolerance loses nothing.
            if (move > 0.0 || reserve > 0) o.tolerance = std::max(opt.tolerance, 1e-9);
            try {
                ritz = o.shift.imag() == 0.0 ? ritz_real(p, o, sz, t, out.iterations)
                                             : ritz_complex(p, o, sz, t, out.iterations);
                done = true;
                break;
            } catch (const SingularShift& e) {
                if (why.empty()) why = e.why;
            }
        }
        if (!done)
            throw InputError(fmt::format("P(shift) is singular at the shift ({}, {}) and at shifts moved by up to "
                                         "1e-3 of the model's frequency scale {:.6g} rad/s ({}); choose another target",
                                         opt.shift.real(), opt.shift.imag(), scale, why));
        out.shift = o.shift;
        if (o.shift != opt.shift && attempt == 0)
            out.notes.push_back(fmt::format("the shift ({:.6g}, {:.6g}) was moved to ({:.6g}, {:.6g}): P(shift) is "
                                            "singular there ({}), e.g. rigid-body modes at 0",
                                            opt.shift.real(), opt.shift.imag(), o.shift.real(), o.shift.imag(), why));
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
    // The wanted count nearest the requested shift.
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
    // Verification: refine every pair, and reject one that stays above the tolerance.
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
    // Double eigenvalues turned into their backward and forward modes (after the
    // refinement, which may rotate a pair's vectors in their plane).
    separate_double_whirl(out.modes, whirl_pairs, real_tol, action);
    {   // Bounds on the DOF-scaled pencil t P t (as the dense solver's): stiff supports do not inflate them.
        const SparsePencil scaled{t.asDiagonal() * p.M * t.asDiagonal(), t.asDiagonal() * p.C * t.asDiagonal(),
                                  t.asDiagonal() * p.K * t.asDiagonal()};
        set_error_bounds(out.modes, action, action_of(scaled), t);
    }
    if (!opt.left_vectors)
        for (Mode& m : out.modes) m.left.resize(0);
    sort_by_frequency(out.modes);
    return out;
}

}  // namespace gyrokit
