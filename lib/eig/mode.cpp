#include "eig/mode.hpp"

#include <cmath>
#include <limits>

namespace gyrokit {

std::string to_string(Whirl w) {
    switch (w) {
        case Whirl::Forward: return "forward";
        case Whirl::Backward: return "backward";
        case Whirl::Real: return "real";
        case Whirl::Undefined: break;
    }
    return "undefined";
}

double Mode::damping_ratio() const {
    const double a = std::abs(lambda);
    return a == 0.0 ? 0.0 : 0.0 - lambda.real() / a;   // 0.0 - x: no negative zero in the output
}

double Mode::log_decrement() const {
    if (lambda.imag() > 0.0) return 0.0 - 2.0 * M_PI * lambda.real() / lambda.imag();   // no negative zero
    if (lambda.real() == 0.0) return 0.0;
    return lambda.real() < 0.0 ? std::numeric_limits<double>::infinity()
                               : -std::numeric_limits<double>::infinity();
}

Whirl classify_whirl(std::complex<double> lambda, const Eigen::VectorXcd& x,
                     const std::vector<std::pair<int, int>>& pairs, double real_tol) {
    if (std::abs(lambda.imag()) <= real_tol) return Whirl::Real;
    if (pairs.empty()) return Whirl::Undefined;
    double turn = 0.0;
    for (const auto& [u, v] : pairs) turn += (x(u) * std::conj(x(v))).imag();
    if (lambda.imag() < 0.0) turn = -turn;  // the conjugate pair turns the other way
    return turn >= 0.0 ? Whirl::Forward : Whirl::Backward;
}

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
    const double na = a.squaredNorm(), nb = b.squaredNorm();
    if (na == 0.0 || nb == 0.0) return 0.0;
    return std::norm(a.dot(b)) / (na * nb);
}

}  // namespace gyrokit
