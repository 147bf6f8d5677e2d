// Independent computations of the API 684 tests (Level I, the API unbalance cases,
// their seeded random family): the eigenvalue nearest a shift by our own state matrix,
// the steady unbalance response by our own LU, an orbit's peak-to-peak by sampling its
// ellipse, and API 617's margins, Avl, Scc and clearance ratios written out by hand.
#pragma once

#include <gyrokit/core/constants.hpp>
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

namespace gyrokit::test {

// The eigenvalue of the pencil nearest `sigma`, independently: the state matrix
// A = [0 I; -M^-1 K, -M^-1 C], (A - sigma I)^-1 by LU, its eigenvalue of largest modulus mu,
// lambda = sigma + 1 / mu.
inline std::complex<double> nearest_eigenvalue(const GyroscopicSystem& sys, double speed, std::complex<double> sigma) {
    const QuadraticPencil p = sys.at_speed(speed);
    const int n = static_cast<int>(p.M.rows());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    const Eigen::LLT<Eigen::MatrixXd> m(p.M);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -m.solve(p.K);
    A.bottomRightCorner(n, n) = -m.solve(p.C);
    const Eigen::MatrixXcd shifted = A.cast<std::complex<double>>() - sigma * Eigen::MatrixXcd::Identity(2 * n, 2 * n);
    const Eigen::MatrixXcd B = shifted.partialPivLu().inverse();
    const Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(B, false);
    Eigen::Index k = 0;
    es.eigenvalues().cwiseAbs().maxCoeff(&k);
    return sigma + 1.0 / es.eigenvalues()(k);
}

inline double rpm(double x) { return x * 2.0 * kPi / 60.0; }

// The case's unbalance vector, built from its loads (x: U e^{i phase}, y: -i U e^{i phase}).
inline Eigen::VectorXcd unbalance_of(const GyroscopicSystem& sys, const ApiUnbalanceCase& c) {
    Eigen::VectorXcd u = Eigen::VectorXcd::Zero(sys.size());
    for (const ApiUnbalanceLoad& l : c.loads) {
        const std::complex<double> f = l.unbalance * std::polar(1.0, l.phase);
        u(sys.dofs.find(l.node, DofMotion::x)) += f;
        u(sys.dofs.find(l.node, DofMotion::y)) += std::complex<double>(0, -1) * f;
    }
    return u;
}

// The steady response by our own LU: (K(w) - w^2 M + i w C(w)) Z = w^2 u.
inline Eigen::VectorXcd response(const GyroscopicSystem& sys, const Eigen::VectorXcd& u, double w) {
    const QuadraticPencil p = sys.at_speed(w);
    const std::complex<double> i(0, 1);
    const Eigen::MatrixXcd d = p.K.cast<std::complex<double>>() - w * w * p.M.cast<std::complex<double>>() +
                               i * w * p.C.cast<std::complex<double>>();
    return d.fullPivLu().solve(w * w * u);
}

// Twice the largest distance of the sampled orbit (x, y) = Re((Zx, Zy) e^{i t}) from its centre.
inline double sampled_peak_to_peak(std::complex<double> zx, std::complex<double> zy) {
    double far = 0.0;
    const int n = 40000;
    for (int k = 0; k < n; ++k) {
        const std::complex<double> e = std::polar(1.0, 2.0 * kPi * k / n);
        far = std::max(far, std::hypot((zx * e).real(), (zy * e).real()));
    }
    return 2.0 * far;
}

inline double pp_at(const GyroscopicSystem& sys, const Eigen::VectorXcd& u, const ApiLocation& l, double w) {
    const Eigen::VectorXcd z = response(sys, u, w);
    return sampled_peak_to_peak(z(sys.dofs.find(l.node, DofMotion::x)), z(sys.dofs.find(l.node, DofMotion::y)));
}

// API 617 2.6.2.10's required margin, written out.
inline double required_margin(double af, bool above) {
    if (af < 2.5) return 0.0;
    const double t = 17.0 * (1.0 - 1.0 / (af - 1.5));
    return above ? std::min(26.0, 10.0 + t) : std::min(16.0, t);
}

// Margins, Scc and the clearance ratios of a case, by hand from its numbers.
inline void check_rules(const ApiUnbalanceStudy& s, const ApiUnbalanceCase& c) {
    bool met = true;
    for (const ApiCritical& k : c.criticals) {
        const double w = k.critical.speed;
        const double af = k.critical.amplification;
        const bool above = w > s.mcs, below = w < s.min_speed;
        const double have = below ? 100 * (s.min_speed - w) / s.min_speed : above ? 100 * (w - s.mcs) / s.mcs : 0.0;
        const double need = required_margin(af, above);
        CHECK(k.required == Approx(need).margin(1e-12));
        CHECK(k.margin.percent == Approx(have).margin(1e-10));
        CHECK(k.met == (need == 0.0 || ((below || above) && have >= need)));
        met = met && k.met;
    }
    CHECK(c.margins_met == met);
    const double n_rpm = std::clamp(c.concern, s.min_speed, s.mcs) * 60 / (2 * kPi);
    CHECK(c.avl == Approx(std::min(25.4e-6, 25.4e-6 * std::sqrt(12000 / n_rpm))).epsilon(1e-13));
    CHECK(c.scale == Approx(std::clamp(c.avl / c.a1, 0.5, 6.0)).epsilon(1e-13));
    for (std::size_t k = 0; k < s.locations.size(); ++k) {
        if (s.locations[k].probe) continue;
        const ApiAmplitude& a = c.amplitudes[k];
        const double checked = (met ? 1.0 : c.scale) * a.peak_to_peak;
        CHECK(a.ratio == Approx(checked / (0.75 * s.locations[k].clearance)).epsilon(1e-13));
    }
}

}  // namespace gyrokit::test
