#include "eig/sparse_eigensolver.hpp"

#include "core/error.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <arpack/arpack.hpp>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

using cd = std::complex<double>;
using SpC = Eigen::SparseMatrix<cd>;

namespace {

// Real sparse matrix times complex vector, without a complex copy of the matrix.
Eigen::VectorXcd times(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x) {
    const Eigen::VectorXd re = A * x.real(), im = A * x.imag();
    Eigen::VectorXcd y(re.size());
    y.real() = re;
    y.imag() = im;
    return y;
}

PencilAction action_of(const SparsePencil& p) { return pencil_action(p.M, p.C, p.K, times); }

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
};

// The sparse LU of P(sigma) = sigma^2 M + sigma C + K in the arithmetic of sigma.
template <class Scalar>
void factorize(Eigen::SparseLU<Eigen::SparseMatrix<Scalar>, Eigen::COLAMDOrdering<int>>& lu, const SparsePencil& p,
               Scalar s) {
    const Eigen::SparseMatrix<Scalar> P =
        (s * s) * p.M.cast<Scalar>() + s * p.C.cast<Scalar>() + p.K.cast<Scalar>();
    lu.compute(P);
    if (lu.info() != Eigen::Success)
        throw InputError(fmt::format("shift ({}, {}) is an eigenvalue or P(shift) is singular ({}); choose another "
                                     "--target",
                                     std::real(s), std::imag(s), lu.lastErrorMessage()));
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

void check_arnoldi(const char* routine, a_int info, const a_int* iparam, const SparseEigenOptions& opt,
                   const ArnoldiSize& sz) {
    if (info == 1)
        throw SolverError(fmt::format("ARPACK reached {} restarts with {} of {} Ritz values converged; raise "
                                      "the number of Lanczos vectors (--lanczos, now {}) or move --target closer "
                                      "to the wanted modes",
                                      opt.max_iterations, iparam[4], sz.nev, sz.ncv));
    if (info != 0)
        throw SolverError(fmt::format("ARPACK {} failed with info = {}; raise --lanczos (now {})", routine, info,
                                      sz.ncv));
}

// Complex shift: complex Arnoldi (znaupd) on the complex operator.
std::vector<Ritz> ritz_complex(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                               int& iterations) {
    const int n = static_cast<int>(p.M.rows());
    const cd s = opt.shift;
    Eigen::SparseLU<SpC, Eigen::COLAMDOrdering<int>> lu;
    factorize(lu, p, s);
    const SpC Mc = p.M.cast<cd>(), CsM = p.C.cast<cd>() + s * p.M.cast<cd>();
    const a_int N = sz.N, nev = sz.nev, ncv = sz.ncv, lworkl = 3 * ncv * ncv + 5 * ncv;
    std::vector<cd> resid(static_cast<size_t>(N)), V(static_cast<size_t>(N * ncv)), workd(3 * static_cast<size_t>(N)),
        workl(static_cast<size_t>(lworkl));
    std::vector<double> rwork(static_cast<size_t>(ncv));
    a_int iparam[11] = {1, 0, opt.max_iterations, 1, 0, 0, 1, 0, 0, 0, 0};   // exact shifts, mode 1 on OP
    a_int ipntr[14] = {};
    a_int ido = 0, info = 0;
    if (opt.start.size() == N && opt.start.allFinite() && opt.start.norm() > 0) {
        Eigen::Map<Eigen::VectorXcd>(resid.data(), N) = opt.start;
        info = 1;   // ARPACK starts from resid
    }
    while (true) {
        arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance,
                      resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl,
                      rwork.data(), info);
        if (ido != -1 && ido != 1) break;
        apply_operator(lu, Mc, CsM, s, workd.data() + ipntr[0] - 1, workd.data() + ipntr[1] - 1, n);
    }
    check_arnoldi("znaupd", info, iparam, opt, sz);

    std::vector<cd> d(static_cast<size_t>(nev + 1)), Z(static_cast<size_t>(N * nev)), workev(2 * static_cast<size_t>(ncv));
    std::vector<a_int> select(static_cast<size_t>(ncv));
    a_int info2 = 0;
    arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), d.data(), Z.data(), N, cd(0.0), workev.data(),
                  arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance, resid.data(), ncv,
                  V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl, rwork.data(), info2);
    if (info2 != 0) throw SolverError(fmt::format("ARPACK zneupd failed with info = {}", info2));
    iterations = static_cast<int>(iparam[2]);
    std::vector<Ritz> out;
    for (a_int j = 0; j < iparam[4]; ++j)
        out.push_back({d[static_cast<size_t>(j)], Eigen::Map<const Eigen::VectorXcd>(Z.data() + j * N, N)});
    return out;
}

