// Critical speeds of the liquid-filled rotor (models/fluid_rotor.hpp): synchronous
// forward whirl, the positive roots of Delta(w) = (gamma - m w^2)(gamma l^2/4 +
// J_eq w^2) - delta^2 for three models of the liquid.
#pragma once

#include <gyrokit/models/fluid_rotor.hpp>

#include <string>
#include <vector>

namespace gyrokit {

enum class LiquidModel { MovingUndamped, MovingDamped, Rigid };
std::string to_string(LiquidModel m);   // "moving_undamped" | "moving_damped" | "rigid"

struct FluidCriticalSpeeds {
    std::vector<double> moving_undamped;   // rad/s, increasing
    std::vector<double> moving_damped;
    std::vector<double> rigid;
    double J_eq = 0;         // undamped equivalent inertia (speed independent), kg m^2
    double J_eq_rigid = 0;   // I - J_rigid, kg m^2
    const std::vector<double>& of(LiquidModel m) const;
};

// Positive roots of the quadratic in w^2 for a speed-independent J_eq.
std::vector<double> critical_speeds_quadratic(const FluidRotor& f, double J_eq);

// Roots of Delta(w) with the damped equivalent inertia: scan of a logarithmic
// speed grid for sign changes, each refined by GSL Brent. The grid spans
// [w_lo, w_hi] with `points` points.
std::vector<double> critical_speeds_damped(const FluidRotor& f, double w_lo, double w_hi, int points = 4000);

// All three models; the damped scan covers 1e-3 to 20 times the largest
// undamped or rigid critical speed.
FluidCriticalSpeeds fluid_critical_speeds(const FluidRotor& f);

// Critical speeds over fill levels (free-surface radii R0, m) of the rotor `p`.
// A level exactly at a sloshing resonance has no undamped answer: it is left out
// and counted, so that a sweep does not fail for one unlucky point.
struct FillSweep {
    std::vector<double> fills;                 // R0 of the levels with an answer, m
    std::vector<FluidCriticalSpeeds> speeds;   // one per entry of fills
    int skipped = 0;
};
FillSweep fill_sweep(const FluidRotorParameters& p, const std::vector<double>& fills);

}  // namespace gyrokit
