// The API 617 Level I stability screen of a scene's FE rotor, as the CLI (gyrokit
// level1) and Python (gyrokit.level1) run it: the machine data from the scene's [api]
// with the caller's values on top, QA from the stages, where Q acts, the curve of the
// first forward mode's log decrement against Q at the maximum continuous speed, Q0,
// the critical speed ratio and the verdict, at each end of the bearings' tolerance bands
// (docs/level1.md).
#pragma once

#include <gyrokit/analysis/level1_stability.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/request.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct Level1Request {
    std::optional<std::string> unit;              // rad/s, Hz or rpm: of the speeds in and out
    std::optional<std::string> machine;           // centrifugal or axial
    std::optional<double> mcs;                    // in unit
    std::optional<double> operating_speed;        // in unit
    std::optional<double> qa;                     // N/m: replaces the stages' QA
    std::optional<double> station;                // in the scene's length unit: where Q acts
    std::optional<double> gas_density;            // kg/m^3
    std::optional<double> q_ratio;                // the curve's range in multiples of QA
    std::optional<int> intervals;                 // equal steps of the curve
    std::optional<std::string> method;            // the dense eigensolver: qz, qz-classic or state
};

// One screen on the bearings as given, or one at each end of the fluid films' clearance
// and viscosity bands where a bearing gives them (bearing_extremes); the verdict is the
// worse screen's. InputError for a scene without an FE rotor or machine data, naming the
// missing key (mcs, qa or stages) and each value out of range.
Level1Study level1_study(const Scene& scene, const Level1Request& request = {});

}  // namespace gyrokit
