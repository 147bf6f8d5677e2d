// Mode shapes at one speed as tables and a figure.
// Speeds and frequencies in the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/analysis/mode_shapes.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// Mode shapes at one speed: one row per mode and whirl pair (the orbit: semi-axes
// in the pair's unit, angle and phase in degrees, whirl), in axial order.
// Axial positions z in `length` (the scene's unit).
Table mode_orbit_table(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u,
                       const LengthUnit& length = {});
// One row per mode and DOF: the scaled eigenvector entry (re, im, amplitude, phase).
Table mode_dof_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& dof_names,
                     const std::vector<std::string>& dof_units, double speed, const SpeedUnit& u);
// The modes listed (frequency, damping, whirl, where the largest motion is).
Table mode_list_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& dof_names,
                      double speed, const SpeedUnit& u);
// Rotor with nodes on its axis: the deflected shape at t = 0 (in the plane, u or v,
// of the reference entry, each translational pair) and the orbit's major semi-axis along z, one line per
// mode. Otherwise: each mode's orbits (ellipses of the pairs in metres, else all).
// Where an FE rotor's disks and bearings (and supports) sit on its axis (m), marked
// on the shape panels; empty: nothing marked.
struct AxisMarks {
    std::vector<double> disks, bearings, supports;
};
Figure mode_shape_figure(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u,
                         const std::string& title, const LengthUnit& length = {}, const AxisMarks& marks = {});

}  // namespace gyrokit
