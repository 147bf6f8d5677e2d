#include <gyrokit/eig/detail/arpack_ritz.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <Eigen/SparseLU>
#include <algorithm>
#include <arpack/arpack.hpp>
#include <cmath>
#include <fmt/format.h>
#include <mutex>
#include <optional>
#include <type_traits>

namespace gyrokit::detail {

namespace {

using cd = std::complex<double>;
using SpC = Eigen::SparseMatrix<cd>;

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

// The Ritz values of the Arnoldi matrix and ARPACK's error estimates, as [dz]naupd leaves
// them in workl, for wanted_complete: complex values at ipntr[5] (znaupd), or their real
// and imaginary parts at ipntr[5] and ipntr[6] (dnaupd); the estimates at ipntr[7].
struct ArnoldiRitz {
    std::vector<cd> values;
    std::vector<double> bounds;
};

template <class Scalar>
ArnoldiRitz arnoldi_ritz_values(const std::vector<Scalar>& workl, const a_int* ipntr, a_int ncv) {
    const auto at = [&](a_int pointer, a_int k) { return workl[static_cast<size_t>(pointer - 1 + k)]; };
    ArnoldiRitz r;
    r.values.resize(static_cast<size_t>(ncv));
    r.bounds.resize(static_cast<size_t>(ncv));
    for (a_int k = 0; k < ncv; ++k) {
        if constexpr (std::is_same_v<Scalar, cd>)
            r.values[static_cast<size_t>(k)] = at(ipntr[5], k);
        else
            r.values[static_cast<size_t>(k)] = cd(at(ipntr[5], k), at(ipntr[6], k));
        r.bounds[static_cast<size_t>(k)] = std::abs(at(ipntr[7], k));
    }
    return r;
}

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

// ARPACK keeps its iteration state in Fortran SAVE variables between the
// reverse-communication calls: two iterations in one process must not overlap
// (threads of a design study, scripts). Parallel speeds run in worker processes.
std::mutex& arpack_mutex() {
    static std::mutex m;
    return m;
}

// One Arnoldi run of at most `restarts` restarts on ARPACK's reverse communication,
// in the arithmetic of Scalar: dnaupd/dneupd (double) or znaupd/zneupd (complex).
template <class Scalar>
struct ArnoldiRun {
    using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
    static constexpr bool complex = std::is_same_v<Scalar, cd>;
    a_int N, nev, ncv, lworkl;
    double tolerance;
    std::vector<Scalar> resid, V, workd, workl;
    std::vector<double> rwork;   // znaupd only
    a_int iparam[11];
    a_int ipntr[14] = {};
    a_int ido = 0, info = 1;     // info = 1: ARPACK starts from resid

    ArnoldiRun(const ArnoldiSize& sz, a_int restarts, double tol, const Vec& start)
        : N(sz.N), nev(sz.nev), ncv(sz.ncv), lworkl(3 * ncv * ncv + (complex ? 5 : 6) * ncv), tolerance(tol),
          resid(start.data(), start.data() + N), V(static_cast<size_t>(N * ncv)), workd(3 * static_cast<size_t>(N)),
          workl(static_cast<size_t>(lworkl)), rwork(complex ? static_cast<size_t>(ncv) : 0),
          iparam{1, 0, restarts, 1, 0, 0, 1, 0, 0, 0, 0} {}   // exact shifts, mode 1 on OP

    // The reverse-communication loop; apply(x, y) is y = OP x.
    template <class Apply>
    void iterate(const Apply& apply) {
        while (true) {
            throw_if_interrupted();
            if constexpr (complex)
                arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, tolerance,
                              resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl,
                              rwork.data(), info);
            else
                arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, tolerance,
                              resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl,
                              info);
            if (ido != -1 && ido != 1) return;
            apply(workd.data() + ipntr[0] - 1, workd.data() + ipntr[1] - 1);
        }
    }
    a_int converged() const { return iparam[4]; }
    int restarts() const { return static_cast<int>(iparam[2]); }
};

// The start vector: the caller's (a real shift takes the real vector spanning the
// same directions as the complex one), else a fixed one.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> start_vector(const SparseEigenOptions& opt, a_int N) {
    const bool given = opt.start.size() == N && opt.start.allFinite() && opt.start.norm() > 0;
    if constexpr (std::is_same_v<Scalar, cd>)
        return given ? Eigen::VectorXcd(opt.start) : Eigen::VectorXcd(fixed_random_vector(static_cast<int>(N)).cast<cd>());
    else
        return given ? Eigen::VectorXd(opt.start.real() + opt.start.imag()) : fixed_random_vector(static_cast<int>(N));
}

