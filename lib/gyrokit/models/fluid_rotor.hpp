// Rigid hollow rotor on an elastic shaft between two bearings, its cylindrical
// cavity (length a, radius R) partly filled with liquid up to the free-surface
// radius R0 (Bogomolov, Korsunskij, Fischer). Potential flow, sloshing modes
// n = 1, 3, 5, ... (axial wave number kappa = n pi / a, circumferential order 1),
// Stokes-layer damping of the sloshing. Every coefficient is re-derived; see
// docs/fluid_rotor.md for the equations as implemented and the corrections to
// the paper.
//
// Coordinates of the coupled system (make_system):
//   z = [x, y, alpha, beta, q_1, s_1, q_3, s_3, ...]
// x, y: translation of the rotor centre C (m); alpha: tilt in the x-z plane
// (rotation about +y), beta: tilt in the y-z plane (rotation about -x), so that
// (x, y) and (alpha, beta) turn forward with the spin; q_n, s_n: free-surface
// displacement amplitude (m, towards the axis) of sloshing mode n in the x-z and
// y-z plane. Whirl pairs: (x, y), (alpha, beta), (q_n, s_n).
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>

#include <string>
#include <vector>

namespace gyrokit {

struct FluidRotorParameters {
    double R = 0;        // cavity radius, m
    double R0 = 0;       // free-surface radius, 0 < R0 < R, m
    double a = 0;        // cavity length, m
    double l = 0;        // bearing distance (shaft length), m
    double rho = 0;      // liquid density, kg/m^3 (0: empty rotor)
    double nu = 0;       // kinematic viscosity, m^2/s (0: no sloshing damping)
    double c1 = 0, c2 = 0;   // bearing stiffnesses (isotropic), N/m
    double c11 = 0;      // shaft stiffness at the rotor, N/m
    double m0 = 0;       // rotor mass without liquid, kg
    double I0 = 0;       // polar moment of inertia of the rotor, kg m^2
    double J0 = 0;       // equatorial moment of inertia about C, kg m^2
    double e = 0;        // rotor eccentricity (unbalance), m
    int modes = 0;       // sloshing terms n = 1, 3, ..., 2 modes - 1; 0: until `tolerance`
    double tolerance = 1e-10;   // truncation of the sloshing sum when modes == 0
    int jstar_terms = 0;        // terms of the J* series; 0: automatic (100, plus fitted tail)
                                // stiffness and damping; 0: lowest undamped critical speed
};

// Throws InputError naming `origin`, the key, the value and the allowed range.
void validate(const FluidRotorParameters& p, const std::string& origin);

// One sloshing mode n. The speed dependence is analytic: sigma_n = w sqrt(ratio),
// tau_n = tau_coeff sqrt(w).
struct SloshingMode {
    int n = 1;
    double kappa = 0;        // n pi / a, 1/m
    double ratio = 0;        // sigma_n^2 / w^2
    double detuning = 0;     // sigma_n^2 / w^2 - 1, computed without subtraction
    double lambda = 0;       // coupling tilt - sloshing, kg m
    double mu = 0;           // generalized sloshing mass, kg
    double tau_coeff = 0;    // tau_n / sqrt(w), s^-1/2
    double wall_integral = 0;   // integral over the wetted walls of |grad_t phi_n|^2, m^2
    double sigma_over_omega() const;
    double tau(double w) const;
};

struct LiquidCoefficients {
    double m_star = 0;       // liquid mass, kg
    double I_star = 0;       // polar moment of the co-rotating liquid, kg m^2
    double J_star = 0;       // potential-flow (Stokes-Zhukovsky) equatorial inertia about C, kg m^2
    double J_rigid = 0;      // equatorial inertia of the liquid frozen as a solid, kg m^2
    int jstar_terms = 0;     // terms of the J* series used
    double jstar_tail = 0;   // fitted tail added to the truncated series, kg m^2
    std::vector<SloshingMode> modes;
};

// The liquid coefficients from exponentially scaled Bessel functions (GSL);
// thin layers (nearly empty) use a Taylor expansion of the radial ODE instead.
LiquidCoefficients liquid_coefficients(const FluidRotorParameters& p);

// Rotor stiffness after condensing the bearing deflections.
struct RotorStiffness {
    double gamma = 0;   // translation, N/m
    double delta = 0;   // translation-tilt coupling, N (sign convention irrelevant: enters squared)
    double tilt = 0;    // tilt stiffness gamma l^2/4, N m
};
RotorStiffness rotor_stiffness(const FluidRotorParameters& p);

// The whole model: parameters, stiffness, liquid coefficients, totals.
struct FluidRotor {
    FluidRotorParameters p;
    RotorStiffness k;
    LiquidCoefficients liquid;
    double m = 0, I = 0;        // m0 + m*, I0 + I*
    double J = 0;               // J0 + J* (liquid moving)
    double J_rigid = 0;         // J0 + J_rigid (liquid as a solid)
};
FluidRotor build_fluid_rotor(const FluidRotorParameters& p);

// Equivalent inertia I - J - sum lambda_n^2 / (mu_n (sigma_n^2/w^2 - 1)):
// independent of w because sigma_n is proportional to w. Infinite exactly at a
// sloshing resonance (throws SolverError there).
double equivalent_inertia(const FluidRotor& f);
// With sloshing damping; depends on w through tau_n / w.
double equivalent_inertia_damped(const FluidRotor& f, double w);
double equivalent_inertia_rigid(const FluidRotor& f);

// Delta(w) = (gamma - m w^2)(gamma l^2/4 + J_eq w^2) - delta^2 for a given J_eq.
double fluid_delta(const FluidRotor& f, double J_eq, double w);

// The coupled rotor + sloshing system, exact at every speed: the sloshing
// stiffness mu_n sigma_n^2 grows with w^2 (stiffness per speed squared K2) and
// the damping mu_n tau_n with sqrt(w) (speed-dependent damping component "sloshing").
GyroscopicSystem make_system(const FluidRotor& f);

namespace detail {

// Solution h(r) = c1 I1(kappa r) + c2 K1(kappa r) with h'(R0) = dR0, h'(R) = dR,
// and the integrals the coefficients need.
struct RadialValues {
    double h_R0 = 0, h_R = 0;
    double P = 0;          // int_R0^R h r^2 dr - (R h(R) - R0 h(R0)) / kappa^2
    double wall_end = 0;   // int_R0^R (h'^2 + h^2/r^2) r dr
    double ratio_m1 = 0;   // only for dR0 = -1, dR = 0: sigma^2/w^2 - 1
    bool thin = false;     // computed by the thin-layer series
};
enum class RadialPath { Automatic, Bessel, Series };
RadialValues radial(double kappa, double R0, double R, double dR0, double dR, RadialPath path = RadialPath::Automatic);

}  // namespace detail

}  // namespace gyrokit
