#include <gyrokit/balancing/sommerfeld.hpp>

#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

void require(bool ok, const std::string& what) {
    if (!ok) throw InputError("sommerfeld: " + what);
}

bool same(double a, double b) { return std::fabs(a - b) <= 1e-12 * std::max(std::fabs(a), std::fabs(b)); }

// dV/domega by the quotient rule.
double vibration_torque_slope(const SommerfeldSystem& s, double U, double w) {
    const double a = s.M * (s.omega_krit * s.omega_krit - w * w);
    const double D = a * a + s.c * s.c * w * w;
    const double dD = 2.0 * a * (-2.0 * s.M * w) + 2.0 * s.c * s.c * w;
    const double N = U * U * s.c * std::pow(w, 5), dN = 5.0 * U * U * s.c * std::pow(w, 4);
    return (dN * D - N * dD) / (D * D);
}

double rotor_speed_at(const SommerfeldSystem& s, double p) {
    return s.n == 0 ? p : p + s.n * vibration_torque(s, s.Ue, p) / s.beta_e;
}

double nominal_at(const SommerfeldSystem& s, double p) {
    const double w0 = rotor_speed_at(s, p);
    return w0 + (vibration_torque(s, s.U0, w0) - s.n * s.beta_e * (s.n == 0 ? 0.0 : p)) / s.beta0;
}

// Grid of hanging speeds: fine over the resonance region (the peak of V has a
// width of about c / M), coarser beyond.
std::vector<double> search_grid(const SommerfeldSystem& s, double p_max) {
    const double p1 = 20.0 * s.omega_krit;
    std::vector<double> g;
    const int n1 = 100000;
    for (int i = 1; i <= n1; ++i) g.push_back(p1 * i / n1);
    if (p_max > p1) {
        const int n2 = 5000;
        for (int i = 1; i <= n2; ++i) g.push_back(p1 + (p_max - p1) * i / n2);
    }
    return g;
}

}  // namespace

SommerfeldSystem sommerfeld_system(const AutobalancerParameters& p) {
    p.validate();
    require(p.drive == Drive::Motor, "the Sommerfeld effect needs the motor drive: give L0 and beta0 instead of speed");
    require(same(p.k_x, p.k_y), fmt::format("k_x = {}, k_y = {}: the analysis needs isotropic bearings (give k)",
                                            p.k_x, p.k_y));
    require(same(p.c_x, p.c_y), fmt::format("c_x = {}, c_y = {}: the analysis needs isotropic bearings (give c)",
                                            p.c_x, p.c_y));
    require(p.c_x > 0.0, fmt::format("c = {}: allowed: > 0 N s/m (without bearing damping there is no vibration "
                                     "torque)", p.c_x));
    SommerfeldSystem s;
    s.n = static_cast<int>(p.rollers.size());
    s.M = p.M();
    s.k = p.k_x;
    s.c = p.c_x;
    s.omega_krit = std::sqrt(s.k / s.M);
    s.U0 = p.m0 * p.eps0;
    s.beta0 = p.beta0;
    if (s.n == 2) {
        const Roller &a = p.rollers[0], &b = p.rollers[1];
        require(same(a.m, b.m) && same(a.eps, b.eps) && same(a.beta, b.beta),
                "the two rollers must be identical in m, eps and beta, eq. (29)");
    }
    if (s.n > 0) {
        s.Ue = p.rollers[0].unbalance();
        s.beta_e = p.rollers[0].beta;
    }
    require(s.U0 > 0.0 || s.n > 0, "m0 * eps0 = 0 and no rollers: nothing excites the rotor");
    s.compensating = s.n == 2 && s.U0 <= 2.0 * s.Ue;
    return s;
}

double vibration_torque(const SommerfeldSystem& s, double U, double w) {
    const double a = s.M * (s.omega_krit * s.omega_krit - w * w);
    const double D = a * a + s.c * s.c * w * w;
    return D > 0.0 ? U * U * s.c * std::pow(w, 5) / D : 0.0;
}

double limit_speed_estimate(const SommerfeldSystem& s) {
    const double w = s.omega_krit;
    if (s.n == 0) return w * (1.0 + std::pow(s.U0 * w, 2) / (s.beta0 * s.c));
    return w * (1.0 + s.n * std::pow(s.Ue * w, 2) / (s.beta_e * s.c));
}

bool curve_point_stable(const SommerfeldSystem& s, double p) {
    const double w0 = rotor_speed_at(s, p);
    const double s00 = s.beta0 + vibration_torque_slope(s, s.U0, w0);
    if (s.n == 0) return s00 > 0.0;
    const double s01 = -s.n * s.beta_e;
    const double s11 = s.n * (s.beta_e + s.n * vibration_torque_slope(s, s.Ue, p));
    const bool pd = s00 > 0.0 && s00 * s11 - s01 * s01 > 0.0;
    return pd && (s.n < 2 || p < s.omega_krit);
}

