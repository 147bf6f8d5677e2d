// The Sommerfeld effect as tables and figures: stationary speed curves, folds and
// a summary at the motor's nominal speed; a run-up's histories and summary.
// Speeds in rad/s, phases in degrees.
#pragma once

#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>

namespace gyrokit {

// The nominal speeds shown when none are asked for: 0 to 1.25 times the larger of
// the motor's nominal speed L0 / beta0 and the jump-up speed (the limit speed
// estimate without a fold), 201 speeds.
SpeedRange stationary_speeds(const AutobalancerParameters& p, const SommerfeldAnalysis& a);
// Every stationary state at each nominal speed of `speeds` (stationary_states).
Table stationary_states_table(const SommerfeldAnalysis& a, const SpeedRange& speeds);
Table folds_table(const SommerfeldAnalysis& a);
// At the motor's nominal speed L0 / beta0: the limit speed estimate and its
// equation, the jumps, the states there and where a slow run-up ends.
Table sommerfeld_summary_table(const AutobalancerParameters& p, const SommerfeldAnalysis& a);
// Rotor and roller speeds against the nominal speed over `speeds`, unstable parts
// dashed, with the synchronous state and the estimate.
Figure stationary_figure(const SommerfeldAnalysis& a, const SpeedRange& speeds, const std::string& title);

// About 200 samples of the run-up's histories.
Table runup_history_table(const RunupResult& r);
// The settings, the speeds held at the end of the hold phase and what the run-up did.
Table runup_summary_table(const RunupSettings& s, const RunupResult& r, const RunupSummary& sm);
// Speeds, vibration amplitude and vibration torques against time.
Figure runup_figure(const AutobalancerParameters& p, const RunupResult& r, const std::string& title);

}  // namespace gyrokit
