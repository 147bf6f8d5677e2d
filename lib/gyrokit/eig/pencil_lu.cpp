#include <gyrokit/eig/detail/pencil_lu.hpp>

#include <lapacke.h>

#include <algorithm>
#include <limits>
#include <type_traits>

namespace gyrokit::detail {

using cd = std::complex<double>;
static_assert(std::is_same_v<lapack_int, int>, "the pivots are kept as int");

namespace {

// Lower and upper bandwidths of the pencil's pattern.
void bandwidths(const SparsePencil& p, int& kl, int& ku) {
    kl = ku = 0;
    for (const SparseMatrix* A : {&p.M, &p.C, &p.K})
        for (Eigen::Index k = 0; k < A->outerSize(); ++k)
            for (SparseMatrix::InnerIterator it(*A, k); it; ++it) {
                kl = std::max(kl, static_cast<int>(it.row() - it.col()));
                ku = std::max(ku, static_cast<int>(it.col() - it.row()));
            }
}

}  // namespace

// The band storage of the last factorization of this thread, kept for the next
// one: at 10^5 DOFs it is 35 MB, which a fresh allocation would map and zero
// again for every mode at every speed.
static thread_local std::vector<cd> spare_band;

PencilLU::~PencilLU() {
    if (ab_.capacity() > spare_band.capacity()) spare_band.swap(ab_);
}

bool PencilLU::compute(const SparsePencil& p, cd lambda) {
    n_ = static_cast<int>(p.M.rows());
    bandwidths(p, kl_, ku_);
    band_ = kl_ + ku_ + 1 <= kMaxBandLU;
    const cd l2 = lambda * lambda;
    if (!band_) {
        const Eigen::SparseMatrix<cd> P = l2 * p.M.cast<cd>() + lambda * p.C.cast<cd>() + p.K.cast<cd>();
        sparse_.compute(P);
        return sparse_.info() == Eigen::Success;
    }
    const int ldab = 2 * kl_ + ku_ + 1;
    if (ab_.capacity() < spare_band.capacity()) ab_.swap(spare_band);
    ab_.assign(static_cast<size_t>(ldab) * static_cast<size_t>(n_), cd(0.0));
    const auto add = [&](const SparseMatrix& A, cd f) {
        for (Eigen::Index k = 0; k < A.outerSize(); ++k)
            for (SparseMatrix::InnerIterator it(A, k); it; ++it)
                ab_[static_cast<size_t>(it.col()) * ldab + static_cast<size_t>(kl_ + ku_ + it.row() - it.col())] +=
                    f * it.value();
    };
    add(p.M, l2);
    add(p.C, lambda);
    add(p.K, cd(1.0));
    ipiv_.assign(static_cast<size_t>(n_), 0);
    const lapack_int info = LAPACKE_zgbtrf_work(LAPACK_COL_MAJOR, n_, n_, kl_, ku_,
                                           reinterpret_cast<lapack_complex_double*>(ab_.data()), ldab, ipiv_.data());
    if (info != 0) return false;   // info > 0: an exactly zero pivot
    // The pivots' reciprocals once: the substitutions then multiply.
    inverse_pivot_.resize(static_cast<size_t>(n_));
    for (int j = 0; j < n_; ++j)
        inverse_pivot_[static_cast<size_t>(j)] = 1.0 / ab_[static_cast<size_t>(j) * ldab + static_cast<size_t>(kl_ + ku_)];
    return true;
}

namespace {

// Solves with zgbtrf's factors (P L U, U with kl + ku superdiagonals at row kv of
// the band storage, L's multipliers below it), as zgbtrs does, without its
// per-column BLAS calls (a narrow band makes them mostly call overhead).
Eigen::VectorXcd band_solve(bool adjoint, int n, int kl, int ku, const std::vector<cd>& ab, const std::vector<int>& ipiv,
                            const std::vector<cd>& inverse_pivot, Eigen::VectorXcd x) {
    const int kv = kl + ku, ldab = 2 * kl + ku + 1;
    const auto at = [&](int row, int col) -> const cd& {
        return ab[static_cast<size_t>(col) * static_cast<size_t>(ldab) + static_cast<size_t>(row)];
    };
    if (!adjoint) {
        for (int j = 0; j + 1 < n; ++j) {   // L, with the row interchanges
            const int l = ipiv[static_cast<size_t>(j)] - 1;
            if (l != j) std::swap(x[l], x[j]);
            const cd xj = x[j];
            for (int k = 1, lm = std::min(kl, n - 1 - j); k <= lm; ++k) x[j + k] -= xj * at(kv + k, j);
        }
        for (int j = n - 1; j >= 0; --j) {   // U
            x[j] *= inverse_pivot[static_cast<size_t>(j)];
            const cd xj = x[j];
            for (int i = std::max(0, j - kv); i < j; ++i) x[i] -= xj * at(kv + i - j, j);
        }
    } else {
        for (int j = 0; j < n; ++j) {   // U^H
            cd s = x[j];
            for (int i = std::max(0, j - kv); i < j; ++i) s -= std::conj(at(kv + i - j, j)) * x[i];
            x[j] = s * std::conj(inverse_pivot[static_cast<size_t>(j)]);
        }
        for (int j = n - 2; j >= 0; --j) {   // L^H, interchanges in reverse
            cd s = x[j];
            for (int k = 1, lm = std::min(kl, n - 1 - j); k <= lm; ++k) s -= std::conj(at(kv + k, j)) * x[j + k];
            x[j] = s;
            const int l = ipiv[static_cast<size_t>(j)] - 1;
            if (l != j) std::swap(x[l], x[j]);
        }
    }
    return x;
}

}  // namespace

Eigen::VectorXcd PencilLU::solve(const Eigen::VectorXcd& b) const {
    if (!band_) return sparse_.solve(b);
    return band_solve(false, n_, kl_, ku_, ab_, ipiv_, inverse_pivot_, b);
}

Eigen::VectorXcd PencilLU::adjoint_solve(const Eigen::VectorXcd& b) const {
    if (!band_) return sparse_.adjoint().solve(b);
    return band_solve(true, n_, kl_, ku_, ab_, ipiv_, inverse_pivot_, b);
}

}  // namespace gyrokit::detail
