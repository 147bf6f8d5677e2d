// The two-roller auto-balancer as every front end runs it: the synchronous states and
// their stability per speed range, or a run of the equations of motion (the full ones,
// or the averaged slow-phase ones) with the scene's [simulation] and the request's
// overrides, each checked here with its field named. Speeds in rad/s (the balancer
// scene's own unit).
#pragma once

#include <gyrokit/scene/balancer_scene.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/io/table.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct BalancerRequest {
    bool simulate = false;                  // the equations of motion instead of the synchronous states
    bool averaged = false;                  // with simulate: the averaged slow-phase equations
    std::optional<double> speed;            // with simulate: a prescribed rotor speed, rad/s
    std::optional<double> duration;         // with simulate: s; unset: the scene's [simulation]
    std::optional<std::string> integrator;  // with simulate: the ODE method
    std::optional<double> abs_tol, rel_tol; // with simulate: the ODE tolerances
};

struct BalancerStudy {
    // The synchronous states (simulate false).
    std::vector<StateStability> stability;
    std::vector<RangeVerdict> verdicts;
    // The run (simulate true): the parameters and settings as run.
    AutobalancerParameters params;
    SimulationSettings settings;
    std::optional<SimulationResult> simulation;
    // States: synchronous_states, balancing_ranges; a run: history, final_state.
    std::vector<Table> tables;
};

// The run's parameters and settings alone (no run): InputError naming the field
// (speed, duration, integrator, abs_tol, rel_tol, averaged; a run's field without
// simulate) and its allowed range, and for a scene that cannot be run (no
// [simulation], no bearing damping).
BalancerStudy balancer_plan(const BalancerScene& scene, const BalancerRequest& request);

// An ODE method by name: InputError naming the field integrator.
OdeMethod integrator_of(const std::string& name);

// The study: balancer_plan, then the states or the run (`progress` as OdeOptions takes it).
BalancerStudy balancer_study(const BalancerScene& scene, const BalancerRequest& request,
                             std::function<void(double)> progress = {});

}  // namespace gyrokit
