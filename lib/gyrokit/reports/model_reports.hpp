// What a model is: its summary table and, for an FE rotor, its drawing.
// Speeds and frequencies in the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/io/plot.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/reports/mode_shape_reports.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// What a model is, for checking one's own: DOFs by unit, nodes and length, mass
// of a rigid translation, the speed-dependent terms, damping components, bearing
// tables, unbalance, rigid-body eigenvalues at standstill (models up to
// kAutoSparseDofs DOFs; larger ones say "not computed"); for FE rotors the
// elements, sections, disks, bearings and supports. Rows: quantity, value, unit.
Table model_summary(const Scene& scene);
// Where the scene's FE rotor has disks, bearings (constant and tabulated) and supports
// on its axis, for the mode shape figure; empty for other models.
AxisMarks axis_marks(const Scene& scene);
// An FE rotor's geometry along z: the shaft sections (outer and inner radius), the
// disks as given (a disk's `geometry`, one per disk in order: its hollow cylinder;
// none: the solid cylinder with its mass, Id and Ip), bearings and supports at their
// nodes, the nodes on the axis. Lengths in `length` (the scene's unit).
Figure fe_rotor_figure(const FeRotor& rotor, const GyroscopicSystem& system, const std::string& title,
                       const LengthUnit& length = {}, const std::vector<std::optional<DiskGeometry>>& geometry = {});
// The drawing of a scene's FE rotor (its disks as the scene gives them).
Figure fe_rotor_figure(const Scene& scene);

}  // namespace gyrokit
