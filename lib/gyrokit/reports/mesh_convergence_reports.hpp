// Mesh convergence as tables: the summary (the mesh chosen, each section's elements) and
// each quantity at each mesh with its change on doubling.
#pragma once

#include <gyrokit/io/table.hpp>
#include <gyrokit/study/mesh_convergence_study.hpp>

#include <vector>

namespace gyrokit {

Table mesh_summary(const MeshConvergenceStudy& s);
Table mesh_quantities(const MeshConvergenceStudy& s);
std::vector<Table> mesh_tables(const MeshConvergenceStudy& s);   // summary, quantities

}  // namespace gyrokit
