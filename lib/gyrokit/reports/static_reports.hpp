// The static analysis of an FE rotor as tables and a figure: deflection and slope
// per node, shear force and bending moment along the shaft, reactions, a summary.
// Lengths in m, deflections in m (the figure in micrometres), forces in N, moments in N m.
#pragma once

#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/analysis/static_deflection.hpp>

#include <string>

namespace gyrokit {

// Lengths (positions z, deflections x and y) in `length`, the scene's unit; forces in N,
// moments in N m, slopes in rad.
Table static_node_table(const StaticResult& s, const LengthUnit& length = {});       // key "deflection"
// Key "internal_forces": each element's start and end.
Table static_section_table(const StaticResult& s, const LengthUnit& length = {});
Table static_reaction_table(const StaticResult& s, const LengthUnit& length = {});   // key "reactions"
// Key "static": the weight, the largest deflection and bending moment and where, the checks.
Table static_summary_table(const StaticResult& s, const LengthUnit& length = {});
// Every table of a static analysis, deflection first (what CSV holds by default).
std::vector<Table> static_tables(const StaticResult& s, const LengthUnit& length = {});
// Deflection (x and y, um) and bending moment (N m) along z (in `length`), reactions marked.
Figure static_figure(const StaticResult& s, const std::string& title, const LengthUnit& length = {});

}  // namespace gyrokit
