// Synchronous states of the auto-balancer (rollers at constant phase relative to
// the rotor) and their stability: the averaged slow-phase equations (32)-(33)
// with the 1/(2 pi) of the average (31) restored, the states (43)-(48), the
// analytic criterion (52) (leading principal minors of the non-symmetric K) and
// the eigenvalues of the linearized slow equations (51).
//
// The slow model is written with complex influence coefficients
// H_x = 1 / (k_x - M Omega^2 + i c_x Omega) (H_y alike), so that it also holds
// with bearing damping: the vibration torque on roller i is
//   V_i = 1/2 f_i Im( e^{i alpha_i} conj((H_x + H_y) F) ),  F = sum_k f_k e^{i alpha_k},
// which for c_x = c_y = 0 is (31) with A_xx + A_yy = H_x + H_y. Slow equations:
//   J_ii alpha_i'' + beta_i alpha_i' + V_i(alpha) = 0.
#pragma once

#include <gyrokit/balancing/autobalancer.hpp>

#include <complex>
#include <limits>
#include <string>
#include <vector>

namespace gyrokit {

// H_x + H_y at Omega; with damped = false the bearing damping is ignored
// (then the value is real: A_xx + A_yy of eq. (27)).
std::complex<double> influence_sum(const AutobalancerParameters& p, double Omega, bool damped);

// V_i of all rollers at phases alpha (rad), N m.
std::vector<double> vibration_torques(const AutobalancerParameters& p, double Omega,
                                      const std::vector<double>& alpha, bool damped);

// dV_i/dalpha_j (n x n, row-major).
std::vector<double> vibration_torque_jacobian(const AutobalancerParameters& p, double Omega,
                                              const std::vector<double>& alpha, bool damped);

// A synchronous state of the undamped slow equations.
struct SynchronousState {
    std::string label;           // two rollers: the paper's equation number "43".."48"; one roller: "0", "pi"
    std::vector<double> alpha;   // rad, in [0, 2 pi)
    bool compensating = false;   // complete compensation (type 1: x = y = 0)
};

// The states that exist for the unbalances (independent of speed, since all
// f_i scale with Omega^2). Two rollers: (43), (44) if the triangle inequality
// (41) holds strictly, then (45), (46), (48), (47) in the order of the paper's
// tables. One roller: alpha = 0 and pi. Throws InputError if the rotor has no
// unbalance (m0 eps0 = 0), where the states are not isolated.
std::vector<SynchronousState> synchronous_states(const AutobalancerParameters& p);

// A speed range in which A_xx + A_yy keeps its sign, eq. (49)-(50).
struct SpeedInterval {
    double from = 0.0, to = std::numeric_limits<double>::infinity();   // rad/s
    std::string name;   // e.g. "Omega < omega_x"
    double sample = 0.0;   // a representative interior speed
};

// The ranges bounded by 0, min(omega_x, omega_y), omega_0 = sqrt((omega_x^2 + omega_y^2)/2),
// max(omega_x, omega_y), infinity; isotropic bearings: 0, omega, infinity.
std::vector<SpeedInterval> speed_intervals(const AutobalancerParameters& p);

// Criterion (52): leading principal minors of K positive (undamped model).
bool stable_by_criterion(const AutobalancerParameters& p, const std::vector<double>& alpha, double Omega);

// Eigenvalues of the linearized slow equations (51) at alpha (2n values).
std::vector<std::complex<double>> slow_eigenvalues(const AutobalancerParameters& p, double Omega,
                                                   const std::vector<double>& alpha, bool damped);

// Largest real part, relative to the largest modulus, below -1e-10 counts as stable.
bool stable_by_eigenvalues(const std::vector<std::complex<double>>& ev);

struct StateStability {
    SynchronousState state;
    SpeedInterval range;
    bool stable_criterion = false;
    bool stable_eigen = false;
    double max_real_eigenvalue = 0.0;   // 1/s, at range.sample
};

// One entry per state and speed range (the paper's Tabellen 1-3), undamped model.
std::vector<StateStability> state_stability_ranges(const AutobalancerParameters& p);

// Per speed range, which synchronous states are stable (criterion (52) and the
// eigenvalues agree): the engineer's question is whether a compensating one is.
struct RangeVerdict {
    SpeedInterval range;
    std::vector<std::string> compensating;   // labels of stable compensating states
    std::vector<std::string> other;          // labels of stable non-compensating states
    std::vector<std::string> disputed;       // criterion and eigenvalues disagree
    // The answer for this range: a compensating state is stable (the CLI column `balances`).
    bool balances() const { return !compensating.empty(); }
};
std::vector<RangeVerdict> range_verdicts(const std::vector<StateStability>& table);

// The synchronous state of the damped slow model (V_i = 0 with complex H) near
// `start`, by Newton's method; with c_x = c_y = 0 this is `start` itself for the
// states (43)-(48). Throws SolverError if Newton does not converge.
std::vector<double> damped_equilibrium(const AutobalancerParameters& p, double Omega, std::vector<double> start);

// The stable state of the damped slow model nearest to the phases `alpha` (largest
// distance of one roller on the circle): which synchronous state a run at speed
// Omega settled in, to check a simulation against the slow model. Each state
// (43)-(48) is moved to its damped equilibrium and kept if its eigenvalues are
// stable. An empty label: no rollers, no rotor unbalance, or no stable state.
struct NearestState {
    std::string label;
    std::vector<double> alpha;   // rad
    double distance = 1e300;     // rad
};
NearestState nearest_stable_state(const AutobalancerParameters& p, double Omega, const std::vector<double>& alpha);

// Right-hand side of the slow equations (state alpha_1, alpha_1', alpha_2, alpha_2').
void slow_rhs(const AutobalancerParameters& p, double Omega, bool damped, const double* s, double* dsdt);

// Phase in [0, 2 pi).
double wrap_phase(double a);
// |a - b| on the circle, in [0, pi].
double phase_distance(double a, double b);

}  // namespace gyrokit
