#include <gyrokit/eig/sharp_bound.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace gyrokit {

PartBounds sharp_part_bounds(const Mode& m, const SparsePencil& p) {
    using Real = long double;
    using Complex = std::complex<Real>;
    const double inf = std::numeric_limits<double>::infinity();
    const Eigen::Index n = m.right.size();
    if (m.left.size() != n || p.M.rows() != n || !std::isfinite(std::abs(m.lambda))) return {inf, inf};
    const Complex l(m.lambda.real(), m.lambda.imag());
    const Real a = std::abs(l);
    std::vector<Complex> r(static_cast<size_t>(n)), d(static_cast<size_t>(n));   // P(l) x and P'(l) x
    std::vector<Real> scale(static_cast<size_t>(n), 0.0L), terms(static_cast<size_t>(n), 0.0L);
    const auto add = [&](const SparseMatrix& A, Complex f, Complex fd, Real fa) {
        for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
            const Complex xj(m.right[j].real(), m.right[j].imag());
            for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
                const auto i = static_cast<size_t>(it.row());
                const Real v = it.value();
                r[i] += f * v * xj;
                d[i] += fd * v * xj;
                scale[i] += fa * std::abs(v) * std::abs(xj);
                terms[i] += 1.0L;
            }
        }
    };
    add(p.M, l * l, Real(2) * l, a * a);
    add(p.C, l, Complex(1), a);
    add(p.K, Complex(1), Complex(0), Real(1));
    Complex yr = 0, yd = 0;
    Real yscale = 0, most = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        const auto k = static_cast<size_t>(i);
        const Complex yi(m.left[i].real(), m.left[i].imag());
        yr += std::conj(yi) * r[k];
        yd += std::conj(yi) * d[k];
        yscale += std::abs(yi) * scale[k];
        most = std::max(most, terms[k]);
    }
    if (!(std::abs(yd) > 0)) return {inf, inf};
    const Complex c = yr / yd;
    const Real rounding = (most + 3) * std::numeric_limits<Real>::epsilon() * yscale / std::abs(yd) +
                          Real(std::numeric_limits<double>::epsilon()) * a + Real(0.01) * std::abs(c);
    const auto part = [&](Real x) {
        const double b = static_cast<double>(2 * std::abs(x) + rounding);
        return std::isfinite(b) ? b : inf;
    };
    return {part(c.real()), part(c.imag())};
}

}  // namespace gyrokit
