// Analysis results as tables (stable column names, see docs/cli.md) and figures.
// Speeds and frequencies are converted to the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/mode_shapes.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/scene.hpp>
#include <gyrokit/io/table.hpp>
#include <optional>

namespace gyrokit {

// With `rigid_body`, the rigid-body eigenvalues follow the modes, whirl "rigid-body".
Table eig_table(const QuadraticSpectrum& s, double speed, const SpeedUnit& u, bool rigid_body = false);
// One line on the rigid-body eigenvalues: how many and which DOFs they move
// (those with at least a tenth of the largest amplitude); empty if none.
std::string rigid_body_note(const std::vector<Mode>& rigid, const std::vector<std::string>& dof_names);
// One warning line per unstable range of the diagram (empty: none).
// One line naming the modes out of range (CampbellDiagram::out_of_range); empty if none.
std::string out_of_range_note(const CampbellDiagram& cd, const SpeedUnit& u);
std::vector<std::string> instability_warnings(const CampbellDiagram& cd, const SpeedUnit& u);
Table campbell_table(const CampbellDiagram& cd, const SpeedUnit& u);
// What a person reads of a Campbell diagram in ten seconds: modes tracked, the
// speed range, critical speeds in it (count; the table is critical_table), the
// least damped mode and where, the stability verdict over every mode (`window`:
// a sparse window's modes only, which it says), accuracy, the plot file.
Table campbell_summary(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& critical, const SpeedUnit& u,
                       const std::string& plot_file, bool window = false);
Table critical_table(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u);
// The same split for reading: the critical speeds (API 684: amplification factor
// >= 2.5), then, if any, the heavily damped crossings in a table of their own.
std::vector<Table> critical_tables(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u);
// x rounded to the decade of its bound (no digits below what is vouched for); x
// itself where the bound is 0, infinite or not a number.
double round_to_bound(double x, double bound);
Table stability_table(const std::vector<StabilityChange>& sc, const SpeedUnit& u);
Table pervasive_table(const PervasiveReport& r, const SpeedUnit& u);
// Every row of the curve; `unit` is the DOF's unit ("" if the model names none).
Table response_table(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                     const ResponseCurve& c, const SpeedUnit& u);
// What a person reads of a response: the largest amplitude of each DOF (refined
// peaks, response_maxima), by unit and then amplitude, at most `limit` per unit
// (0: all); the title says how many were left out.
Table response_summary(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                       const std::vector<ResponseMaximum>& maxima, const SpeedUnit& u, std::size_t limit);
// The DOFs a plot of many shows: those with the `per_unit` largest maxima in each unit.
std::vector<int> largest_responses(const std::vector<std::string>& dof_units,
                                   const std::vector<ResponseMaximum>& maxima, std::size_t per_unit);
// Mode shapes at one speed: one row per mode and whirl pair (the orbit: semi-axes
// in the pair's unit, angle and phase in degrees, whirl), in axial order.
Table mode_orbit_table(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u);
// One row per mode and DOF: the scaled eigenvector entry (re, im, amplitude, phase).
Table mode_dof_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& dof_names,
                     const std::vector<std::string>& dof_units, double speed, const SpeedUnit& u);
// The modes listed (frequency, damping, whirl, where the largest motion is).
Table mode_list_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& dof_names,
                      double speed, const SpeedUnit& u);
// Rotor with nodes on its axis: the deflected shape at t = 0 (in the plane, u or v,
// of the reference entry, each translational pair) and the orbit's major semi-axis along z, one line per
// mode. Otherwise: each mode's orbits (ellipses of the pairs in metres, else all).
Figure mode_shape_figure(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u,
                         const std::string& title);
Table extrema_table(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                    const std::vector<ResponseExtremum>& e,
                    const SpeedUnit& u);

// Frequencies against speed with the harmonic lines and critical speeds, forward
// whirl solid red, backward dashed blue; damping ratio in a second panel.
Figure campbell_figure(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& cs,
                       const std::vector<int>& harmonics, const SpeedUnit& u, const std::string& title);
// Bode plot of the DOFs `shown` (empty: every DOF of the curve): amplitude (log)
// against speed, one panel per physical unit, then the phase in degrees.
Figure response_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                       const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                       const std::vector<int>& shown = {});
// Polar plot: Im Z against Re Z over the speed range, one panel per unit, true to shape.
Figure response_polar_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                             const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                             const std::vector<int>& shown = {});

// What a model is, for checking one's own: DOFs by unit, nodes and length, mass
// of a rigid translation, the speed-dependent terms, damping components, bearing
// tables, unbalance, rigid-body eigenvalues at standstill (models up to
// kAutoSparseDofs DOFs; larger ones say "not computed"); for FE rotors the
// elements, sections, disks, bearings and supports. Rows: quantity, value, unit.
Table model_summary(const Scene& scene);
// An FE rotor's geometry along z: the shaft sections (outer and inner radius),
// the disks (radius and width of the solid cylinder with their mass, Id and Ip),
// bearings and supports at their nodes, the nodes on the axis.
Figure fe_rotor_figure(const FeRotor& rotor, const GyroscopicSystem& system, const std::string& title);

}  // namespace gyrokit
