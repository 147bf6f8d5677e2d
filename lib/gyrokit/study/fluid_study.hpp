// The liquid-filled rotor as every front end runs it (gyrokit fluid, gyrokit.fluid):
// the critical speeds with the liquid moving (undamped, damped) and frozen, the
// sloshing coefficients, or with a list of fill levels the sweep of the free-surface
// radius R0 (the paper's Bild 2); speeds in the request's unit, else the scene's.
#pragma once

#include <gyrokit/analysis/fluid_critical_speeds.hpp>
#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/scene/scene.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct FluidRequest {
    std::optional<std::string> unit;                // rad/s, Hz or rpm; unset: the scene's [speeds] units
    std::optional<std::vector<double>> fill;        // free-surface radii R0 (m) of a sweep; unset: the scene's level
};

struct FluidStudy {
    SpeedUnit unit;
    FluidRotor rotor;                         // the scene's fill level, built
    std::optional<FluidCriticalSpeeds> critical;   // without a sweep
    std::optional<FillSweep> sweep;           // with `fill`
    Diagnostics diagnostics;                  // fill levels skipped at a sloshing resonance
};

// InputError naming the scene where its model is no fluid_rotor, and the field `fill`
// with its allowed range 0 < R0 < R.
FluidStudy fluid_study(const Scene& scene, const FluidRequest& request);

}  // namespace gyrokit
