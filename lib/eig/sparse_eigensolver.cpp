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

double backward_error(const SparsePencil& p, cd lambda, const Eigen::VectorXcd& x) {
    const double a = std::abs(lambda);
    const double denom = (a * a * p.M.norm() + a * p.C.norm() + p.K.norm()) * x.norm();
    if (denom == 0.0) return 0.0;
    const Eigen::VectorXcd r = (lambda * lambda) * (p.M.cast<cd>() * x) + lambda * (p.C.cast<cd>() * x) +
                               p.K.cast<cd>() * x;
    return r.norm() / denom;
}

SparseSpectrum solve_quadratic_sparse(const SparsePencil& p, const SparseEigenOptions& opt,
                                      const std::vector<std::pair<int, int>>& whirl_pairs) {
    const int n = static_cast<int>(p.M.rows());
    if (n < 2) throw InputError("the sparse eigensolver needs at least 2 DOFs; use the dense solver");
    if (opt.modes < 1 || 2 * opt.modes + 2 > 2 * n - 1)
        throw InputError(fmt::format("--modes {}: allowed for this model with {} DOFs: 1 to {}", opt.modes, n,
                                     std::max(1, n - 2)));
    const cd s = opt.shift;
    // P(sigma) and its sparse LU: the only factorization per call.
    const SpC P = (s * s) * p.M.cast<cd>() + s * p.C.cast<cd>() + p.K.cast<cd>();
    Eigen::SparseLU<SpC, Eigen::COLAMDOrdering<int>> lu;
    lu.compute(P);
    if (lu.info() != Eigen::Success)
        throw InputError(fmt::format("shift ({}, {}) is an eigenvalue or P(shift) is singular ({}); choose another "
                                     "--target",
                                     s.real(), s.imag(), lu.lastErrorMessage()));
    const SpC Mc = p.M.cast<cd>(), CsM = p.C.cast<cd>() + s * p.M.cast<cd>();

    // Conjugates come along with a real shift, so ask for twice the wanted count.
    const a_int N = 2 * n;
    const a_int nev = std::min<a_int>(2 * opt.modes + 2, N - 2);
    a_int ncv = opt.lanczos_vectors > 0 ? opt.lanczos_vectors : std::max<a_int>(2 * nev + 1, 30);
    ncv = std::min<a_int>(ncv, N);
    if (ncv <= nev + 1)
        throw InputError(fmt::format("--lanczos {}: must exceed 2 * modes + 3 = {}", ncv, nev + 1));
    const a_int lworkl = 3 * ncv * ncv + 5 * ncv;
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
    Eigen::VectorXcd v1(n), v2(n), w2(n);
    while (true) {
        arpack::naupd(ido, arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance,
                      resid.data(), ncv, V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl,
                      rwork.data(), info);
        if (ido != -1 && ido != 1) break;
        const cd* x = workd.data() + ipntr[0] - 1;
        cd* y = workd.data() + ipntr[1] - 1;
        v1 = Eigen::Map<const Eigen::VectorXcd>(x, n);
        v2 = Eigen::Map<const Eigen::VectorXcd>(x + n, n);
        w2 = -lu.solve(Mc * v1 + CsM * v2);
        Eigen::Map<Eigen::VectorXcd>(y, n) = v2 + s * w2;
        Eigen::Map<Eigen::VectorXcd>(y + n, n) = w2;
    }
    if (info == 1)
        throw SolverError(fmt::format("ARPACK reached {} restarts with {} of {} Ritz values converged; raise "
                                      "the number of Lanczos vectors (--lanczos, now {}) or move --target closer "
                                      "to the wanted modes",
                                      opt.max_iterations, iparam[4], nev, ncv));
    if (info != 0)
        throw SolverError(fmt::format("ARPACK znaupd failed with info = {}; raise --lanczos (now {})", info, ncv));

    std::vector<cd> d(static_cast<size_t>(nev + 1)), Z(static_cast<size_t>(N * nev)), workev(2 * static_cast<size_t>(ncv));
    std::vector<a_int> select(static_cast<size_t>(ncv));
    a_int info2 = 0;
    arpack::neupd(1, arpack::howmny::ritz_vectors, select.data(), d.data(), Z.data(), N, cd(0.0), workev.data(),
                  arpack::bmat::identity, N, arpack::which::largest_magnitude, nev, opt.tolerance, resid.data(), ncv,
                  V.data(), N, iparam, ipntr, workd.data(), workl.data(), lworkl, rwork.data(), info2);
    if (info2 != 0) throw SolverError(fmt::format("ARPACK zneupd failed with info = {}", info2));

    SparseSpectrum out;
    out.iterations = static_cast<int>(iparam[2]);
    out.converged = static_cast<int>(iparam[4]);
    const double scale = std::sqrt(p.K.norm() / p.M.norm());
    const double real_tol = 1e-7 * (std::isfinite(scale) && scale > 0 ? scale : 1.0);
    for (a_int j = 0; j < out.converged; ++j) {
        const cd theta = d[static_cast<size_t>(j)];
        if (std::abs(theta) == 0.0) continue;
        Mode m;
        m.lambda = s + 1.0 / theta;
        if (m.lambda.imag() < -real_tol) continue;   // the conjugate of a kept mode
        if (std::abs(m.lambda.imag()) <= real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        const Eigen::Map<const Eigen::VectorXcd> z(Z.data() + j * N, N);
        const Eigen::VectorXcd top = z.head(n), bottom = z.tail(n);
        const bool use_top = backward_error(p, m.lambda, top) < backward_error(p, m.lambda, bottom);
        m.right = (use_top ? top : bottom).normalized();
        m.backward_error = backward_error(p, m.lambda, m.right);
        m.whirl = classify_whirl(m.lambda, m.right, whirl_pairs, real_tol);
        out.modes.push_back(std::move(m));
    }
    // The wanted count nearest the shift, reported by frequency.
    std::sort(out.modes.begin(), out.modes.end(),
              [&](const Mode& a, const Mode& b) { return std::abs(a.lambda - s) < std::abs(b.lambda - s); });
    if (static_cast<int>(out.modes.size()) > opt.modes) out.modes.resize(static_cast<size_t>(opt.modes));
    std::sort(out.modes.begin(), out.modes.end(),
              [](const Mode& a, const Mode& b) { return a.lambda.imag() < b.lambda.imag(); });
    return out;
}

}  // namespace gyrokit
