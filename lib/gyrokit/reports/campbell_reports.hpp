// A Campbell diagram as a table, its summary, notes and figure.
// Speeds and frequencies in the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// One line naming the modes out of range (CampbellDiagram::out_of_range); empty if none.
std::string out_of_range_note(const CampbellDiagram& cd, const SpeedUnit& u);
// One warning line per unstable range (empty: none), edges as refined (refine_edges).
std::vector<std::string> instability_warnings(const std::vector<UnstableRange>& unstable, const SpeedUnit& u);
// "from A to B unit": each edge to the digits its bound vouches for, a grid speed
// inside the range named as such.
std::string unstable_span(const UnstableRange& r, const SpeedUnit& u);
Table campbell_table(const CampbellDiagram& cd, const SpeedUnit& u);
// What a person reads of a Campbell diagram in ten seconds: modes tracked, the
// speed range, critical speeds in it (count; the table is critical_table), the
// least damped mode and where, the stability verdict over every mode (`window`:
// a sparse window's modes only, which it says; `unstable`: the refined ranges of
// every mode), accuracy, the plot file.
Table campbell_summary(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& critical,
                       const std::vector<UnstableRange>& unstable, const SpeedUnit& u,
                       const std::string& plot_file, bool window = false);
// Frequencies against speed with the harmonic lines and critical speeds, forward
// whirl solid red, backward dashed blue; damping ratio in a second panel.
Figure campbell_figure(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& cs,
                       const std::vector<int>& harmonics, const SpeedUnit& u, const std::string& title);

}  // namespace gyrokit
