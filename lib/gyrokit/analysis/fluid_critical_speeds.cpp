#include <gyrokit/analysis/fluid_critical_speeds.hpp>

#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

std::string to_string(LiquidModel m) {
    switch (m) {
        case LiquidModel::MovingUndamped: return "moving_undamped";
        case LiquidModel::MovingDamped: return "moving_damped";
        case LiquidModel::Rigid: return "rigid";
    }
    return "?";
}

const std::vector<double>& FluidCriticalSpeeds::of(LiquidModel m) const {
    return m == LiquidModel::MovingUndamped ? moving_undamped : m == LiquidModel::MovingDamped ? moving_damped : rigid;
}

std::vector<double> critical_speeds_quadratic(const FluidRotor& f, double J_eq) {
    // -m J W^2 + (gamma J - m k_t) W + (gamma k_t - delta^2) = 0, W = w^2.
    const double A = -f.m * J_eq;
    const double B = f.k.gamma * J_eq - f.m * f.k.tilt;
    const double C = f.k.gamma * f.k.tilt - f.k.delta * f.k.delta;
    std::vector<double> W;
    if (A == 0.0) {
        if (B != 0.0) W.push_back(-C / B);
    } else {
        const double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            // Stable pair of roots: no cancellation between B and the root.
            const double qq = -0.5 * (B + std::copysign(std::sqrt(disc), B));
            W.push_back(qq / A);
            if (qq != 0.0) W.push_back(C / qq);
        }
    }
    std::vector<double> w;
    for (double x : W)
        if (std::isfinite(x) && x > 0.0) w.push_back(std::sqrt(x));
    std::sort(w.begin(), w.end());
    return w;
}

std::vector<double> critical_speeds_damped(const FluidRotor& f, double w_lo, double w_hi, int points) {
    const auto D = [&f](double w) { return fluid_delta(f, equivalent_inertia_damped(f, w), w); };
    std::vector<double> roots;
    const double r = std::log(w_hi / w_lo) / (points - 1);
    double wa = w_lo, fa = D(wa);
    for (int i = 1; i < points; ++i) {
        const double wb = w_lo * std::exp(r * i), fb = D(wb);
        if (!std::isfinite(fb))
            throw SolverError(fmt::format("Delta(w) is not finite at w = {} rad/s", wb));
        if (fa == 0.0) roots.push_back(wa);
        else if ((fa < 0) != (fb < 0)) roots.push_back(find_root(D, wa, wb, 1e-13));
        wa = wb;
        fa = fb;
    }
    return roots;
}

FluidCriticalSpeeds fluid_critical_speeds(const FluidRotor& f) {
    FluidCriticalSpeeds cs;
    cs.J_eq_rigid = equivalent_inertia_rigid(f);
    cs.rigid = critical_speeds_quadratic(f, cs.J_eq_rigid);
    cs.J_eq = equivalent_inertia(f);
    cs.moving_undamped = critical_speeds_quadratic(f, cs.J_eq);
    double top = std::sqrt(f.k.gamma / f.m);
    for (double w : cs.rigid) top = std::max(top, w);
    for (double w : cs.moving_undamped) top = std::max(top, w);
    cs.moving_damped = critical_speeds_damped(f, 1e-3 * top, 20.0 * top);
    return cs;
}

FillSweep fill_sweep(const FluidRotorParameters& p, const std::vector<double>& fills) {
    FillSweep out;
    for (double R0 : fills) {
        FluidRotorParameters q = p;
        q.R0 = R0;
        const FluidRotor f = build_fluid_rotor(q);
        try {
            out.speeds.push_back(fluid_critical_speeds(f));
        } catch (const SolverError&) {
            ++out.skipped;
            continue;
        }
        out.fills.push_back(R0);
    }
    return out;
}

}  // namespace gyrokit
