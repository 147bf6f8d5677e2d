// The undamped critical speed map of an FE rotor: its synchronous critical speeds,
// forward and backward, against the bearings' stiffness over decades, with the
// rigid-support limit, and the bearings' own stiffness (constant or over speed)
// to read the map with (docs/critical_map.md).
//
// At each stiffness k every bearing is an isotropic spring k (cross-coupling and all
// damping removed; pedestals, supports and couplings' springs kept). An undamped rotor
// whirls synchronously at w where lambda = i w solves (K - w^2 (M - i G)) x = 0,
// i.e. the Hermitian-definite pencil (M - i G) x = nu K x with nu = 1 / w^2 > 0
// (K positive definite once the rotor is held); nu <= 0 is a mode that gyroscopic
// stiffening keeps from ever meeting the 1x line.
#pragma once

#include <gyrokit/models/rotor_model.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The critical speeds of each whirl a map shows unless asked otherwise.
constexpr int kCriticalMapModes = 3;

struct CriticalSpeedMapOptions {
    std::vector<double> stiffness;   // N/m, > 0, increasing; empty: default_map_stiffness(model)
    int modes = kCriticalMapModes;   // the lowest critical speeds of each whirl at each stiffness, >= 1
};

struct MapPoint {
    double stiffness = 0.0;          // N/m
    int number = 0;                  // 1, 2, ... by speed within its whirl
    std::string whirl;               // "forward", "backward" (or "planar", "none": anisotropic pedestals)
    double speed = 0.0;              // rad/s
    double backward_error = 0.0;     // of lambda = i speed on the quadratic pencil
};

// A bearing's stiffness over speed, to overlay on the map: where its curve crosses a
// map line the rotor on that bearing has a critical speed.
struct BearingCurve {
    std::string name;                // "kxx bearing 1", "kyy bearing 2": numbered as in the model (bearing_numbers)
    std::vector<double> stiffness;   // N/m
    std::vector<double> speed;       // rad/s (constant bearings: the map's speed span)
};

struct CriticalSpeedMap {
    std::vector<double> stiffness;
    std::vector<MapPoint> points;    // by stiffness, then whirl, then number
    std::vector<MapPoint> rigid;     // the bearings as rigid supports (the limit k -> infinity); stiffness = inf
    std::vector<BearingCurve> bearings;
    double max_backward_error = 0.0;
};

// The default stiffness range: kMapStiffnessPoints values, log spaced, from
// kMapStiffnessFrom to kMapStiffnessTo times the shaft's own stiffness 48 E I / L^3
// (length-weighted mean E I, rotor length L: a simply supported beam loaded at mid-span).
constexpr double kMapStiffnessFrom = 1e-2, kMapStiffnessTo = 1e3;
constexpr int kMapStiffnessPoints = 31;
std::vector<double> default_map_stiffness(const RotorModel& model);

// InputError for a model without bearings, a stiffness list that is not positive and
// increasing, modes < 1, or a rotor the bearings do not hold. The bearings' curves:
// constant bearings at their kxx and kyy; tables and fluid films over speed.
CriticalSpeedMap critical_speed_map(const RotorModel& model, const CriticalSpeedMapOptions& options = {});

}  // namespace gyrokit
