// The Sommerfeld effect of a motor-driven rotor / auto-balancer as every front end runs
// it: the stationary speed curves with their branches, stability, limit speed estimate
// and exact folds over the request's nominal speeds (by default the range the curves
// need), or a run-up through the full equations of motion with the scene's [runup] and
// the request's overrides, each checked here with its field named. Speeds in rad/s.
#pragma once

#include <gyrokit/scene/balancer_scene.hpp>
#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/table.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct SommerfeldRequest {
    bool runup = false;                     // a run-up instead of the stationary curves
    std::optional<SpeedRange> speeds;       // the curves' nominal speeds, rad/s; unset: stationary_speeds
    std::optional<std::string> integrator;  // with runup: the ODE method
    std::optional<double> abs_tol, rel_tol; // with runup: the ODE tolerances
    std::optional<double> max_speed;        // with runup: the largest nominal speed, rad/s
};

struct SommerfeldStudy {
    // The stationary analysis (also behind a run-up's summary).
    SommerfeldAnalysis analysis;
    SpeedRange speeds;
    // The run-up (runup true): its settings as run, the run and its summary.
    RunupSettings settings;
    std::optional<RunupResult> runup;
    std::optional<RunupSummary> summary;
    // Curves: stationary_states, folds, summary; a run-up: runup_history, summary.
    std::vector<Table> tables;
};

// The settings alone (no analysis, no run): InputError naming the field (speeds,
// integrator, abs_tol, rel_tol, max_speed; a run-up's field without runup, speeds
// with it) and its allowed range, and for a scene without [runup] where one is asked.
SommerfeldStudy sommerfeld_plan(const BalancerScene& scene, const SommerfeldRequest& request);

// The study: sommerfeld_plan, then the curves or the run-up (`progress` as OdeOptions takes it).
SommerfeldStudy sommerfeld_study(const BalancerScene& scene, const SommerfeldRequest& request,
                                 std::function<void(double)> progress = {});

}  // namespace gyrokit
