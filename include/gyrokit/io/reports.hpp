// Analysis results as tables (stable column names, see docs/cli.md) and figures.
// Speeds and frequencies are converted to the chosen unit; re and im stay in 1/s.
#pragma once

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

namespace gyrokit {

// With `rigid_body`, the rigid-body eigenvalues follow the modes, whirl "rigid-body".
Table eig_table(const QuadraticSpectrum& s, double speed, const SpeedUnit& u, bool rigid_body = false);
// One line on the rigid-body eigenvalues: how many and which DOFs they move
// (those with at least a tenth of the largest amplitude); empty if none.
std::string rigid_body_note(const std::vector<Mode>& rigid, const std::vector<std::string>& dof_names);
// One warning line per unstable range of the diagram (empty: none).
std::vector<std::string> instability_warnings(const CampbellDiagram& cd, const SpeedUnit& u);
Table campbell_table(const CampbellDiagram& cd, const SpeedUnit& u);
// What a person reads of a Campbell diagram in ten seconds: modes tracked, the
// speed range, critical speeds in it (count; the table is critical_table), the
// least damped mode and where, the stability verdict, accuracy, the plot file.
Table campbell_summary(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& critical, const SpeedUnit& u,
                       const std::string& plot_file);
Table critical_table(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u);
Table stability_table(const std::vector<StabilityChange>& sc, const SpeedUnit& u);
Table pervasive_table(const PervasiveReport& r, const SpeedUnit& u);
Table response_table(const std::vector<std::string>& dof_names, const ResponseCurve& c, const SpeedUnit& u);
Table extrema_table(const std::vector<std::string>& dof_names, const std::vector<ResponseExtremum>& e,
                    const SpeedUnit& u);

// Frequencies against speed with the harmonic lines and critical speeds, forward
// whirl solid red, backward dashed blue; damping ratio in a second panel.
Figure campbell_figure(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& cs,
                       const std::vector<int>& harmonics, const SpeedUnit& u, const std::string& title);
// Amplitude (log) and phase per DOF against speed.
Figure response_figure(const std::vector<std::string>& dof_names, const ResponseCurve& c, const SpeedUnit& u,
                       const std::string& title);

}  // namespace gyrokit
