// Frequency response functions as a table and a figure (the response's Bode or
// polar figure over frequency).
#pragma once

#include <gyrokit/analysis/frequency_response.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The unit of each DOF's FRF column: its own unit per the input's force ("m/N",
// "rad/(N m)", ...); "" where the model names no units.
std::vector<std::string> frf_units(const std::vector<std::string>& dof_units, int input);
// The FRF as a curve over frequency (for response_figure and response_polar_figure).
ResponseCurve frf_curve(const FrequencyResponse& r);
// Key "frf": one row per frequency and output DOF: re, im, amplitude, phase (deg).
Table frf_table(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                const FrequencyResponse& r, const SpeedUnit& u);
// Bode (amplitude per unit, linear unless `log_amplitude`, phase) or, with `polar`, Im H
// against Re H; titled with the input DOF and the spin speed.
Figure frf_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                  const FrequencyResponse& r, const SpeedUnit& u, bool polar, bool log_amplitude = false);

}  // namespace gyrokit
