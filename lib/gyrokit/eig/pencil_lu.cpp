#include <gyrokit/eig/detail/pencil_lu.hpp>

#include <gyrokit/core/parallel.hpp>

#include <lapacke.h>

#include <algorithm>
#include <limits>

namespace gyrokit::detail {

using cd = std::complex<double>;

namespace {

// |re| + |im|, the modulus LAPACK's pivot search (izamax) compares.
double abs1(cd z) { return std::abs(z.real()) + std::abs(z.imag()); }

// 1 / z for a finite nonzero z, scaled by its largest part so that |z|^2 neither
// overflows nor underflows (std::complex's division goes through a library call
// that checks for infinities and NaN at every pivot).
cd reciprocal(cd z) {
    const double s = std::max(std::abs(z.real()), std::abs(z.imag()));
    const double a = z.real() / s, b = z.imag() / s;
    const double d = s * (a * a + b * b);
    return {a / d, -b / d};
}

// a[i] -= l[i] * t for i < count, in real arithmetic: std::complex's product checks
// every result for NaN and keeps the loop from vectorizing.
void subtract_multiple(cd* a, const cd* l, cd t, int count) {
    double* ar = reinterpret_cast<double*>(a);
    const double* lr = reinterpret_cast<const double*>(l);
    const double tr = t.real(), ti = t.imag();
    for (int i = 0; i < count; ++i) {
        const double re = lr[2 * i], im = lr[2 * i + 1];
        ar[2 * i] -= re * tr - im * ti;
        ar[2 * i + 1] -= re * ti + im * tr;
    }
}

// sum of conj(a[i]) * x[i] for i < count, in real arithmetic (as above).
cd conjugate_dot(const cd* a, const cd* x, int count) {
    const double* ar = reinterpret_cast<const double*>(a);
    const double* xr = reinterpret_cast<const double*>(x);
    double re = 0.0, im = 0.0;
    for (int i = 0; i < count; ++i) {
        re += ar[2 * i] * xr[2 * i] + ar[2 * i + 1] * xr[2 * i + 1];
        im += ar[2 * i] * xr[2 * i + 1] - ar[2 * i + 1] * xr[2 * i];
    }
    return {re, im};
}

// LU with partial pivoting of a band matrix in LAPACK's band storage (zgbtrf's
// unblocked algorithm, zgbtf2, which zgbtrf itself runs below 32 subdiagonals): by
// columns, the pivot the first of the largest |re| + |im| below the diagonal, rows
// interchanged over the columns U reaches. Own code because zgbtf2 makes four BLAS
// calls per column, which at 7 subdiagonals cost several times the arithmetic.
// Column c is stored by fill(c) just before the elimination first reaches it (while
// it is in cache). False at a zero (or NaN) pivot.
template <class Fill>
bool band_factor(int n, int kl, int ku, cd* ab, int* ipiv, cd* inverse_pivot, const Fill& fill) {
    const int kv = kl + ku;
    const size_t ldab = static_cast<size_t>(2 * kl + ku + 1);
    // A(r, c) is ab[c * ldab + kv + r - c].
    const auto at = [&](int r, int c) -> cd& { return ab[static_cast<size_t>(c) * ldab + static_cast<size_t>(kv + r - c)]; };
    int ju = 0;   // the last column U reaches so far
    for (int c = 0; c < std::min(kv, n); ++c) fill(c);
    for (int j = 0; j < n; ++j) {
        if (j + kv < n) fill(j + kv);
        cd* column = &at(j, j);   // column[i] = A(j + i, j)
        const int km = std::min(kl, n - 1 - j);
        int jp = 0;
        double largest = abs1(column[0]);
        for (int i = 1; i <= km; ++i)
            if (abs1(column[i]) > largest) largest = abs1(column[i]), jp = i;
        ipiv[j] = j + jp + 1;
        if (!(largest > 0.0)) return false;   // zero (or NaN)
        ju = std::max(ju, std::min(j + ku + jp, n - 1));
        if (jp != 0)
            for (int c = j; c <= ju; ++c) std::swap(at(j, c), at(j + jp, c));
        const cd inverse = reciprocal(column[0]);
        inverse_pivot[j] = inverse;
        for (int i = 1; i <= km; ++i) column[i] *= inverse;
        for (int c = j + 1; c <= ju; ++c) {
            cd* row_j = &at(j, c);   // row_j[i] = A(j + i, c)
            if (row_j[0] != 0.0) subtract_multiple(row_j + 1, column + 1, row_j[0], km);
        }
    }
    return true;
}

}  // namespace

// The band storage of the last factorization of this thread, kept for the next
// one: at 10^5 DOFs it is 35 MB, which a fresh allocation would map and zero
// again for every mode at every speed.
static thread_local std::vector<cd> spare_band;
// A kept thread of the parallel loops that goes to sleep frees its spare.
[[maybe_unused]] static const bool spare_released = (on_idle([] { std::vector<cd>().swap(spare_band); }), true);

PencilLU::~PencilLU() {
    if (ab_.capacity() > spare_band.capacity()) spare_band.swap(ab_);
}

bool PencilLU::compute(const SparsePencil& p, cd lambda) {
    n_ = static_cast<int>(p.M.rows());
    // The bandwidths from every stored entry in the order factored (the fill below
    // writes each entry at its distance from the diagonal, so no column's rows may be
    // assumed sorted, nor the order to fit a pattern it was not found for).
    order_ = p.band_order && p.band_order->old_of.size() == static_cast<size_t>(n_) &&
                     p.band_order->new_of.size() == static_cast<size_t>(n_)
                 ? p.band_order
                 : nullptr;
    pattern_bandwidths({&p.M, &p.C, &p.K}, order_.get(), kl_, ku_);
    // An order found for another pattern (a system edited since) may not fit this one:
    // the given order then, where its band is the narrower.
    if (order_ && kl_ + ku_ + 1 > kMaxBandLU) {
        int kl = 0, ku = 0;
        pattern_bandwidths({&p.M, &p.C, &p.K}, nullptr, kl, ku);
        if (kl + ku < kl_ + ku_) order_.reset(), kl_ = kl, ku_ = ku;
    }
    band_ = kl_ + ku_ + 1 <= kMaxBandLU;
    const cd l2 = lambda * lambda;
    if (!band_) {
        order_.reset();
        const Eigen::SparseMatrix<cd> P = l2 * p.M.cast<cd>() + lambda * p.C.cast<cd>() + p.K.cast<cd>();
        sparse_.compute(P);
        return sparse_.info() == Eigen::Success;
    }
    const int ldab = 2 * kl_ + ku_ + 1;
    if (ab_.capacity() < spare_band.capacity()) ab_.swap(spare_band);
    ab_.resize(static_cast<size_t>(ldab) * static_cast<size_t>(n_));
    ipiv_.resize(static_cast<size_t>(n_));
    // Column c of P(lambda) in the order factored: zero, then M's, C's and K's entries
    // (rows c - ku ... c + kl at kl + ku + row - c; the first kl rows are the pivoting's fill).
    const BandOrder* order = order_.get();
    const auto fill = [&](int c) {
        cd* column = ab_.data() + static_cast<size_t>(c) * static_cast<size_t>(ldab);
        std::fill(column, column + ldab, cd(0.0));
        const int source = order ? order->old_of[static_cast<size_t>(c)] : c;
        const auto add = [&](const SparseMatrix& A, cd f) {
            for (SparseMatrix::InnerIterator it(A, source); it; ++it) {
                const int row = order ? order->new_of[static_cast<size_t>(it.row())] : static_cast<int>(it.row());
                column[kl_ + ku_ + row - c] += f * it.value();
            }
        };
        add(p.M, l2);
        add(p.C, lambda);
        add(p.K, cd(1.0));
    };
    // The pivots' reciprocals (kept by the factorization): the substitutions multiply.
    inverse_pivot_.resize(static_cast<size_t>(n_));
    return band_factor(n_, kl_, ku_, ab_.data(), ipiv_.data(), inverse_pivot_.data(), fill);
}

namespace {

// Solves with zgbtrf's factors (P L U, U with kl + ku superdiagonals at row kv of
// the band storage, L's multipliers below it), as zgbtrs does, without its
// per-column BLAS calls (a narrow band makes them mostly call overhead): P x = b
// where x is given, P^H y = c where y is given, both in one pass over the factors
// each way (the substitutions read the factors from memory: at 10^5 DOFs they do
// not fit in cache).
void band_solve(int n, int kl, int ku, const std::vector<cd>& ab, const std::vector<int>& ipiv,
                const std::vector<cd>& inverse_pivot, Eigen::VectorXcd* x, Eigen::VectorXcd* y) {
    const int kv = kl + ku, ldab = 2 * kl + ku + 1;
    const auto at = [&](int row, int col) -> const cd* {
        return &ab[static_cast<size_t>(col) * static_cast<size_t>(ldab) + static_cast<size_t>(row)];
    };
    const auto pivot = [&](int j) { return ipiv[static_cast<size_t>(j)] - 1; };
    for (int j = 0; j < n; ++j) {
        const int i0 = std::max(0, j - kv), below = std::min(kl, n - 1 - j);
        if (y) {   // U^H
            cd& yj = (*y)[j];
            yj = (yj - conjugate_dot(at(kv + i0 - j, j), &(*y)[i0], j - i0)) *
                 std::conj(inverse_pivot[static_cast<size_t>(j)]);
        }
        if (x && j + 1 < n) {   // L, with the row interchanges
            if (pivot(j) != j) std::swap((*x)[pivot(j)], (*x)[j]);
            subtract_multiple(&(*x)[j + 1], at(kv + 1, j), (*x)[j], below);
        }
    }
    for (int j = n - 1; j >= 0; --j) {
        const int i0 = std::max(0, j - kv), below = std::min(kl, n - 1 - j);
        if (x) {   // U
            (*x)[j] *= inverse_pivot[static_cast<size_t>(j)];
            subtract_multiple(&(*x)[i0], at(kv + i0 - j, j), (*x)[j], j - i0);
        }
        if (y && j + 1 < n) {   // L^H, interchanges in reverse
            (*y)[j] -= conjugate_dot(at(kv + 1, j), &(*y)[j + 1], below);
            if (pivot(j) != j) std::swap((*y)[pivot(j)], (*y)[j]);
        }
    }
}

}  // namespace

// v in the order factored (to: true) or back in the given order, through a copy
// kept by the thread (these solves run at every step of every mode).
static thread_local std::vector<cd> reorder_copy;
[[maybe_unused]] static const bool reorder_copy_released =
    (on_idle([] { std::vector<cd>().swap(reorder_copy); }), true);

void PencilLU::reorder(Eigen::VectorXcd& v, bool to) const {
    if (!order_) return;
    reorder_copy.assign(v.data(), v.data() + v.size());
    const std::vector<int>& old_of = order_->old_of;
    if (to)
        for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = reorder_copy[static_cast<size_t>(old_of[static_cast<size_t>(i)])];
    else
        for (Eigen::Index i = 0; i < v.size(); ++i) v[old_of[static_cast<size_t>(i)]] = reorder_copy[static_cast<size_t>(i)];
}

Eigen::VectorXcd PencilLU::solve(const Eigen::VectorXcd& b) const {
    if (!band_) return sparse_.solve(b);
    Eigen::VectorXcd x = b;
    reorder(x, true);
    band_solve(n_, kl_, ku_, ab_, ipiv_, inverse_pivot_, &x, nullptr);
    reorder(x, false);
    return x;
}

Eigen::VectorXcd PencilLU::adjoint_solve(const Eigen::VectorXcd& c) const {
    if (!band_) return sparse_.adjoint().solve(c);
    Eigen::VectorXcd y = c;
    reorder(y, true);
    band_solve(n_, kl_, ku_, ab_, ipiv_, inverse_pivot_, nullptr, &y);
    reorder(y, false);
    return y;
}

void PencilLU::solve_both(const Eigen::VectorXcd& b, const Eigen::VectorXcd& c, Eigen::VectorXcd& x,
                          Eigen::VectorXcd& y) const {
    if (!band_) {
        x = sparse_.solve(b);
        y = sparse_.adjoint().solve(c);
        return;
    }
    x = b;
    y = c;
    reorder(x, true);
    reorder(y, true);
    band_solve(n_, kl_, ku_, ab_, ipiv_, inverse_pivot_, &x, &y);
    reorder(x, false);
    reorder(y, false);
}

}  // namespace gyrokit::detail
