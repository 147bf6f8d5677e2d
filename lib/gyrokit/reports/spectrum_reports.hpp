// The modes of one speed as a table.
// Speeds and frequencies in the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// With `rigid_body`, the rigid-body eigenvalues follow the modes, whirl "rigid-body".
Table eig_table(const QuadraticSpectrum& s, double speed, const SpeedUnit& u, bool rigid_body = false);
// One line on the rigid-body eigenvalues: how many and which DOFs they move
// (those with at least a tenth of the largest amplitude); empty if none.
std::string rigid_body_note(const std::vector<Mode>& rigid, const std::vector<std::string>& dof_names);

}  // namespace gyrokit
