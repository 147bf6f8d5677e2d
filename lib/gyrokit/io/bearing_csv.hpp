// Bearing coefficient tables from CSV: a header line naming the columns, then
// one row per speed. Required columns (any order; extra columns ignored):
// speed (rad/s), dof_x, dof_y (0-based DOF indices, equal in every row),
// kxx, kxy, kyx, kyy (N/m), cxx, cxy, cyx, cyy (N s/m). Lines starting with '#'
// and blank lines are skipped.
#pragma once

#include <gyrokit/core/bearing_table.hpp>

#include <string>

namespace gyrokit {

// Throws InputError "<path>: line <n>: <what is wrong>; <what is allowed>".
// The table is checked against `dofs` (the model size). With `dof_x`, `dof_y`
// given (>= 0: a finite-element bearing at a node) the columns dof_x, dof_y
// are not needed and, if present, ignored.
BearingTable read_bearing_csv(const std::string& path, int dofs, int dof_x = -1, int dof_y = -1);

}  // namespace gyrokit
