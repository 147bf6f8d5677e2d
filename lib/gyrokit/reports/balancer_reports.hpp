// The two-roller auto-balancer as tables and figures: its synchronous states and
// balancing ranges (the paper's Tabellen 1-3) and a simulation's histories and
// final state. Phases in degrees, speeds in rad/s.
#pragma once

#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// One row per state and speed range (state_stability_ranges); the unbounded top range ends at "inf".
Table synchronous_states_table(const AutobalancerParameters& p, const std::vector<StateStability>& states);
// Per speed range, whether a compensating state is stable and which states are (range_verdicts).
Table balancing_ranges_table(const std::vector<RangeVerdict>& verdicts);

// About 200 samples of the histories, phases wrapped to [0, 360) degrees.
Table simulation_history_table(const SimulationResult& r);
// What the run (`averaged`: the slow-phase equations) ended in, beside the stable
// state of the slow model nearest to it (nearest_stable_state at the final speed).
Table simulation_final_table(const SimulationSettings& s, const SimulationResult& r, bool averaged,
                             const NearestState& predicted);
// The phase histories and, for the full equations, the rotor centre's radius.
Figure simulation_figure(const SimulationResult& r, bool averaged, const std::string& title);

}  // namespace gyrokit
