// Scene files of the auto-balancer ([model] type = "autobalancer", optional
// [simulation] and [runup]). Isotropic bearings may be given as k (or omega)
// and c instead of the per-axis keys. Every key is range-checked and unknown keys are rejected; an
// error is one InputError line naming the file, the table, the key, the value
// and the allowed range.
#pragma once

#include <gyrokit/balancing/autobalancer.hpp>
#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/simulation.hpp>

#include <string>

namespace gyrokit {

struct BalancerScene {
    std::string file, title;
    AutobalancerParameters params;
    bool has_simulation = false;   // a [simulation] table was given
    SimulationSettings simulation;  // phases converted to rad
    bool has_runup = false;         // a [runup] table was given
    RunupSettings runup;            // phases converted to rad
};

BalancerScene load_balancer_scene(const std::string& path);

}  // namespace gyrokit
