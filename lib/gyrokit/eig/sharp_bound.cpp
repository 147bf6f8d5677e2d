#include <gyrokit/eig/sharp_bound.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gyrokit {

SharpEigenvalue sharp_eigenvalue(const Mode& m, const SparsePencil& p) {
    using Real = long double;
    using Complex = std::complex<Real>;
    const double inf = std::numeric_limits<double>::infinity();
    const SharpEigenvalue unknown{m.lambda, inf, inf};
    const Eigen::Index n = m.right.size();
    if (m.left.size() != n || p.M.rows() != n || p.C.rows() != n || p.K.rows() != n ||
        !std::isfinite(std::abs(m.lambda)))
        return unknown;
    const Complex l(m.lambda.real(), m.lambda.imag());
    const Real a = std::abs(l);
    std::vector<Complex> r(static_cast<size_t>(n)), d(static_cast<size_t>(n));   // P(l) x and P'(l) x
    std::vector<Real> scale(static_cast<size_t>(n), 0.0L), dscale(static_cast<size_t>(n), 0.0L),
        terms(static_cast<size_t>(n), 0.0L);
    // A's products with x: f A x into r, fd A x into d, their scales |f| |A| |x|, |fd| |A| |x|.
    const auto add = [&](const SparseMatrix& A, Complex f, Complex fd) {
        for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
            const Complex xj(m.right[j].real(), m.right[j].imag());
            for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
                const auto i = static_cast<size_t>(it.row());
                const Real v = it.value();
                r[i] += f * v * xj;
                d[i] += fd * v * xj;
                scale[i] += std::abs(f) * std::abs(v) * std::abs(xj);
                dscale[i] += std::abs(fd) * std::abs(v) * std::abs(xj);
                terms[i] += 1.0L;
            }
        }
    };
    add(p.M, l * l, Real(2) * l);
    add(p.C, l, Complex(1));
    add(p.K, Complex(1), Complex(0));
    Complex yr = 0, yd = 0;
    Real yscale = 0, ydscale = 0, most = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto k = static_cast<size_t>(i);
        const Complex yi(m.left[i].real(), m.left[i].imag());
        yr += std::conj(yi) * r[k];
        yd += std::conj(yi) * d[k];
        yscale += std::abs(yi) * scale[k];
        ydscale += std::abs(yi) * dscale[k];
        most = std::max(most, terms[k]);
    }
    if (!(std::abs(yd) > Real(1e-6) * ydscale)) return unknown;
    const Complex c = yr / yd;
    const Complex exact = l - c;
    const Real left = (most + 3) * std::numeric_limits<Real>::epsilon() * yscale / std::abs(yd) +
                      Real(0.01) * std::abs(c) + Real(std::numeric_limits<double>::epsilon()) * std::abs(exact);
    const double b = static_cast<double>(left);
    if (!std::isfinite(b)) return unknown;
    return {{static_cast<double>(exact.real()), static_cast<double>(exact.imag())}, b, b};
}

}  // namespace gyrokit
