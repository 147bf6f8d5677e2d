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

}  // namespace gyrokit
