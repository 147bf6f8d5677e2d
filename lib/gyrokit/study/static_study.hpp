// The static analysis of a scene's FE rotor at standstill: its speed-dependent
// bearings (tables, fluid films) hold their nodes rigidly (a film at standstill
// carries its load at the clearance's edge: no stiffness of its own, no motion),
// constant bearings act as their springs (docs/static.md).
#pragma once

#include <gyrokit/scene/scene.hpp>
#include <gyrokit/analysis/static_deflection.hpp>

namespace gyrokit {

// InputError for a scene that is not an FE rotor, or a speed-dependent bearing on a
// pedestal (its standstill stiffness is not defined).
StaticResult static_study(const Scene& scene, StaticOptions options = {});

}  // namespace gyrokit
