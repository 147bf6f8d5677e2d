// Transient response of a rotor by time integration (docs/transient.md): the model
//   M z'' + (D(w) + w G) z' + (K + w N + w^2 K2 + bearings(w)) z = Re(u (phi'^2 - i phi'') e^{i phi})
// under its unbalance u with the rotor's angle phi(t), at a constant speed or in a
// run-up / run-down w(t) = w0 + alpha t, integrated by the Newmark average-acceleration
// method (gamma = 1/2, beta = 1/4: unconditionally stable, second order, and the
// energy of an undamped linear system is conserved).
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/core/speed_range.hpp>

#include <memory>
#include <string>
#include <vector>

namespace gyrokit {

// The speed history: w(t) = from + acceleration t until the speed reaches `to`,
// then `to` held. acceleration 0: the constant speed `from` (to == from).
struct SpeedProfile {
    double from = 0.0, to = 0.0;   // rad/s
    double acceleration = 0.0;     // rad/s^2; > 0 for a run-up, < 0 for a run-down
    // The end of the ramp, (to - from) / acceleration (0 at constant speed).
    double ramp_end() const;
    double speed(double t) const;          // phi'(t), rad/s
    double angle(double t) const;          // phi(t), rad, phi(0) = 0
    double angular_acceleration(double t) const;   // phi''(t), rad/s^2
    double top() const { return from > to ? from : to; }
    // InputError naming the field (speed, run_up, acceleration), the value and the allowed range.
    void validate(const SpeedUnit& u = {}) const;   // messages name speeds in `u`
};

// The unbalance force at time t: Re(u (phi'^2 - i phi'') e^{i phi}), the reaction of the
// unbalance masses to their acceleration (x of a mass m e: m e (phi'^2 cos phi + phi'' sin phi));
// at constant speed w^2 Re(u e^{i w t}).
Eigen::VectorXd unbalance_force_at(const Eigen::VectorXcd& u, const SpeedProfile& p, double t);

// Steps per period of the highest frequency the default time step resolves.
constexpr int kStepsPerPeriod = 32;
// The default limit of time steps of one run, and the largest a caller may allow.
constexpr long long kTransientMaxSteps = 2000000;
constexpr long long kTransientStepLimit = 50000000;
// The relative change of speed after which the speed-dependent coefficients
// (bearing tables, fluid films, speed-dependent damping) are evaluated afresh.
constexpr double kCoefficientSpeedStep = 1e-3;

// The default time step: kStepsPerPeriod steps per period of the excitation band's
// upper edge (kBandMargin times the top speed), which bounds every mode the run can
// excite; the unbalance at the top speed gets kBandMargin times as many.
double transient_time_step(const SpeedProfile& p);

// What a constant-speed run settles on: the trapezoidal rule's steady state is exactly
// the steady response at the frequency w_hat = (2/dt) tan(w dt/2) (the spin held at w),
// so each output's amplitude differs from the steady |Z_k(w)| by |Z_k(w_hat)| / |Z_k(w)| - 1,
// computed by one solve per step tried. The default step of such a run keeps that within
// kSteadyDeviation / 2 (the other half left to the peak's sampling) for every output of at
// least 1e-3 of the largest: the band's step, shortened where needed, down to
// kSteadyStepFloor of it and to no more than `max_steps` steps over `duration`.
constexpr double kSteadyDeviation = 1e-3;
constexpr double kSteadyStepFloor = 1.0 / 16.0;
struct SteadyStep {
    double dt = 0.0;           // s
    double deviation = 0.0;    // the largest relative deviation of the outputs at dt
};
// The relative deviation at a given step (SolverError where the dynamic stiffness at w is
// singular: no steady response).
double steady_deviation(const GyroscopicSystem& sys, double speed, double dt, const std::vector<int>& outputs,
                        SolverKind kind = SolverKind::Auto);
SteadyStep steady_time_step(const GyroscopicSystem& sys, const SpeedProfile& p, const std::vector<int>& outputs,
                            double duration, long long max_steps, SolverKind kind = SolverKind::Auto);

// One Newmark average-acceleration integrator of a model, stepping z, z', z'' with a
// force given at each step. The effective matrix S(w) = 4/dt^2 M + 2/dt C(w) + K(w) is
// factored once (dense LU, or sparse LU above kAutoSparseDofs) and again only when
// needed: G, N and K2 enter at the exact speed of each step through a residual
// correction with the last factorization; the speed-dependent coefficients are held
// until the speed has moved by kCoefficientSpeedStep relative (of the speed, at least
// of 1% of `speed_scale`), then evaluated afresh and S refactored.
class NewmarkIntegrator {
public:
    struct Stats {
        long long steps = 0;
        int factorizations = 0;      // LU factorizations of S
        int coefficient_updates = 0; // evaluations of the speed-dependent coefficients
        int max_corrections = 0;     // residual corrections in one solve
        double max_residual = 0.0;   // largest ||S z - r|| / (||S|| ||z|| + ||r||) accepted
    };

