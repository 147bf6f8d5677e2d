#include <gyrokit/models/fluid_rotor.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_bessel.h>
#include <gsl/gsl_sf_zeta.h>
#include <vector>

namespace gyrokit {

namespace {

// Scaled Bessel functions: Ih_m(x) = e^{-x} I_m(x), Kh_m(x) = e^{x} K_m(x).
struct Scaled {
    double I0, I1, I2, K0, K1, K2;
    double DI() const { return I0 - I1 / x; }    // e^{-x} I1'(x)
    double DK() const { return -K0 - K1 / x; }   // e^{x} K1'(x)
    double x;
};

Scaled scaled(double x) {
    Scaled s;
    s.x = x;
    s.I0 = gsl_sf_bessel_I0_scaled(x);
    s.I1 = gsl_sf_bessel_I1_scaled(x);
    s.I2 = gsl_sf_bessel_In_scaled(2, x);
    s.K0 = gsl_sf_bessel_K0_scaled(x);
    s.K1 = gsl_sf_bessel_K1_scaled(x);
    s.K2 = gsl_sf_bessel_Kn_scaled(2, x);
    return s;
}

// Bessel path: H(x) = C1 e^{x-X} Ih1(x) + C2 e^{X0-x} Kh1(x) on [X0, X]; every
// exponential factor is <= 1, so nothing overflows for any kappa R.
detail::RadialValues radial_bessel(double kappa, double R0, double R, double dR0, double dR) {
    const double X0 = kappa * R0, X = kappa * R;
    const double d = kappa * (R - R0);   // formed from R - R0, not X - X0
    const double E = std::exp(-d);
    const Scaled a = scaled(X0), b = scaled(X);
    const double g0 = dR0 / kappa, g1 = dR / kappa;   // H'(X0), H'(X)
    const double det = b.DI() * a.DK() - E * E * b.DK() * a.DI();
    const double C1 = (g1 * a.DK() - E * b.DK() * g0) / det;
    const double C2 = (b.DI() * g0 - E * a.DI() * g1) / det;
    detail::RadialValues v;
    v.h_R = C1 * b.I1 + C2 * E * b.K1;
    v.h_R0 = C1 * E * a.I1 + C2 * a.K1;
    // int x^2 H dx from d/dx(x^2 I2) = x^2 I1, d/dx(x^2 K2) = -x^2 K1.
    const double up = X * X * (C1 * b.I2 - C2 * E * b.K2);
    const double lo = X0 * X0 * (C1 * E * a.I2 - C2 * a.K2);
    const double int_hr2 = (up - lo) / (kappa * kappa * kappa);
    v.P = int_hr2 - (R * v.h_R - R0 * v.h_R0) / (kappa * kappa);
    // int (H'^2 + H^2/x^2) x dx = [x H H' - (x^2+1) H^2/2 + x^2 H'^2/2] (Lommel).
    const auto prim = [](double x, double H, double Hp) {
        return x * H * Hp - 0.5 * (x * x + 1.0) * H * H + 0.5 * x * x * Hp * Hp;
    };
    v.wall_end = prim(X, v.h_R, g1) - prim(X0, v.h_R0, g0);
    // sigma^2/w^2 - 1 = X0 p/f, f = K1 - L I1, p = K0 + L I0 at X0, L = K1'(X)/I1'(X):
    // no subtraction from 1, so a nearly full cavity keeps its digits.
    const double ell = b.DK() / b.DI();
    const double f = a.K1 - E * E * ell * a.I1;
    const double p = a.K0 + E * E * ell * a.I0;
    v.ratio_m1 = X0 * p / f;
    return v;
}

// Taylor coefficients about x0 of the order-1 modified Bessel ODE
// x^2 y'' + x y' - (x^2 + 1) y = 0 with y(x0) = c0, y'(x0) = c1.
std::vector<double> taylor(double x0, double c0, double c1, double s, int kmax) {
    std::vector<double> a{c0, c1};
    a.reserve(kmax + 2);
    double biggest = std::max(std::fabs(c0), std::fabs(c1) * s);
    int small = 0;
    for (int m = 0; static_cast<int>(a.size()) < kmax; ++m) {
        const double am1 = m >= 1 ? a[m - 1] : 0.0, am2 = m >= 2 ? a[m - 2] : 0.0;
        const double next = (-x0 * (m + 1) * (2 * m + 1) * a[m + 1] - (double(m) * m - 1.0 - x0 * x0) * a[m] +
                             2.0 * x0 * am1 + am2) /
                            (x0 * x0 * (m + 2) * (m + 1));
        a.push_back(next);
        const double t = std::fabs(next) * std::pow(s, m + 2);
        biggest = std::max(biggest, t);
        small = t < 1e-18 * biggest ? small + 1 : 0;
        if (small >= 3) break;
    }
    return a;
}

double poly(const std::vector<double>& a, double s, int from = 0) {
    double r = 0.0;
    for (int k = static_cast<int>(a.size()) - 1; k >= from; --k) r = r * s + a[k];
    return from == 0 ? r : r * std::pow(s, from);
}
double dpoly(const std::vector<double>& a, double s, int from = 1) {   // sum_{k>=from} k a_k s^{k-1}
    double r = 0.0;
    for (int k = static_cast<int>(a.size()) - 1; k >= from; --k) r = r * s + k * a[k];
    return r * std::pow(s, from - 1);
}

// Thin-layer path (kappa (R - R0) small against 1 and against kappa R0): the
// Bessel combinations cancel to O(kappa (R - R0)) there, the Taylor series of the
// radial ODE about X0 does not.
detail::RadialValues radial_series(double kappa, double R0, double R, double dR0, double dR) {
    const double X0 = kappa * R0, s = kappa * (R - R0);
    const auto A = taylor(X0, 1.0, 0.0, s, 400), B = taylor(X0, 0.0, 1.0, s, 400);
    const double g0 = dR0 / kappa, g1 = dR / kappa;
    // H = alpha A + beta B; beta = H'(X0); alpha from H'(X) = g1 without forming B'(s) - 1 by subtraction.
    const double beta = g0;
    const double dA = dpoly(A, s, 2);                    // A'(s), A has no linear term
    const double dBm1 = dpoly(B, s, 2);                  // B'(s) - 1
    const double alpha = ((g1 - g0) - beta * dBm1) / dA;
    detail::RadialValues v;
    v.thin = true;
    v.h_R0 = alpha;
    const double dh = alpha * poly(A, s, 2) + beta * poly(B, s, 1);   // H(X) - H(X0)
    v.h_R = alpha + dh;
    // Gauss-Legendre on the (polynomial-like) layer.
    gsl_integration_glfixed_table* t = gsl_integration_glfixed_table_alloc(48);
    double int_hx2 = 0.0, wall = 0.0;
    for (size_t i = 0; i < 48; ++i) {
        double si = 0, wi = 0;
        gsl_integration_glfixed_point(0.0, s, i, &si, &wi, t);
        const double x = X0 + si;
        const double H = alpha * poly(A, si) + beta * poly(B, si);
        const double Hp = alpha * dpoly(A, si) + beta * dpoly(B, si);
        int_hx2 += wi * H * x * x;
        wall += wi * (Hp * Hp + H * H / (x * x)) * x;
    }
    gsl_integration_glfixed_table_free(t);
    v.P = int_hx2 / (kappa * kappa * kappa) - ((R - R0) * v.h_R + R0 * dh) / (kappa * kappa);
    v.wall_end = wall;
    v.ratio_m1 = R0 / v.h_R0 - 1.0;
    return v;
}

}  // namespace

namespace detail {

RadialValues radial(double kappa, double R0, double R, double dR0, double dR, RadialPath path) {
    gsl_set_error_handler_off();
    const double d = kappa * (R - R0), X0 = kappa * R0;
    const bool thin = d < 0.5 && d < 0.25 * X0;
    if (path == RadialPath::Series || (path == RadialPath::Automatic && thin))
        return radial_series(kappa, R0, R, dR0, dR);
    return radial_bessel(kappa, R0, R, dR0, dR);
}

}  // namespace detail

double SloshingMode::sigma_over_omega() const { return std::sqrt(ratio); }
double SloshingMode::tau(double w) const { return tau_coeff * std::sqrt(std::max(w, 0.0)); }

void validate(const FluidRotorParameters& p, const std::string& origin) {
    const auto pos = [](double v) { return std::isfinite(v) && v > 0; };
    const auto nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
    check_parameter(pos(p.R), origin, "R", p.R, "> 0 (m)");
    check_parameter(pos(p.R0), origin, "R0", p.R0, "> 0 (m)");
    if (!(p.R0 < p.R))
        throw InputError(fmt::format("{}: R0 = {} is not below R = {}; allowed: 0 < R0 < R (m)", origin, p.R0, p.R));
    check_parameter(pos(p.a), origin, "a", p.a, "> 0 (m)");
    check_parameter(pos(p.l), origin, "l", p.l, "> 0 (m)");
    check_parameter(nonneg(p.rho), origin, "rho", p.rho, ">= 0 (kg/m^3)");
    check_parameter(nonneg(p.nu), origin, "nu", p.nu, ">= 0 (m^2/s)");
    check_parameter(pos(p.c1), origin, "c1", p.c1, "> 0 (N/m)");
    check_parameter(pos(p.c2), origin, "c2", p.c2, "> 0 (N/m)");
    check_parameter(pos(p.c11), origin, "c11", p.c11, "> 0 (N/m)");
    check_parameter(pos(p.m0), origin, "m0", p.m0, "> 0 (kg)");
    check_parameter(nonneg(p.I0), origin, "I0", p.I0, ">= 0 (kg m^2)");
    check_parameter(pos(p.J0), origin, "J0", p.J0, "> 0 (kg m^2)");
    check_parameter(nonneg(p.e), origin, "e", p.e, ">= 0 (m)");
    check_parameter(p.modes >= 0 && p.modes <= 100000, origin, "modes", p.modes, "[1, 100000], or absent for a tolerance");
    check_parameter(std::isfinite(p.tolerance) && p.tolerance > 0 && p.tolerance < 1, origin, "tolerance", p.tolerance,
         "0 < tolerance < 1");
    check_parameter(p.jstar_terms >= 0 && p.jstar_terms <= 10000000, origin, "jstar_terms", p.jstar_terms,
         "[1, 10000000], or absent for automatic");
}

RotorStiffness rotor_stiffness(const FluidRotorParameters& p) {
    RotorStiffness k;
    const double u2 = 1.0 / (p.c11 + 2.0 * p.c2), u1 = 1.0 / (p.c11 + 2.0 * p.c1);
    k.gamma = p.c11 * (1.0 - 0.5 * p.c11 * (u1 + u2));
    k.delta = p.c11 * p.c11 * p.l / 4.0 * (u2 - u1);   // a force: c11^2 l/4, not c11^2 l^2/4
    k.tilt = k.gamma * p.l * p.l / 4.0;
    return k;
}

LiquidCoefficients liquid_coefficients(const FluidRotorParameters& p) {
    LiquidCoefficients c;
    const double R = p.R, R0 = p.R0, a = p.a, rho = p.rho;
    const double dR2 = (R - R0) * (R + R0);        // R^2 - R0^2 without cancellation
    const double dR4 = dR2 * (R * R + R0 * R0);
    c.m_star = rho * kPi * a * dR2;
    c.I_star = 0.5 * rho * kPi * a * dR4;
    c.J_rigid = c.m_star * ((R * R + R0 * R0) / 4.0 + a * a / 12.0);
    if (rho == 0.0) return c;

    // J*: rho int (y^2 - z^2) dV plus the correction potential F = sum A_n g_n(r) sin(Theta) sin(kappa z)
    // with dF/dr = -2 z sin(Theta) on both cylinders; term n = 16 rho a P[g_n] / (pi n^2).
    const int NJ = p.jstar_terms > 0 ? p.jstar_terms : 100;   // the fitted tail makes 100 terms exact to ~1e-10
    double sum = 0.0, t_prev = 0.0, t_last = 0.0;
    for (int j = NJ - 1; j >= 0; --j) {   // smallest terms first
        const int n = 2 * j + 1;
        const double kappa = n * kPi / a;
        const auto g = detail::radial(kappa, R0, R, -1.0, -1.0);
        const double term = 16.0 * rho * a * g.P / (kPi * double(n) * n);
        if (j == NJ - 1) t_last = term;
        if (j == NJ - 2) t_prev = term;
        sum += term;
    }
    // Tail: fit t_n = A/n^4 + B/n^5 to the last two terms, sum with Hurwitz zeta.
    double tail = 0.0;
    const double n2 = 2.0 * NJ - 1.0;
    const double q = (n2 + 2.0) / 2.0;
    if (NJ >= 2) {
        const double n1 = n2 - 2.0;
        const double B = (t_prev * std::pow(n1, 4) - t_last * std::pow(n2, 4)) / (1.0 / n1 - 1.0 / n2);
        const double A = t_last * std::pow(n2, 4) - B / n2;
        tail = A * gsl_sf_hzeta(4.0, q) / 16.0 + B * gsl_sf_hzeta(5.0, q) / 32.0;
    } else {
        tail = t_last * std::pow(n2, 4) * gsl_sf_hzeta(4.0, q) / 16.0;
    }
    c.jstar_terms = NJ;
    c.jstar_tail = std::isfinite(tail) ? tail : 0.0;
    c.J_star = 0.5 * c.I_star - c.m_star * a * a / 12.0 + sum + c.jstar_tail;

    // Sloshing modes.
    const double scale = p.I0 + c.I_star + p.J0 + c.J_star;
    int below = 0;
    const int cap = p.modes > 0 ? p.modes : 5000;
    for (int j = 0; j < cap; ++j) {
        SloshingMode m;
        m.n = 2 * j + 1;
        m.kappa = m.n * kPi / a;
        const auto h = detail::radial(m.kappa, R0, R, -1.0, 0.0);
        const double sgn = (m.n % 4 == 1) ? 1.0 : -1.0;   // sin(n pi / 2)
        m.detuning = h.ratio_m1;
        m.ratio = h.thin ? R0 / h.h_R0 : 1.0 + h.ratio_m1;
        m.mu = rho * kPi * a * R0 * h.h_R0 / 2.0;
        m.lambda = 2.0 * kPi * rho * sgn * h.P;
        m.wall_integral = 0.5 * kPi * a * h.h_R * h.h_R * (1.0 / R + m.kappa * m.kappa * R) + 2.0 * kPi * h.wall_end;
        m.tau_coeff = rho * std::sqrt(p.nu * std::sqrt(m.ratio) / 2.0) * m.wall_integral / m.mu;
        if (!(std::isfinite(m.mu) && std::isfinite(m.lambda) && std::isfinite(m.ratio) && std::isfinite(m.tau_coeff) &&
              m.mu > 0 && m.ratio > 0))
            throw SolverError(fmt::format("sloshing mode n = {} has no finite coefficients (R = {}, R0 = {}, a = {})",
                                          m.n, R, R0, a));
        c.modes.push_back(m);
        if (p.modes == 0) {
            const double contrib = m.lambda * m.lambda / (m.mu * std::fabs(m.detuning));
            below = contrib < p.tolerance * scale ? below + 1 : 0;
            if (below >= 2) break;
            // A series that has not met its tolerance after `cap` modes is not a converged model.
            if (j + 1 == cap)
                throw SolverError(fmt::format("the sloshing modes do not reach tolerance = {} within {} modes "
                                              "(R = {}, R0 = {}, a = {}); give modes = N, or a larger tolerance",
                                              p.tolerance, cap, R, R0, a));
        }
    }
    if (!std::isfinite(c.J_star))
        throw SolverError(fmt::format("J* is not finite (R = {}, R0 = {}, a = {})", R, R0, a));
    return c;
}

FluidRotor build_fluid_rotor(const FluidRotorParameters& p) {
    validate(p, "fluid rotor");
    FluidRotor f;
    f.p = p;
    f.k = rotor_stiffness(p);
    f.liquid = liquid_coefficients(p);
    f.m = p.m0 + f.liquid.m_star;
    f.I = p.I0 + f.liquid.I_star;
    f.J = p.J0 + f.liquid.J_star;
    f.J_rigid = p.J0 + f.liquid.J_rigid;
    return f;
}

double equivalent_inertia(const FluidRotor& f) {
    double s = 0.0;
    for (const auto& m : f.liquid.modes) {
        if (m.detuning == 0.0)
            throw SolverError(fmt::format("sloshing mode n = {} is exactly at resonance (sigma_n = w) for R0 = {}: "
                                          "the undamped model has no finite equivalent inertia; use the damped one",
                                          m.n, f.p.R0));
        s += m.lambda * m.lambda / (m.mu * m.detuning);
    }
    return f.I - f.J - s;
}

double equivalent_inertia_damped(const FluidRotor& f, double w) {
    double s = 0.0;
    for (const auto& m : f.liquid.modes) {
        const double t = m.tau_coeff / std::sqrt(w);   // tau_n / w
        const double den = m.detuning * m.detuning + t * t;
        if (den > 0) s += m.lambda * m.lambda * m.detuning / (m.mu * den);
    }
    return f.I - f.J - s;
}

double equivalent_inertia_rigid(const FluidRotor& f) { return f.I - f.J_rigid; }

double fluid_delta(const FluidRotor& f, double J_eq, double w) {
    const double w2 = w * w;
    return (f.k.gamma - f.m * w2) * (f.k.tilt + J_eq * w2) - f.k.delta * f.k.delta;
}

GyroscopicSystem make_system(const FluidRotor& f) {
    // Assembled sparse: two DOFs per sloshing mode, and up to 100,000 modes may be asked for.
    const int ns = static_cast<int>(f.liquid.modes.size());
    const int n = 4 + 2 * ns;
    GyroscopicSystem s;
    using T = Eigen::Triplet<double>;
    std::vector<T> M, K, G, K2, D;   // D per sqrt(w)
    s.dofs.names = {"x", "y", "alpha", "beta"};
    M.insert(M.end(), {T(0, 0, f.m), T(1, 1, f.m), T(2, 2, f.J), T(3, 3, f.J)});
    K.insert(K.end(), {T(0, 0, f.k.gamma), T(1, 1, f.k.gamma), T(2, 2, f.k.tilt), T(3, 3, f.k.tilt)});
    for (const auto& [i, j] : {std::pair{0, 2}, std::pair{2, 0}, std::pair{1, 3}, std::pair{3, 1}})
        K.emplace_back(i, j, -f.k.delta);
    G.insert(G.end(), {T(2, 3, f.I), T(3, 2, -f.I)});
    s.whirl_pairs = {{0, 1}, {2, 3}};
    bool damped = false;
    for (int j = 0; j < ns; ++j) {
        const auto& m = f.liquid.modes[static_cast<size_t>(j)];
        const int q = 4 + 2 * j, r = q + 1;
        s.dofs.names.push_back("q" + std::to_string(m.n));
        s.dofs.names.push_back("s" + std::to_string(m.n));
        M.insert(M.end(), {T(q, q, m.mu), T(r, r, m.mu), T(2, q, m.lambda), T(q, 2, m.lambda), T(3, r, m.lambda),
                           T(r, 3, m.lambda)});
        K2.insert(K2.end(), {T(q, q, m.mu * m.ratio), T(r, r, m.mu * m.ratio)});   // mu_n (sigma_n/w)^2 w^2
        D.insert(D.end(), {T(q, q, m.mu * m.tau(1.0)), T(r, r, m.mu * m.tau(1.0))});   // mu_n tau_n(1) sqrt(w)
        damped = damped || m.mu * m.tau(1.0) != 0.0;
        s.whirl_pairs.emplace_back(q, r);
    }
    const auto sparse = [n](const std::vector<T>& t) {
        SparseMatrix A(n, n);
        A.setFromTriplets(t.begin(), t.end());
        return A;
    };
    s.M = sparse(M);
    s.K = sparse(K);
    s.G = sparse(G);
    s.K2 = sparse(K2);
    if (ns > 0 && damped) {
        const SparseMatrix Ds = sparse(D);
        s.damping.push_back({"sloshing", Ds, [Ds](double w) { return SparseMatrix(Ds * std::sqrt(std::max(w, 0.0))); }});
    }
    if (f.p.e > 0) {
        s.unbalance = Eigen::VectorXcd::Zero(n);
        s.unbalance(0) = f.p.m0 * f.p.e;
        s.unbalance(1) = std::complex<double>(0.0, -f.p.m0 * f.p.e);
    }
    return s;
}

}  // namespace gyrokit
