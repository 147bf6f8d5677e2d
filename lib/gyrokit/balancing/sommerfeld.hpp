// Sommerfeld effect of the motor-driven auto-balancer (Ryzhik, Amer, Duckstein,
// Sperling: "Zum Sommerfeldeffekt beim selbsttätigen Auswuchten in einer Ebene"):
// stationary speed curves (16), (25), (36), (42)/(43), their branches and
// stability, the limit speed estimates (17)/(26)/(43) and the exact folds.
//
// Isotropic bearings (k, c) are required. The vibration torque of an unbalance
// U = m eps running at omega is (15)/(23)
//   V(U, omega) = U^2 c omega^5 / (M^2 (omega_krit^2 - omega^2)^2 + c^2 omega^2).
// With n identical rollers at a common speed omega_e and phase difference 0 (the
// only non-synchronous state, (35)), the stationary equations (22)/(34)/(42) are
//   beta0 omega0 - n beta_e omega_e + V(U0, omega0) = beta0 Omega,
//   beta_e omega_e + n V(U_e, omega_e)              = beta_e omega0,
// where the rotor unbalance and the rollers excite at different frequencies and
// their cross terms average out (41). The curve is explicit in the "hanging"
// speed p (rotor speed without rollers, roller speed otherwise):
//   omega0(p) = p + n V(U_e, p) / beta_e,  Omega(p) = omega0 + (V(U0, omega0) - n beta_e p) / beta0.
// Its local maximum is the exact jump-up speed, the following local minimum the
// jump-down speed (quasi-static decrease of Omega).
#pragma once

#include <gyrokit/balancing/autobalancer.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The reduced parameters of the stationary analysis.
struct SommerfeldSystem {
    int n = 0;                 // rollers
    double M = 0.0, k = 0.0, c = 0.0, omega_krit = 0.0;
    double U0 = 0.0;           // rotor unbalance m0 eps0, kg m
    double Ue = 0.0;           // one roller's m_e eps_e, kg m
    double beta_e = 0.0;       // one roller's beta_e, N m s
    double beta0 = 0.0;        // total beta0 of eq. (6), N m s
    bool compensating = false; // a vibration-free synchronous state exists (two rollers, U0 <= 2 U_e)
};

// Checks the scene for the stationary analysis (motor drive, isotropic bearings
// with c > 0, identical rollers, some unbalance) and reduces it. InputError otherwise.
SommerfeldSystem sommerfeld_system(const AutobalancerParameters& p);

// V(U, omega) above, N m.
double vibration_torque(const SommerfeldSystem& s, double U, double omega);

// (17) without rollers, (26) with one, (43) (factor 2) with two; rad/s.
double limit_speed_estimate(const SommerfeldSystem& s);

// A point of a stationary curve.
struct StationaryPoint {
    double nominal = 0.0;       // Omega = L0 / beta0, rad/s
    double rotor_speed = 0.0;   // omega0, rad/s
    double roller_speed = 0.0;  // omega_e, rad/s (0 without rollers)
    std::string branch;         // resonance, unstable, upper, single, synchronous
    bool stable = false;
};

// Stability of the non-synchronous state: the speed equations have the symmetric
// Jacobian S = [[beta0 + V0', -n beta_e], [-n beta_e, n (beta_e + n V_e')]] and a
// positive definite inertia, so they are stable iff S is positive definite
// (equivalently dOmega/dp > 0); two rollers at phase difference 0 are in addition
// only phase-stable below omega_krit (Section 3.3).
bool curve_point_stable(const SommerfeldSystem& s, double p);

// The synchronous compensated state (37): omega0 = omega_e = beta0 Omega / (beta0 - n beta_e);
// stable above omega_krit. Only when s.compensating.
StationaryPoint synchronous_point(const SommerfeldSystem& s, double Omega);

struct Fold {
    StationaryPoint point;   // nominal speed and speeds at the fold
    double p = 0.0;          // hanging speed at the fold
    bool maximum = false;    // jump-up (local maximum of Omega(p)) or jump-down (local minimum)
};

struct SommerfeldAnalysis {
    SommerfeldSystem system;
    double estimate = 0.0;       // (17)/(26)/(43), rad/s
    std::vector<Fold> folds;     // all local extrema of Omega(p), increasing p
    bool has_jump = false;       // a fold pair exists
    Fold jump_up, jump_down;     // the pair with the largest jump-up speed
};

SommerfeldAnalysis analyse_sommerfeld(const AutobalancerParameters& p);

// The non-synchronous curve at hanging speed p, with its branch (relative to the
// jump pair) and stability.
StationaryPoint curve_point(const SommerfeldAnalysis& a, double p);

// All stationary states at nominal speed Omega: the non-synchronous curve's
// solutions (increasing hanging speed) and, if it exists, the synchronous state.
std::vector<StationaryPoint> stationary_states(const SommerfeldAnalysis& a, double Omega);

// Where a slow (quasi-static) run-up from rest to the nominal speed Omega ends: the
// rotor follows the resonance branch up to its fold, so between jump_down and
// jump_up it stays captured below the resonance although a faster state exists.
enum class QuasiStaticRunup {
    Continuous,       // no fold: the rotor speed follows the nominal speed
    BelowResonance,   // Omega below jump_down: one state only
    Captured,         // jump_down <= Omega < jump_up: held on the resonance branch
    Passes,           // Omega >= jump_up: jumps up at jump_up
};
QuasiStaticRunup quasi_static_runup(const SommerfeldAnalysis& a, double Omega);

// The non-synchronous curve sampled in p over (0, p_max] (for plots).
std::vector<StationaryPoint> stationary_curve(const SommerfeldAnalysis& a, double p_max, int points);

}  // namespace gyrokit
