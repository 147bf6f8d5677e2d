// gyrokit-bench-tradeoffs: reference eigenvalues. Every eigenpair of a dense
// solver refined by Newton's method in long double on the bordered system
// [P(l) x; v^H x - 1] (v the start vector): solve P(l) u = P'(l) x,
// l <- l - 1 / (v^H u), x <- u / (v^H u). The pencil's double entries are exact
// in long double, so the refined pairs are eigenpairs of the given pencil with
// backward errors near long-double rounding (1e-19 and below), three orders
// below what double precision allows.
#include "reference.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

using namespace gyrokit;

namespace tradeoffs {

namespace {

using cld = std::complex<long double>;
using SpLd = Eigen::SparseMatrix<cld>;
using VecLd = Eigen::Matrix<cld, Eigen::Dynamic, 1>;

}  // namespace

Reference refine_long_double(const SparsePencil& p, const QuadraticSpectrum& start) {
    const SpLd M = p.M.cast<cld>(), C = p.C.cast<cld>(), K = p.K.cast<cld>();
    const long double nM = M.norm(), nC = C.norm(), nK = K.norm();
    const SpLd pattern = M + C + K;
    Eigen::SparseLU<SpLd, Eigen::COLAMDOrdering<int>> lu;
    lu.analyzePattern(pattern);
    Reference ref;
    ref.spectrum = start;
    const auto bwd = [&](cld l, const VecLd& x) {
        const VecLd r = (l * l) * (M * x) + l * (C * x) + K * x;
        return r.norm() / ((std::norm(l) * nM + std::abs(l) * nC + nK) * x.norm());
    };
    for (Mode& m : ref.spectrum.modes) {
        cld l(m.lambda.real(), m.lambda.imag());
        VecLd x = m.right.cast<cld>();
        const VecLd v = x / x.squaredNorm();   // v^H x = 1
        long double e = bwd(l, x);
        for (int it = 0; it < 10 && e > 1e-18L; ++it) {
            SpLd P = (l * l) * M + l * C + K;
            lu.factorize(P);
            if (lu.info() != Eigen::Success) break;   // P(l) singular: l is exact
            const VecLd u = lu.solve((cld(2) * l) * (M * x) + C * x);
            const cld vu = v.dot(u);
            const cld l_next = l - cld(1) / vu;
            const VecLd x_next = u / vu;
            if (!std::isfinite(std::abs(l_next)) || !x_next.allFinite()) break;   // keep the last finite pair
            l = l_next;
            x = x_next;
            e = bwd(l, x);
        }
        const std::complex<double> refined(static_cast<double>(l.real()), static_cast<double>(l.imag()));
        ref.max_move = std::max(ref.max_move, std::abs(refined - m.lambda) / std::abs(m.lambda));
        ref.max_backward_error = std::max(ref.max_backward_error, static_cast<double>(e));
        m.lambda = refined;
    }
    for (size_t i = 0; i < ref.spectrum.modes.size(); ++i)
        for (size_t j = i + 1; j < ref.spectrum.modes.size(); ++j)
            if (std::abs(ref.spectrum.modes[i].lambda - ref.spectrum.modes[j].lambda) <=
                1e-12 * std::abs(ref.spectrum.modes[i].lambda))
                ref.distinct = false;
    return ref;
}

QuadraticSpectrum window(const QuadraticSpectrum& s, int k, std::complex<double> shift) {
    QuadraticSpectrum w = s;
    std::sort(w.modes.begin(), w.modes.end(), [&](const Mode& a, const Mode& b) {
        return std::abs(a.lambda - shift) < std::abs(b.lambda - shift);
    });
    if (static_cast<int>(w.modes.size()) > k) w.modes.resize(static_cast<size_t>(k));
    return w;
}

}  // namespace tradeoffs
