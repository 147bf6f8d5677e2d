// Transient runs as tables (the envelope, the full history) and figures: the orbit
// at constant speed, the run-up envelope against the steady response, the waterfall.
#pragma once

#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/analysis/transient_signals.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// Key "transient": one row per envelope window and DOF: the window's peak (the largest |z|),
// the time_s, speed and revolution where it occurred, dof, unit, and steady (the steady
// unbalance response amplitude at that speed, `steady` windows x DOFs: envelope_steady).
Table transient_table(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                      const TransientEnvelope& e, const Eigen::MatrixXd& steady, const SpeedUnit& u);
// Key "history": every step: time_s, speed, then each recorded DOF by name.
Table transient_history_table(const std::vector<std::string>& dof_names, const TransientResult& r,
                              const SpeedUnit& u);

// The orbit: column cy against column cx over the run (at most about 20,000 points), and
// the steady orbit Re((Zx, Zy) e^{i w t}) dashed; true to shape.
Figure transient_orbit_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                              const TransientResult& r, int cx, int cy, std::complex<double> Zx,
                              std::complex<double> Zy, const std::string& title);
// The run-up picture: the envelope (peak per window) of each DOF against speed, and the
// steady response amplitude at `speeds` (speeds x DOFs) as a thin line in the same colour.
Figure transient_runup_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                              const TransientEnvelope& e, const std::vector<double>& speeds,
                              const Eigen::MatrixXd& steady, const SpeedUnit& u, const std::string& title);
// Waterfalls, one panel each: every window's spectrum drawn as a line raised to the
// window's speed (`by_speed`; else its time, for a constant speed), amplitudes scaled so
// that the largest spans three windows' spacing; the 1x line dashed.
Figure waterfall_figure(const std::vector<std::string>& dof_names, const std::vector<std::string>& dof_units,
                        const std::vector<Waterfall>& w, const SpeedUnit& u, bool by_speed, const std::string& title);

// A run's one-line description: "run-up 0 to 1571 rad/s at 100 rad/s^2 from rest", "at 600 rad/s
// from its steady state" (the acceleration in SpeedUnit::per_second: rad/s^2, Hz/s, rpm/s).
std::string transient_description(const SpeedProfile& p, const SpeedUnit& u, bool steady_start);

// The table a person reads of a run (the CLI's, Python's first): the envelope over 20
// windows of whole revolutions against the steady response, titled with the run.
constexpr int kTransientTableWindows = 20;
// Lengths in `length` (the scene's unit), here and in the figures below.
Table transient_run_table(const GyroscopicSystem& sys, const TransientResult& r, const SpeedUnit& u, bool steady_start,
                          SolverKind kind, const LengthUnit& length = {});

// The picture of a run as the CLI's --plot draws it: at a constant speed the orbit of the
// first two recorded DOFs with the steady orbit (none with fewer than two: InputError), else
// the run-up envelope (400 windows) against the steady response on 1001 speeds.
Figure transient_figure(const GyroscopicSystem& sys, const TransientResult& r, const SpeedUnit& u,
                        bool steady_start, SolverKind kind, const LengthUnit& length = {});
// The waterfall of the first two recorded DOFs (--waterfall).
Figure transient_waterfall_figure(const GyroscopicSystem& sys, const TransientResult& r, const SpeedUnit& u,
                                  bool steady_start, const LengthUnit& length = {});

}  // namespace gyrokit
