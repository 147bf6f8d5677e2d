// The static analysis of an FE rotor as tables and a figure: deflection and slope
// per node, shear force and bending moment along the shaft, reactions, a summary.
// Lengths in m, deflections in m (the figure in micrometres), forces in N, moments in N m.
#pragma once

#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/models/fe_statics.hpp>

#include <string>

namespace gyrokit {

Table static_node_table(const StaticResult& s);       // key "deflection"
Table static_section_table(const StaticResult& s);    // key "internal_forces": each element's start and end
Table static_reaction_table(const StaticResult& s);   // key "reactions"
// Key "static": the weight, the largest deflection and bending moment and where, the checks.
Table static_summary_table(const StaticResult& s);
// Deflection (x and y, um) and bending moment (N m) along z, reactions marked.
Figure static_figure(const StaticResult& s, const std::string& title);

}  // namespace gyrokit
