#include "eig/mode.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
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

namespace {

// H x for the Hermitian form x^H H x = sum over the pairs of Im(x_u conj(x_v)).
Eigen::VectorXcd whirl_form(const Eigen::VectorXcd& x, const std::vector<std::pair<int, int>>& pairs) {
    const std::complex<double> half_i(0.0, 0.5);
    Eigen::VectorXcd y = Eigen::VectorXcd::Zero(x.size());
    for (const auto& [u, v] : pairs) {
        y(u) += half_i * x(v);
        y(v) -= half_i * x(u);
    }
    return y;
}

// Turns modes a and b (double eigenvalue) into their most backward and most
// forward combination if both stay eigenvectors to working accuracy.
void separate_pair(Mode& a, Mode& b, const std::vector<std::pair<int, int>>& pairs, const BackwardError& bwd) {
    Eigen::MatrixXcd V(a.right.size(), 2);
    V.col(0) = a.right;
    V.col(1) = b.right;
    const Eigen::Matrix2cd G = V.adjoint() * V;
    if (G.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() < 1e-6 * G.trace().real()) return;   // one direction
    Eigen::MatrixXcd HV(V.rows(), 2);
    HV.col(0) = whirl_form(V.col(0), pairs);
    HV.col(1) = whirl_form(V.col(1), pairs);
    Eigen::Matrix2cd A = V.adjoint() * HV;
    A = 0.5 * (A + A.adjoint()).eval();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2cd> es(A, G);
    if (es.info() != Eigen::Success) return;
    const Eigen::Vector2d mu = es.eigenvalues();   // ascending: backward, forward
    if (mu(1) - mu(0) <= 1e-8) return;             // no whirl content to separate
    Eigen::VectorXcd backward = (V * es.eigenvectors().col(0)).normalized();
    Eigen::VectorXcd forward = (V * es.eigenvectors().col(1)).normalized();
    // Backward below forward, as the pair splits once the rotor turns (and as
    // the modes are listed: by frequency, then by real part).
    const bool a_forward = a.lambda.imag() != b.lambda.imag() ? a.lambda.imag() > b.lambda.imag()
                                                               : a.lambda.real() > b.lambda.real();
    Eigen::VectorXcd& xa = a_forward ? forward : backward;
    Eigen::VectorXcd& xb = a_forward ? backward : forward;
    const double ea = bwd(a.lambda, xa), eb = bwd(b.lambda, xb);
    const double eps = std::numeric_limits<double>::epsilon();
    const double allowed = 10.0 * std::max({a.backward_error, b.backward_error, eps});
    if (!(std::max(ea, eb) <= allowed)) return;
    a.right = std::move(xa);
    b.right = std::move(xb);
    a.backward_error = ea;
    b.backward_error = eb;
}

}  // namespace

void separate_double_whirl(std::vector<Mode>& modes, const std::vector<std::pair<int, int>>& pairs,
                           double real_tol, const BackwardError& backward_error) {
    if (pairs.empty()) return;
    std::vector<bool> done(modes.size(), false);
    for (std::size_t i = 0; i < modes.size(); ++i) {
        if (done[i] || std::abs(modes[i].lambda.imag()) <= real_tol) continue;
        std::size_t best = modes.size();
        double gap = 1e-6 * std::abs(modes[i].lambda);
        for (std::size_t j = i + 1; j < modes.size(); ++j) {
            const double d = std::abs(modes[j].lambda - modes[i].lambda);
            if (!done[j] && d <= gap) {
                gap = d;
                best = j;
            }
        }
        if (best == modes.size()) continue;
        done[i] = done[best] = true;
        separate_pair(modes[i], modes[best], pairs, backward_error);
        modes[i].whirl = classify_whirl(modes[i].lambda, modes[i].right, pairs, real_tol);
        modes[best].whirl = classify_whirl(modes[best].lambda, modes[best].right, pairs, real_tol);
    }
}

double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
    const double na = a.squaredNorm(), nb = b.squaredNorm();
    if (na == 0.0 || nb == 0.0) return 0.0;
    return std::norm(a.dot(b)) / (na * nb);
}

}  // namespace gyrokit
