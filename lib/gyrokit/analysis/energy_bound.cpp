// The energy bound on the growth rate of every mode (energy_bound.hpp).
#include <gyrokit/analysis/energy_bound.hpp>

#include <gyrokit/core/constants.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

// M = L L^T with a lower bound on its least eigenvalue (the computed one less its rounding).
struct MassFactor {
    Eigen::LLT<Eigen::MatrixXd> llt;
    double mu_min = 0.0;
    double norm = 0.0;
};

// The least eigenvalue of L^-1 A L^-T (A symmetric) and its rounding allowance:
// the Cholesky reduction's error n eps (||A|| + |mu| ||M||) / mu_min(M).
struct Least {
    double value = 0.0;
    double allowance = 0.0;
};

Eigen::MatrixXd reduced(const Eigen::MatrixXd& A, const MassFactor& m) {
    // L^-1 A L^-T, formed as L^-1 (L^-1 A)^T: A is symmetric.
    const Eigen::MatrixXd X = m.llt.matrixL().solve(A);
    Eigen::MatrixXd H = m.llt.matrixL().solve(X.transpose());
    return H;
}

Least least_eigenvalue(const Eigen::MatrixXd& A, const MassFactor& m) {
    Eigen::MatrixXd H = reduced(A, m);
    H = 0.5 * (H + H.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H, Eigen::EigenvaluesOnly);
    Least l;
    l.value = es.eigenvalues().minCoeff();
    const double n = static_cast<double>(A.rows());
    l.allowance = n * eps * (A.norm() + std::abs(l.value) * m.norm) / m.mu_min;
    return l;
}

bool speed_independent(const GyroscopicSystem& sys) {
    if (!sys.bearings.empty() || sys.has_circulatory() || sys.has_speed_squared_stiffness()) return false;
    for (const DampingComponent& d : sys.damping)
        if (d.of_speed) return false;
    // The gyroscopic matrix adds to S only where it is not exactly skew.
    return sys.G.nonZeros() == 0 || SparseMatrix(sys.G + SparseMatrix(sys.G.transpose())).norm() == 0.0;
}

// The rate at one speed; holds = false with the reason where K_s is not definite.
GrowthRateBound at_speed(const GyroscopicSystem& sys, const MassFactor& m, double w) {
    GrowthRateBound b;
    b.speed = w;
    const QuadraticPencil p = sys.at_speed(w);
    const Least k = least_eigenvalue(0.5 * (p.K + p.K.transpose()), m);
    if (!(k.value - k.allowance > 0.0)) {
        b.reason = fmt::format("the stiffness is not positive definite at {:.6g} rad/s (least eigenvalue of "
                               "K_s with M: {:.3g}, within rounding of 0 or below): a rigid-body or a statically "
                               "unstable motion has no energy bound",
                               w, k.value);
        return b;
    }
    const Least s = least_eigenvalue(0.5 * (p.C + p.C.transpose()), m);
    double rate = std::max(0.0, s.allowance - s.value);
    const Eigen::MatrixXd Kk = 0.5 * (p.K - p.K.transpose());
    if (Kk.norm() > 0.0) {
        const double n = static_cast<double>(Kk.rows());
        const double kk = reduced(Kk, m).norm() + n * eps * Kk.norm() / m.mu_min;   // Frobenius >= 2-norm
        rate += kk / (2.0 * std::sqrt(k.value - k.allowance));
    }
    b.holds = std::isfinite(rate);
    b.rate = rate;
    if (!b.holds) b.reason = fmt::format("the bound is not finite at {:.6g} rad/s", w);
    return b;
}

}  // namespace

GrowthRateBound growth_rate_bound(const GyroscopicSystem& sys, const std::vector<double>& speeds, double stop_above) {
    GrowthRateBound out;
    if (speeds.empty()) {
        out.reason = "no speeds";
        return out;
    }
    if (sys.size() > kGrowthBoundMaxDofs) {
        out.reason = fmt::format("{} DOFs: the bound works on dense matrices, up to {}", sys.size(),
                                 kGrowthBoundMaxDofs);
        return out;
    }
    MassFactor m;
    const Eigen::MatrixXd M = sys.M.dense();
    m.llt.compute(M);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> me(M, Eigen::EigenvaluesOnly);
    m.norm = M.norm();
    m.mu_min = me.eigenvalues().minCoeff() - static_cast<double>(M.rows()) * eps * m.norm;
    if (m.llt.info() != Eigen::Success || !(m.mu_min > 0.0)) {
        out.reason = "the mass matrix is not positive definite (a DOF without mass)";
        return out;
    }
    const bool once = speed_independent(sys);
    out.rate = 0.0;
    out.holds = true;
    for (double w : speeds) {
        const GrowthRateBound b = at_speed(sys, m, w);
        if (!b.holds) return b;
        if (b.rate >= out.rate) out.rate = b.rate, out.speed = w;
        if (once || out.rate > stop_above) break;
    }
    return out;
}

double neutral_rate(double band) { return kNeutralLogDec * band / (2.0 * kPi); }

std::optional<GrowthRateBound> modes_above_band_decay(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                                      double band) {
    if (!(band > 0.0) || !std::isfinite(band)) return std::nullopt;
    const GrowthRateBound b = growth_rate_bound(sys, speeds, neutral_rate(band));
    if (!b.holds || !(b.rate <= neutral_rate(band))) return std::nullopt;
    return b;
}

}  // namespace gyrokit
