// The transient unbalance response as every front end runs it: a constant speed or a
// run-up / run-down in the study's unit (the scene's [speeds] units unless the call
// names one), the recorded DOFs by name or node, the start, duration, step and step
// limit, each checked here with its field named; the run and its table in the study's
// unit and the scene's length unit.
#pragma once

#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/study/request.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct TransientRequest {
    std::optional<double> speed;                  // a constant speed, in the study's unit
    std::optional<std::array<double, 2>> run_up;  // from, to, in the study's unit
    std::optional<double> acceleration;           // the study's unit per s; > 0 up, < 0 down
    std::optional<double> duration;               // s; unset: the ramp, or 100 revolutions
    std::optional<double> dt;                     // s; unset: transient_time_step
    std::vector<std::string> dofs;                // recorded DOFs by name
    std::optional<int> node;                      // or the lateral translations of this node
    std::optional<std::string> start;             // rest (default) or steady
    std::optional<long long> max_steps;           // unset: defaults::max_steps
};

struct TransientStudy {
    SpeedUnit unit;
    LengthUnit length;
    TransientOptions options;   // as run (speeds in rad/s), the solver kind decided
    TransientResult result;
    Table table;                // the envelope against the steady response (transient_run_table)
};

// The options alone, checked as the run would check them (no run): InputError naming the
// field (speed, run_up, acceleration, duration, dt, dofs, node, start, max_steps) and its
// allowed range; `common` as
// resolve_request takes it (unit, solver; speeds are not used).
TransientOptions transient_options(const Scene& scene, const RotorRequest& common, const TransientRequest& request);

// The run: transient_options, then transient_response (SolverError where it fails).
TransientStudy transient_study(const Scene& scene, const RotorRequest& common, const TransientRequest& request);

}  // namespace gyrokit
