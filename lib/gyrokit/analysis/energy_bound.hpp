// A bound on how fast any mode of the system can grow, from its energy alone: no
// eigenvalue is solved, so it covers every mode (also the mesh's highest) at the
// cost of a few symmetric eigenvalue problems.
//
// With M and the symmetric part K_s of the stiffness positive definite, the
// energy E = (z'^T M z' + z^T K_s z) / 2 of a free motion changes as
//   dE/dt = -z'^T S z' - z'^T K_k z,   S = (C + C^T)/2,  K_k = (K - K^T)/2
// (the skew part of C, gyroscopic, does no work). In mass-normalised coordinates
// (hats: L^-1 A L^-T with M = L L^T) this gives dE/dt <= 2 rho E with
//   rho = max(0, -mu_min(S^)) + ||K_k^||_2 / (2 sqrt(mu_min(K_s^))),
// so |z| grows no faster than exp(rho t): every eigenvalue has Re lambda <= rho.
// Damping that is positive semi-definite and stiffness without circulatory part
// give rho = 0 (Kelvin-Tait-Chetaev: no mode of any speed is unstable); cross-
// coupled bearings (K_k != 0) make rho large and the bound says little.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct GrowthRateBound {
    bool holds = false;   // M and K_s positive definite at every speed: the bound applies
    double rate = std::numeric_limits<double>::infinity();   // 1/s: Re lambda <= rate for every eigenvalue
    double speed = 0.0;   // rad/s: where the rate is largest (holds) or where it failed
    std::string reason;   // why it does not hold
};

// Above this many DOFs the bound is not formed (it works on dense matrices).
constexpr int kGrowthBoundMaxDofs = 1000;

// The bound over `speeds` (rad/s), the largest rate of them, with the rounding
// of the symmetric eigenvalues (n eps ||A|| / mu_min(M), Golub & Van Loan 8.7) on
// the unsafe side of each term. Speeds are solved once where nothing depends on
// speed but the gyroscopic matrix. The speeds are left as soon as the rate passes
// `stop_above` (1/s): then `rate` is that speed's, a lower bound of the largest.
GrowthRateBound growth_rate_bound(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  double stop_above = std::numeric_limits<double>::infinity());

// The log decrement below which no mode counts as growing: any rotor's material
// damping (a log decrement of 1e-3 and more for steel) outweighs it.
constexpr double kNeutralLogDec = 1e-6;

// The rate that keeps every mode above `band` (rad/s) neutral or decaying: such a
// mode has Im lambda > band, so its log decrement is at least -2 pi rate / band.
double neutral_rate(double band);

// The bound over `speeds` where it shows that no mode above `band` grows (its rate
// at most neutral_rate(band)); none where it does not hold or allows more.
std::optional<GrowthRateBound> modes_above_band_decay(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                                      double band);

}  // namespace gyrokit
