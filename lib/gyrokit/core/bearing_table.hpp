// A bearing (or seal) whose stiffness and damping change with spin speed,
// given as a table of coefficients against speed and acting between one DOF
// pair (x, y) and the ground, or a pedestal's DOF pair (px, py):
//   force = -[kxx kxy; kyx kyy] (x - px, y - py) - [cxx cxy; cyx cyy] (x' - px', y' - py'),
// and its opposite on the pedestal.
// Between table speeds every coefficient is interpolated linearly; outside the
// table the end row is held (constant extrapolation), and `covers` tells the
// caller so that it can report it.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>
#include <vector>

namespace gyrokit {

struct BearingCoefficients {
    Eigen::Matrix2d K = Eigen::Matrix2d::Zero();   // N/m
    Eigen::Matrix2d C = Eigen::Matrix2d::Zero();   // N s/m
};

struct BearingTable {
    std::string name;             // e.g. the CSV file it came from; names it in messages
    // The name without its folders (drive_end.csv): tables and legends, where the
    // path the scene was opened by would only differ between machines.
    std::string label() const;
    int dof_x = 0, dof_y = 0;     // 0-based DOF indices of the model
    int pedestal_x = -1, pedestal_y = -1;   // the pair it acts against; -1: the ground
    std::vector<double> speeds;   // rad/s, strictly increasing, at least two
    std::vector<BearingCoefficients> rows;   // one per speed
    // Instead of rows: coefficients computed at any speed (a fluid-film bearing
    // from its geometry); `speeds` then holds one speed, below which the model's
    // values there hold (its validity ends: at standstill a film carries nothing).
    std::function<BearingCoefficients(double)> model = {};
    // false: only the stiffness acts (how a pervasive-damping check takes the
    // other damping components alone).
    bool damping_enabled = true;

    // Coefficients at speed w (linear interpolation, end rows held outside).
    BearingCoefficients at(double w) const;
    // True if w lies inside [speeds.front(), speeds.back()] (a model: w >= speeds.front()).
    bool covers(double w) const;
    bool has_damping() const;

    // Throws InputError naming the table, the item, the value and the allowed range.
    void validate(int dofs) const;

private:
    void validate_rows() const;
};

// One line per table that the speed range leaves: "bearing table NAME covers A..B rad/s;
// speeds outside hold the end values (from X to Y requested)". Empty if all are covered.
std::vector<std::string> extrapolation_notes(const std::vector<BearingTable>& tables, double from, double to);

}  // namespace gyrokit
