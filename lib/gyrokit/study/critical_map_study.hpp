// The undamped critical speed map of a scene's FE rotor, as the CLI's critical-map
// and Python's gyrokit.critical_speed_map both run it (docs/critical_map.md).
#pragma once

#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/scene/scene.hpp>

namespace gyrokit {

// InputError for a scene that is not an FE rotor, and as critical_speed_map for the
// options (a stiffness list that is not positive and increasing, modes < 1).
CriticalSpeedMap critical_map_study(const Scene& scene, const CriticalSpeedMapOptions& options = {});

}  // namespace gyrokit
