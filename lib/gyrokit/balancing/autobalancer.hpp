// Rigid rotor in one plane with up to two compensating rollers in a viscous-filled
// ring (Sperling, Duckstein, Ryzhik: "Selbsttätiges Auswuchten mittels zweier
// beliebiger Rollen"), equations of motion (18) as a first-order system.
//
// Generalized coordinates x, y (rotor centre), phi0 (rotor angle), phi_i (path
// angle of roller i). The state keeps the roller angles relative to the rotor,
// alpha_i = phi_i - phi0, and the rotor angle relative to a uniform reference
// rotation, so that no state component grows with the number of revolutions and
// the integrator's tolerance stays meaningful in long runs.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace gyrokit {

// One compensating roller (ball: mu = 2/5, solid cylinder: mu = 1/2, point mass: 0).
struct Roller {
    double m = 0.0;     // mass, kg
    double eps = 0.0;   // radius of the path of the roller centre, m
    double R = 0.0;     // radius of the raceway the roller rolls on, m (R = eps + r)
    double mu = 0.0;    // J_S = mu m r^2, eq. (4)
    double beta = 0.0;  // viscous coefficient beta_i of eq. (12), N m s

    double r() const { return R - eps; }              // roller radius, m
    double unbalance() const { return m * eps; }       // U_i, kg m
    double J_ii() const { return (1.0 + mu) * m * eps * eps; }   // eq. (7)
    double J_0i() const { return mu * m * R * eps; }             // eq. (7)
};

enum class Drive {
    PrescribedSpeed,   // phi0 = speed * t; the drive supplies whatever torque it takes
    Motor              // L(phi0') = L0 - ..., eq. (16)-(18) with the total beta0 of (17)
};

struct AutobalancerParameters {
    double m = 1.0;      // base rotor mass, kg
    double J = 0.0;      // base rotor polar moment of inertia, kg m^2
    double m0 = 0.0;     // unbalance mass, kg
    double eps0 = 0.0;   // its eccentricity, m
    double k_x = 0.0, k_y = 0.0;   // bearing stiffness, N/m
    double c_x = 0.0, c_y = 0.0;   // bearing damping, N s/m
    std::vector<Roller> rollers;   // 0, 1 or 2; absent rollers are not modelled

    Drive drive = Drive::PrescribedSpeed;
    double speed = 0.0;  // prescribed rotor speed Omega, rad/s
    double L0 = 0.0;     // motor torque constant, N m
    double beta0 = 0.0;  // total beta0 of eq. (17) (motor slope + external damping + sum beta_i), N m s

    double M() const;            // m + m0 + sum m_i, eq. (6)
    double J00() const;          // eq. (6)
    double omega_x() const;      // sqrt(k_x / M), eq. (28)
    double omega_y() const;
    double f_unbalance(int i, double Omega) const;   // f_i = m_i eps_i Omega^2 (i = 0: rotor), eq. (25)
    // The speed the rotor turns at in the mean: the prescribed speed, or the
    // nominal speed L0 / beta0 of the motor.
    double reference_speed() const;

    // Throws InputError naming the parameter, its value and the allowed range.
    void validate() const;
};

// A time-varying nominal speed of the motor drive (run-ups): the drive torque is
// L0(t) = beta0 speed(t); `angle` is the integral of `speed` from 0, so that the
// rotor angle stays a bounded lag behind it in the state.
struct NominalSpeedProfile {
    std::function<double(double)> speed;   // rad/s
    std::function<double(double)> angle;   // rad
};

// The equations of motion (18) for one parameter set.
//
// State layout (n = number of rollers):
//   [0] x, [1] y, [2] x', [3] y',
//   motor drive only: [4] theta0 = phi0 - Omega_ref t, [5] phi0',
//   then per roller i: alpha_i = phi_i - phi0, alpha_i' = phi_i' - phi0'.
class AutobalancerModel {
public:
    // Validates the parameters (InputError).
    explicit AutobalancerModel(AutobalancerParameters p);

    const AutobalancerParameters& parameters() const { return p_; }
    std::size_t state_size() const { return static_cast<std::size_t>(first_roller_ + 2 * rollers()); }
    int rollers() const { return static_cast<int>(p_.rollers.size()); }
    bool motor() const { return p_.drive == Drive::Motor; }

    std::size_t alpha_index(int i) const { return static_cast<std::size_t>(first_roller_ + 2 * i); }
    std::size_t alpha_rate_index(int i) const { return alpha_index(i) + 1; }

    // Initial state: rotor centre (x, y) at rest, rollers at relative phases
    // `alpha` (rad) and at rest relative to the rotor, rotor at its reference speed.
    std::vector<double> initial_state(const std::vector<double>& alpha, double x = 0.0, double y = 0.0) const;

    // Motor drive only: replace the constant nominal speed L0 / beta0 by a profile.
    // The state's theta0 is then phi0 - profile.angle(t). InputError without a motor.
    void set_nominal_profile(NominalSpeedProfile profile);
    bool has_profile() const { return static_cast<bool>(profile_.speed); }

    double rotor_angle(double t, const double* s) const;   // phi0, rad
    double rotor_speed(const double* s) const;             // phi0', rad/s

    // dydt = f(t, y). Returns false (and leaves dydt unspecified) if a value is
    // not finite or the mass matrix is not positive definite; `why` then says which.
    bool rhs(double t, const double* s, double* dsdt, const char** why = nullptr) const;

private:
    AutobalancerParameters p_;
    int first_roller_;
    double omega_ref_;
    NominalSpeedProfile profile_;
};

}  // namespace gyrokit
