// Unbalance response as tables and figures (Bode, polar).
// Speeds and frequencies in the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <cstddef>

#include <string>
#include <vector>

namespace gyrokit {

// Lengths as the scene states them: the columns of `Z` (the outputs `outputs`, indices
// into `units`) whose unit is m scaled to `length`, and `units` renamed ("m" -> "mm").
// Before the tables and figures of an mm scene; other units (rad) stay.
void to_length_unit(const std::vector<int>& outputs, Eigen::MatrixXcd& Z, std::vector<std::string>& units,
                    const LengthUnit& length);

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
Table extrema_table(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                    const std::vector<ResponseExtremum>& e,
                    const SpeedUnit& u);

// Bode plot of the DOFs `shown` (empty: every DOF of the curve): amplitude against
// speed, one panel per physical unit, then the phase in degrees. The amplitude axis is
// linear (the half-power band of a peak reads off it) unless `log_amplitude`.
// `axis` names the curve's abscissa ("speed"; a frequency response: "frequency").
Figure response_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                       const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                       const std::vector<int>& shown = {}, const std::string& axis = "speed",
                       bool log_amplitude = false);
// Polar plot: Im Z against Re Z over the speed range, one panel per unit, true to shape.
Figure response_polar_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                             const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                             const std::vector<int>& shown = {}, const std::string& axis = "speed");

}  // namespace gyrokit
