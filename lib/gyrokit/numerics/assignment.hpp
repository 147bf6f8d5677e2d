// Optimal assignment (Hungarian method) used to match modes between speeds.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace gyrokit {

// cost is rows x cols; returns for each row the assigned column or -1 (when
// rows > cols). Minimizes the total cost.
std::vector<int> solve_assignment(const Eigen::MatrixXd& cost);

}  // namespace gyrokit