// Real shift: the operator is real, so real Arnoldi (dnaupd) on a real LU
// finds the same eigenvalues, conjugate pairs together, at a fraction of the
// cost of complex arithmetic.
std::vector<Ritz> ritz_real(const SparsePencil& p, const SparseEigenOptions& opt, const ArnoldiSize& sz,
                            int& iterations) {
    using SpD = Eigen::SparseMatrix<double>;
    const int n = static_cast<int>(p.M.rows());
    const double s = opt.shift.real();
    Eigen::SparseLU<SpD, Eigen::COLAMDOrdering<int>> lu;
    factorize(lu, p, s);
    const SpD CsM = p.C + s * p.M;
    const a_int N = sz.N, nev = sz.nev, ncv = sz.ncv, lworkl = 3 * ncv * ncv + 6 * ncv;
    std::vector<double> resid(static_cast<size_t>(N)), V(static_cast<size_t>(N * ncv)),
        workd(3 * static_cast<size_t>(N)), workl(static_cast<size_t>(lworkl));
    a_int iparam[11] = {1, 0, opt.max_iterations, 1, 0, 0, 1, 0, 0, 0, 0};   // exact shifts, mode 1 on OP
    a_int ipntr[14] = {};
    a_int ido = 0, info = 0;
    if (opt.start.size() == N && opt.start.allFinite() && opt.start.norm() > 0) {
        // A real start spanning the same directions as the complex one.
        Eigen::Map<Eigen::VectorXd>(resid.data(), N) = opt.start.real() + opt.start.imag();
        info = 1;
    }
    while (true) {
        arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance,
                      resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl, info);
        if (ido != -1 && ido != 1) break;
        apply_operator(lu, p.M, CsM, s, workd.data() + ipntr[0] - 1, workd.data() + ipntr[1] - 1, n);
    }
    check_arnoldi("dnaupd", info, iparam, opt, sz);

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
    std::vector<Ritz> out;
    const a_int found = std::min<a_int>(iparam[4], nev + 1);
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

}  // namespace

SparseSpectrum solve_quadratic_sparse(const SparsePencil& p, const SparseEigenOptions& opt,
                                      const std::vector<std::pair<int, int>>& whirl_pairs) {
    const int n = static_cast<int>(p.M.rows());
    if (n < 2) throw InputError("the sparse eigensolver needs at least 2 DOFs; use the dense solver");
    if (opt.modes < 1 || 2 * opt.modes + 2 > 2 * n - 1)
        throw InputError(fmt::format("--modes {}: allowed for this model with {} DOFs: 1 to {}", opt.modes, n,
                                     std::max(1, n - 2)));
    const cd s = opt.shift;
    // Conjugates come along with a real shift, so ask for twice the wanted count.
    ArnoldiSize sz;
    sz.N = 2 * n;
    sz.nev = std::min<a_int>(2 * opt.modes + 2, sz.N - 2);
    sz.ncv = opt.lanczos_vectors > 0 ? opt.lanczos_vectors : std::max<a_int>(2 * sz.nev + 1, 30);
    sz.ncv = std::min<a_int>(sz.ncv, sz.N);
    if (sz.ncv <= sz.nev + 1)
        throw InputError(fmt::format("--lanczos {}: must exceed 2 * modes + 3 = {}", sz.ncv, sz.nev + 1));
    int iterations = 0;
    const std::vector<Ritz> ritz =
        s.imag() == 0.0 ? ritz_real(p, opt, sz, iterations) : ritz_complex(p, opt, sz, iterations);

    SparseSpectrum out;
    out.iterations = iterations;
    out.converged = static_cast<int>(ritz.size());
    const PencilAction action = action_of(p);
    const double scale = std::sqrt(action.norm_K / action.norm_M);
    const double real_tol = 1e-7 * (std::isfinite(scale) && scale > 0 ? scale : 1.0);
    for (const Ritz& r : ritz) {
        if (std::abs(r.theta) == 0.0) continue;
        Mode m;
        m.lambda = s + 1.0 / r.theta;
        if (m.lambda.imag() < -real_tol) continue;   // the conjugate of a kept mode
        if (std::abs(m.lambda.imag()) <= real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        const Eigen::VectorXcd top = r.z.head(n), bottom = r.z.tail(n);
        // The backward error does not depend on the vector's scale: the better half's is the mode's.
        const double et = backward_error(action, m.lambda, top), eb = backward_error(action, m.lambda, bottom);
        m.right = unit_vector(et < eb ? top : bottom);
        m.backward_error = std::min(et, eb);
        m.whirl = classify_whirl(m.lambda, m.right, whirl_pairs, real_tol);
        out.modes.push_back(std::move(m));
    }
    separate_double_whirl(out.modes, whirl_pairs, real_tol, action);
    // The wanted count nearest the shift, reported by frequency.
    std::sort(out.modes.begin(), out.modes.end(),
              [&](const Mode& a, const Mode& b) { return std::abs(a.lambda - s) < std::abs(b.lambda - s); });
    if (static_cast<int>(out.modes.size()) > opt.modes) out.modes.resize(static_cast<size_t>(opt.modes));
    std::stable_sort(out.modes.begin(), out.modes.end(), [](const Mode& a, const Mode& b) {
        return a.lambda.imag() != b.lambda.imag() ? a.lambda.imag() < b.lambda.imag() : a.lambda.real() < b.lambda.real();
    });
    return out;
}

}  // namespace gyrokit
