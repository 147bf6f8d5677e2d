// Time integration of the auto-balancer: a GSL odeiv2 driver with a selectable
// stepper and tolerances, and the simulation of the full equations of motion
// (18) or of the averaged slow-phase equations.
#pragma once

#include <gyrokit/balancing/autobalancer.hpp>

#include <functional>
#include <string>
#include <vector>

namespace gyrokit {

// GSL odeiv2 steppers. The implicit ones (rk4imp, bsimp, msbdf) get a
// finite-difference Jacobian.
enum class OdeMethod { Rk2, Rk4, Rkf45, Rkck, Rk8pd, Msadams, Rk4imp, Bsimp, Msbdf };

// "rk8pd", "rkf45", ...; anything else is an InputError listing the choices.
OdeMethod parse_ode_method(const std::string& name);
std::string ode_method_name(OdeMethod m);
const std::vector<std::string>& ode_method_names();

struct OdeOptions {
    OdeMethod method = OdeMethod::Rk8pd;
    double abs_tol = 1e-10;   // per component, in the state's units
    double rel_tol = 1e-10;
    double h0 = 0.0;          // first step, s (0: a small fraction of the first output interval)
    unsigned long max_steps = 100000000;   // accepted steps over the whole run
    // Called at most twice a second with the fraction of the time span done (and
    // once with 1 at the end, if it was called before); e.g. a progress bar.
    std::function<void(double)> progress;
    // The work done up to time t, in any unit (e.g. the phase of the fastest
    // oscillation, rad): the steps so far are projected to the end of the run in
    // proportion to it. Unset: in proportion to time.
    std::function<double(double)> work;
};

struct OdeStats {
    unsigned long steps = 0;        // accepted steps
    unsigned long evaluations = 0;  // right-hand-side calls
    double seconds = 0.0;           // wall time
};

// f(t, y, dydt) returns false with a reason when it cannot be evaluated.
using OdeRhs = std::function<bool(double t, const double* y, double* dydt, const char** why)>;

// Integrates y from t0 through the increasing times `t_out`, calling
// on_output(t, y) at each. Throws SolverError naming the time and the reason
// when the driver fails (step size underflow, no progress, step limit, a
// right-hand side that cannot be evaluated), and early, after 2 s of wall time,
// when the steps so far project a run of more than 1.5 x max_steps. Throws
// Interrupted when a stop is requested (core/interrupt.hpp).
void integrate_ode(const OdeRhs& f, std::vector<double>& y, double t0, const std::vector<double>& t_out,
                   const OdeOptions& o, const std::function<void(double, const double*)>& on_output,
                   OdeStats* stats = nullptr);

struct SimulationSettings {
    double duration = 10.0;           // s
    std::vector<double> alpha;        // initial relative phases, rad (one per roller)
    double x = 0.0, y = 0.0;          // initial rotor centre, m
    OdeOptions ode;
    double average_revolutions = 20;  // the final phases are means over this many last revolutions
    int samples_per_revolution = 16;  // in that window
    int history_points = 2000;        // samples of the phase histories over the whole run
};

struct SimulationResult {
    // Histories (history_points + 1 samples): time, relative phases (unwrapped, rad), rotor speed, |r|.
    std::vector<double> t, speed, radius;
    std::vector<std::vector<double>> alpha;
    // Means over the final window: relative phases in [0, 2 pi), rotor speed.
    std::vector<double> final_alpha;
    double final_speed = 0.0;
    double residual_rms = 0.0, residual_max = 0.0;   // rotor centre radius over the final window, m
    double revolutions = 0.0;
    OdeStats stats;
};

// Integrates the full equations of motion (18).
SimulationResult simulate(const AutobalancerParameters& p, const SimulationSettings& s);

// Integrates the averaged slow-phase equations (damped influence coefficients) at
// the reference speed; only phases and speed are filled, the residual is the
// amplitude of the averaged vibration |(H_x + H_y)/2| |F| (isotropic estimate).
SimulationResult simulate_averaged(const AutobalancerParameters& p, const SimulationSettings& s);

}  // namespace gyrokit