// Runs ARPACK with each restart budget in turn: a quick run, then the full one.
// `extract(run, ritz)` turns a finished run into the Ritz pairs, or nullopt when
// it stopped at the limit short of the wanted values (the next budget, or an error).
template <class Scalar, class Apply, class Extract>
std::vector<Ritz> staged_arnoldi(const SparseEigenOptions& opt, const ArnoldiSize& sz, const Apply& apply,
                                 const Extract& extract, int& iterations) {
    const char* routine = std::is_same_v<Scalar, cd> ? "znaupd" : "dnaupd";
    const auto start = start_vector<Scalar>(opt, sz.N);
    const std::lock_guard<std::mutex> one_at_a_time(arpack_mutex());
    a_int converged = 0;
    for (const a_int budget : restart_budgets(opt.max_iterations)) {
        ArnoldiRun<Scalar> run(sz, budget, opt.tolerance, start);
        run.iterate(apply);
        check_arnoldi(routine, run.info, sz);
        converged = run.converged();
        if (run.info == 1 && converged < 1) continue;
        std::optional<std::vector<Ritz>> out = extract(run, arnoldi_ritz_values(run.workl, run.ipntr, run.ncv));
        if (!out) continue;
        iterations = run.restarts();
        return *std::move(out);
    }
    throw not_converged(opt, sz, converged);
}

// Complex shift: complex Arnoldi (znaupd) on the complex operator.
std::vector<Ritz> ritz_complex(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                               const Eigen::VectorXd& t, int& iterations) {
    const int n = static_cast<int>(p.M.rows());
    const cd s = opt.shift;
    Eigen::SparseLU<SpC, Eigen::COLAMDOrdering<int>> lu;
    factorize(lu, p, s, t);
    const SpC Mc = p.M.cast<cd>(), CsM = p.C.cast<cd>() + s * p.M.cast<cd>();
    const auto apply = [&](const cd* x, cd* y) { apply_operator(lu, Mc, CsM, s, x, y, n); };
    const auto extract = [&](ArnoldiRun<cd>& run, const ArnoldiRitz& ritz) -> std::optional<std::vector<Ritz>> {
        const a_int N = run.N, nev = run.nev;
        std::vector<cd> d(static_cast<size_t>(nev + 1)), Z(static_cast<size_t>(N * nev)),
            workev(2 * static_cast<size_t>(run.ncv));
        std::vector<a_int> select(static_cast<size_t>(run.ncv));
        a_int info2 = 0;
        arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), d.data(), Z.data(), N, cd(0.0), workev.data(),
                      arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, run.tolerance,
                      run.resid.data(), run.ncv, run.V.data(), N, run.iparam, run.ipntr, run.workd.data(),
                      run.workl.data(), run.lworkl, run.rwork.data(), info2);
        if (info2 != 0) throw SolverError(fmt::format("ARPACK zneupd failed with info = {}", info2));
        const a_int found = std::min<a_int>(run.converged(), nev);
        // Upper half-plane eigenvalues count (the modes); their conjugates do not.
        const auto upper = [&](cd theta) {
            const cd l = s + 1.0 / theta;
            return l.imag() >= -1e-7 * std::abs(l);
        };
        if (run.info == 1 && found < nev &&
            !wanted_complete({d.begin(), d.begin() + found}, ritz.values, ritz.bounds, sz.wanted, upper))
            return std::nullopt;
        std::vector<Ritz> out;
        for (a_int j = 0; j < found; ++j)
            out.push_back({d[static_cast<size_t>(j)], Eigen::Map<const Eigen::VectorXcd>(Z.data() + j * N, N)});
        return out;
    };
    return staged_arnoldi<cd>(opt, sz, apply, extract, iterations);
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
    const auto apply = [&](const double* x, double* y) { apply_operator(lu, p.M, CsM, s, x, y, n); };
    const auto extract = [&](ArnoldiRun<double>& run, const ArnoldiRitz& ritz) -> std::optional<std::vector<Ritz>> {
        const a_int N = run.N, nev = run.nev;
        // dneupd may return one value more than nev (a conjugate pair across the edge).
        std::vector<double> dr(static_cast<size_t>(nev + 1)), di(static_cast<size_t>(nev + 1)),
            Z(static_cast<size_t>(N * (nev + 1))), workev(3 * static_cast<size_t>(run.ncv));
        std::vector<a_int> select(static_cast<size_t>(run.ncv));
        a_int info2 = 0;
        arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), dr.data(), di.data(), Z.data(), N, 0.0, 0.0,
                      workev.data(), arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, run.tolerance,
                      run.resid.data(), run.ncv, run.V.data(), N, run.iparam, run.ipntr, run.workd.data(),
                      run.workl.data(), run.lworkl, info2);
        if (info2 != 0) throw SolverError(fmt::format("ARPACK dneupd failed with info = {}", info2));
        const a_int found = std::min<a_int>(run.converged(), nev + 1);
        if (run.info == 1 && found < nev) {
            std::vector<cd> converged;
            for (a_int j = 0; j < found; ++j) converged.emplace_back(dr[static_cast<size_t>(j)], di[static_cast<size_t>(j)]);
            if (!wanted_complete(converged, ritz.values, ritz.bounds, sz.wanted, [](cd) { return true; }))
                return std::nullopt;
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
    };
    return staged_arnoldi<double>(opt, sz, apply, extract, iterations);
}

}  // namespace

std::vector<Ritz> arnoldi_ritz_pairs(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                                     const Eigen::VectorXd& t, int& iterations) {
    return opt.shift.imag() == 0.0 ? ritz_real(p, opt, sz, t, iterations) : ritz_complex(p, opt, sz, t, iterations);
}

}  // namespace gyrokit::detail