    // Keeps a copy of `sys`; `speed_scale` (rad/s, e.g. the top speed) sets the coefficient
    // rule's floor near standstill. InputError for a dt that is not finite and > 0.
    NewmarkIntegrator(const GyroscopicSystem& sys, double dt, double speed_scale, SolverKind kind = SolverKind::Auto);
    ~NewmarkIntegrator();
    NewmarkIntegrator(const NewmarkIntegrator&) = delete;
    NewmarkIntegrator& operator=(const NewmarkIntegrator&) = delete;

    // The state at time t and speed w; z'' from M z'' = f - C(w) z' - K(w) z (SolverError if M is singular).
    void start(double t, double w, const Eigen::VectorXd& z, const Eigen::VectorXd& v, const Eigen::VectorXd& f);
    // One step to t + dt, where the speed is w and the force f. SolverError where S is
    // singular or the state stops being finite (an unstable run: the motion overflows).
    void step(double w, const Eigen::VectorXd& f);

    double time() const;
    const Eigen::VectorXd& z() const;
    const Eigen::VectorXd& v() const;
    const Eigen::VectorXd& a() const;
    const Stats& stats() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

struct TransientOptions {
    SpeedProfile profile;
    double duration = 0.0;         // s; 0: the ramp (a run-up) or 100 revolutions (constant speed)
    double dt = 0.0;               // s; 0: transient_time_step (steady_time_step at a constant speed)
    std::vector<int> outputs;      // DOFs recorded; empty: those of the largest unbalance (transient_outputs)
    bool start_steady = false;     // start on the steady response at `from`; false: at rest
    long long max_steps = kTransientMaxSteps;
    SolverKind kind = SolverKind::Auto;
    SpeedUnit unit;                // the unit its messages and notes name speeds in
};

struct TransientResult {
    SpeedProfile profile;
    double dt = 0.0;               // s, the step used
    std::vector<double> t, speed;  // every step, s and rad/s
    std::vector<int> dofs;         // the DOF of each column of z
    Eigen::MatrixXd z;             // (steps + 1) x dofs, displacements in each DOF's unit
    NewmarkIntegrator::Stats stats;
    std::vector<std::string> notes;   // the time step chosen, coefficients held, ...
};

// The DOFs recorded by default: the lateral translations of the node of the largest
// unbalance entry (a model with nodes), else the whirl pair holding it, else that DOF.
std::vector<int> transient_outputs(const GyroscopicSystem& sys);

// The checks transient_response makes before any work, alone: InputError naming the
// field (dt, duration, max_steps, speed, run_up, acceleration), an output DOF out of
// range, no unbalance.
void check_transient_options(const GyroscopicSystem& sys, const TransientOptions& opt);

// InputError (a field named: dt, duration, max_steps, speed, run_up, acceleration, an
// output DOF out of range, no unbalance) before any work; SolverError where the
// integration fails (see NewmarkIntegrator).
TransientResult transient_response(const GyroscopicSystem& sys, const TransientOptions& opt);

}  // namespace gyrokit
