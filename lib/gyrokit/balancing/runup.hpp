// Run-ups of the motor-driven auto-balancer through the full equations of motion
// (7): the nominal speed Omega(t) = L0(t) / beta0 rises as a sine from 0 to
// max_speed, is held, and falls back to 0 (Bild 4 of the Sommerfeld paper).
// The summary compares the speeds held at the end of the hold phase with the
// stationary curves and says whether the rotor or the rollers were captured at
// the resonance or passed it.
#pragma once

#include <gyrokit/balancing/autobalancer.hpp>
#include <gyrokit/balancing/simulation.hpp>

#include <string>
#include <vector>

namespace gyrokit {

struct RunupSettings {
    double max_speed = 0.0;            // rad/s
    double rise = 0.0, hold = 0.0, fall = 0.0;   // durations of the three phases, s
    std::vector<double> alpha;         // initial roller phases relative to the rotor, rad
    OdeOptions ode = [] {
        OdeOptions o;
        o.abs_tol = o.rel_tol = 1e-9;
        return o;
    }();
    int history_points = 2000;         // uniform samples over the whole run
    double hold_window = 0.25;         // held speeds: means over this final fraction of the hold phase

    double duration() const { return rise + hold + fall; }
    // Throws InputError (durations >= 0, rise and hold > 0, max_speed > 0, tolerances in (0, 1)).
    void validate() const;
};

// The profile: (1 - cos(pi t / rise)) / 2 rise, hold, (1 + cos(pi (t - t1) / fall)) / 2 fall; and its integral.
double runup_nominal_speed(const RunupSettings& s, double t);
double runup_nominal_angle(const RunupSettings& s, double t);

struct RunupResult {
    // Histories.
    std::vector<double> t, nominal, rotor_speed, amplitude;   // rad/s, rad/s, |r| in m
    std::vector<double> torque_rotor, torque_rollers;         // B0 (9) and sum B_i (20), N m
    std::vector<double> phase_difference;                     // |alpha1 - alpha2| on the circle, rad (two rollers)
    std::vector<std::vector<double>> roller_speed;            // phi_i', rad/s
    std::vector<std::vector<double>> alpha;                   // phi_i - phi0, unwrapped, rad
    // Over the final window of the hold phase: mean speeds (exact, from the angle
    // increments), mean amplitude, circular means of the phases.
    double held_nominal = 0.0, held_rotor_speed = 0.0, held_roller_speed = 0.0, held_amplitude = 0.0;
    double held_phase_difference = 0.0;       // rad in [0, pi], two rollers
    std::vector<double> held_alpha;           // rad in [0, 2 pi); meaningful when the rollers are synchronous
    double final_rotor_speed = 0.0;
    OdeStats stats;
};

RunupResult simulate_runup(const AutobalancerParameters& p, const RunupSettings& s);

// What the run-up did, against the stationary analysis at the held nominal speed.
struct RunupSummary {
    std::string outcome;      // "captured" (held on the resonance branch above omega_krit), "passed", "subcritical"
    bool captured = false;
    std::string branch;       // the stable stationary branch nearest to the held speeds
    double stationary_rotor_speed = 0.0, stationary_roller_speed = 0.0;   // on that branch, rad/s
    double omega_krit = 0.0, jump_up = 0.0;   // rad/s (jump_up 0 without a fold)
};

// Throws InputError as sommerfeld_system does.
RunupSummary summarize_runup(const AutobalancerParameters& p, const RunupResult& r);

}  // namespace gyrokit
