#include "analysis/unbalance_response.hpp"

#include "analysis/scalar_search.hpp"
#include "core/error.hpp"

#include <fmt/format.h>

namespace gyrokit {

Eigen::VectorXcd unbalance_response(const GyroscopicSystem& sys, double w) {
    if (sys.unbalance.size() == 0)
        throw InputError("the model defines no unbalance load; the response is zero");
    const Eigen::VectorXcd f = sys.unbalance_force(w);
    if (w == 0.0) return Eigen::VectorXcd::Zero(sys.size());   // no force at standstill
    const QuadraticPencil p = sys.at_speed(w);
    const std::complex<double> l(0.0, w);
    const Eigen::MatrixXcd S = p.evaluate(l);
    Eigen::PartialPivLU<Eigen::MatrixXcd> lu(S);
    Eigen::VectorXcd Z = lu.solve(f);
    const double res = (S * Z - f).norm(), scale = S.norm() * Z.norm() + f.norm();
    if (!Z.allFinite() || res > 1e-8 * scale)
        throw SolverError(fmt::format("the dynamic stiffness is singular at {} rad/s (an undamped resonance): "
                                      "the response is unbounded; add damping or move the speed grid",
                                      w));
    return Z;
}

ResponseCurve unbalance_response(const GyroscopicSystem& sys, const std::vector<double>& speeds) {
    ResponseCurve c;
    c.speeds = speeds;
    c.Z.resize(static_cast<Eigen::Index>(speeds.size()), sys.size());
    for (size_t i = 0; i < speeds.size(); ++i)
        c.Z.row(static_cast<Eigen::Index>(i)) = unbalance_response(sys, speeds[i]).transpose();
    return c;
}

std::vector<ResponseExtremum> response_extrema(const GyroscopicSystem& sys, const ResponseCurve& c) {
    std::vector<ResponseExtremum> out;
    const Eigen::Index ns = c.Z.rows();
    for (int k = 0; k < sys.size(); ++k) {
        for (Eigen::Index i = 1; i + 1 < ns; ++i) {
            const double a0 = std::abs(c.Z(i - 1, k)), a1 = std::abs(c.Z(i, k)), a2 = std::abs(c.Z(i + 1, k));
            const bool peak = a1 > a0 && a1 >= a2, dip = a1 < a0 && a1 <= a2;
            if (!peak && !dip) continue;
            const double s = peak ? -1.0 : 1.0;
            const auto f = [&](double w) {
                try {
                    return s * std::abs(unbalance_response(sys, w)(k));
                } catch (const SolverError&) {   // exactly on an undamped resonance
                    return s * std::numeric_limits<double>::infinity();
                }
            };
            const double w = find_minimum(f, c.speeds[static_cast<size_t>(i - 1)],
                                          c.speeds[static_cast<size_t>(i + 1)], 1e-12);
            out.push_back({k, peak, w, s * f(w)});
        }
    }
    return out;
}

}  // namespace gyrokit
