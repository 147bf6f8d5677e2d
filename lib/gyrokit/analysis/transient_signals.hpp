// What engineers read of a transient run (docs/transient.md): the amplitude envelope
// (the peak per revolution), the steady unbalance response at the same speeds to
// compare it with, and the waterfall (spectra of windows of the signal).
#pragma once

#include <gyrokit/analysis/transient.hpp>

#include <vector>

namespace gyrokit {

struct TransientEnvelope {
    std::vector<double> end;          // end of each window, s
    std::vector<int> dofs;            // the DOF of each column
    // windows x dofs: the largest |z| in the window, and the time (s), speed (rad/s) and
    // revolution (counted from 1) where it occurred.
    Eigen::MatrixXd peak, t, speed;
    Eigen::Matrix<long long, Eigen::Dynamic, Eigen::Dynamic> revolution;
};

// The largest |z| of each recorded DOF over whole revolutions of the rotor (phi from
// 2 pi j to 2 pi (j + 1)): the revolutions that end within the same of `max_windows`
// equal spans of the run form one window (at a constant speed or a ramp, windows of
// equal time and speed span), each revolution its own window where fewer than
// `max_windows` are made. The unfinished last revolution is left out; a run shorter
// than one revolution is one window.
TransientEnvelope transient_envelope(const TransientResult& r, int max_windows = 40);

// The steady unbalance response amplitudes |Z_k(w)| of `dofs` at `speeds` (rad/s):
// speeds x dofs; +inf where the dynamic stiffness is singular (an undamped resonance).
Eigen::MatrixXd steady_amplitudes(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  const std::vector<int>& dofs, SolverKind kind = SolverKind::Auto);

// The steady amplitude |Z_k| at the speed of each peak of the envelope: windows x dofs.
Eigen::MatrixXd envelope_steady(const GyroscopicSystem& sys, const TransientEnvelope& e,
                                SolverKind kind = SolverKind::Auto);

struct Waterfall {
    int dof = 0;                      // the model DOF analysed
    std::vector<double> t, speed;     // centre of each window: s, and the speed there (rad/s)
    std::vector<double> frequencies;  // rad/s, from 0 to the band edge (kBandMargin x the top speed)
    Eigen::MatrixXd amplitude;        // windows x frequencies: a sine's amplitude reads as itself
    double window = 0.0;              // length of each window, s (resolution ~ 2 pi / window)
};

// The shortest window of a waterfall in periods of the top speed: its resolution,
// about 2 / kWaterfallPeriods of the top speed between the Hann window's first zeros.
constexpr double kWaterfallPeriods = 16.0;

// Spectra of `windows` Hann-weighted windows of the recorded column `column`, each
// twice the run's length / windows long (half overlapping) but at least
// kWaterfallPeriods periods of the top speed, at `frequencies` points; one window of
// the whole run where the run is shorter. InputError for a column out of range or
// counts out of [2, 10000].
Waterfall transient_waterfall(const TransientResult& r, int column, int windows = 40, int frequencies = 300);

}  // namespace gyrokit