StationaryPoint synchronous_point(const SommerfeldSystem& s, double Omega) {
    StationaryPoint q;
    q.nominal = Omega;
    q.rotor_speed = q.roller_speed = s.beta0 * Omega / (s.beta0 - s.n * s.beta_e);
    q.branch = "synchronous";
    q.stable = q.rotor_speed > s.omega_krit;
    return q;
}

StationaryPoint curve_point(const SommerfeldAnalysis& a, double p) {
    const SommerfeldSystem& s = a.system;
    StationaryPoint q;
    q.rotor_speed = rotor_speed_at(s, p);
    q.roller_speed = s.n == 0 ? 0.0 : p;
    q.nominal = nominal_at(s, p);
    q.stable = curve_point_stable(s, p);
    if (!a.has_jump) q.branch = "single";
    else if (p <= a.jump_up.p) q.branch = "resonance";
    else if (p < a.jump_down.p) q.branch = "unstable";
    else q.branch = "upper";
    return q;
}

SommerfeldAnalysis analyse_sommerfeld(const AutobalancerParameters& params) {
    SommerfeldAnalysis a;
    a.system = sommerfeld_system(params);
    const SommerfeldSystem& s = a.system;
    a.estimate = limit_speed_estimate(s);
    const std::vector<double> g = search_grid(s, 0.0);
    std::vector<double> v(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) v[i] = nominal_at(s, g[i]);
    for (std::size_t i = 1; i + 1 < g.size(); ++i) {
        const bool mx = v[i] > v[i - 1] && v[i] >= v[i + 1];
        const bool mn = v[i] < v[i - 1] && v[i] <= v[i + 1];
        if (!mx && !mn) continue;
        const double sign = mx ? -1.0 : 1.0;
        Fold f;
        f.maximum = mx;
        f.p = find_minimum([&](double p) { return sign * nominal_at(s, p); }, g[i - 1], g[i + 1], 1e-13);
        a.folds.push_back(f);
    }
    // The jump pair: the largest local maximum and the minimum that follows it.
    for (std::size_t i = 0; i + 1 < a.folds.size(); ++i) {
        if (!a.folds[i].maximum || a.folds[i + 1].maximum) continue;
        if (!a.has_jump || nominal_at(s, a.folds[i].p) > nominal_at(s, a.jump_up.p)) {
            a.has_jump = true;
            a.jump_up = a.folds[i];
            a.jump_down = a.folds[i + 1];
        }
    }
    for (Fold& f : a.folds) f.point = curve_point(a, f.p);
    if (a.has_jump) {
        a.jump_up.point = curve_point(a, a.jump_up.p);
        a.jump_down.point = curve_point(a, a.jump_down.p);
    }
    return a;
}

std::vector<StationaryPoint> stationary_states(const SommerfeldAnalysis& a, double Omega) {
    const SommerfeldSystem& s = a.system;
    if (!(Omega >= 0.0) || !std::isfinite(Omega))
        throw InputError(fmt::format("sommerfeld: nominal speed {}: allowed: a finite number >= 0 rad/s", Omega));
    std::vector<StationaryPoint> out;
    if (Omega == 0.0) {
        StationaryPoint q = curve_point(a, 0.0);
        out.push_back(q);
    } else {
        // Omega(p) >= p (1 - n beta_e / beta0): no solution beyond p_max.
        const double p_max = 1.01 * Omega / (1.0 - s.n * s.beta_e / s.beta0) + 1.0;
        const std::vector<double> g = search_grid(s, p_max);
        double p0 = 0.0, f0 = -Omega;
        for (double p : g) {
            if (p > p_max) break;
            const double f1 = nominal_at(s, p) - Omega;
            if (f1 == 0.0) {
                out.push_back(curve_point(a, p));
            } else if ((f0 < 0.0 && f1 > 0.0) || (f0 > 0.0 && f1 < 0.0)) {
                const double r = find_root([&](double x) { return nominal_at(s, x) - Omega; }, p0, p, 1e-13);
                out.push_back(curve_point(a, r));
            }
            p0 = p;
            f0 = f1;
        }
    }
    for (auto& q : out) q.nominal = Omega;   // the root's own residual is below the tolerance
    if (s.compensating) out.push_back(synchronous_point(s, Omega));
    return out;
}

QuasiStaticRunup quasi_static_runup(const SommerfeldAnalysis& a, double Omega) {
    if (!a.has_jump) return QuasiStaticRunup::Continuous;
    if (Omega < a.jump_down.point.nominal) return QuasiStaticRunup::BelowResonance;
    if (Omega < a.jump_up.point.nominal) return QuasiStaticRunup::Captured;
    return QuasiStaticRunup::Passes;
}

std::vector<StationaryPoint> stationary_curve(const SommerfeldAnalysis& a, double p_max, int points) {
    if (!(p_max > 0.0) || points < 2) throw InputError("sommerfeld: the curve needs p_max > 0 and >= 2 points");
    std::vector<StationaryPoint> out;
    for (int i = 1; i <= points; ++i) out.push_back(curve_point(a, p_max * i / points));
    return out;
}

}  // namespace gyrokit
