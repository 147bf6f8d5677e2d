// The undamped critical speed map as a table and a log-log figure.
// Speeds in the chosen unit, stiffness in N/m.
#pragma once

#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>

namespace gyrokit {

// Key "critical_map": one row per stiffness, whirl and number; the rigid-support
// limit last (stiffness inf).
Table critical_map_table(const CriticalSpeedMap& map, const SpeedUnit& u);
// Key "bearing_curves": the bearings' own stiffness over speed.
Table bearing_curve_table(const CriticalSpeedMap& map, const SpeedUnit& u);
// Critical speed against bearing stiffness (log-log): forward solid, backward dashed,
// the rigid-support limits as dotted lines, the bearings' curves in black.
Figure critical_map_figure(const CriticalSpeedMap& map, const SpeedUnit& u, const std::string& title);

}  // namespace gyrokit
