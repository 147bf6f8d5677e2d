// Critical speeds, stability changes and pervasive damping as tables.
// Speeds and frequencies in the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The amplification factor as printed: 3 digits (a half-power width or a damping
// ratio is not known better), "inf" for an undamped mode, "-" where not set.
Cell amplification_cell(const CriticalSpeed& c);
Table critical_table(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u);
// The same split for reading: the critical speeds (API 684: amplification factor
// >= 2.5), then, if any, the heavily damped crossings in a table of their own.
std::vector<Table> critical_tables(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u);
// x rounded to the decade of its bound (no digits below what is vouched for); x
// itself where the bound is 0, infinite or not a number.
double round_to_bound(double x, double bound);
Table stability_table(const std::vector<StabilityChange>& sc, const SpeedUnit& u);
Table pervasive_table(const PervasiveReport& r, const SpeedUnit& u);
// What a pervasive-damping check covered (sets, speeds, modes up to f_cut) and its
// verdict, also where nothing is lost.
Table pervasive_summary(const PervasiveReport& r, const SpeedUnit& u);

}  // namespace gyrokit
