#include <gyrokit/balancing/synchronous_states.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

// Phases with the rotor's unbalance prepended (alpha_0 = 0) and the f_k.
void forces(const AutobalancerParameters& p, double Omega, std::vector<double>& f) {
    f.assign(p.rollers.size() + 1, 0.0);
    for (std::size_t k = 0; k < f.size(); ++k) f[k] = p.f_unbalance(static_cast<int>(k), Omega);
}

double phase_of(const std::vector<double>& alpha, std::size_t k) { return k == 0 ? 0.0 : alpha[k - 1]; }

}  // namespace

double wrap_phase(double a) {
    double w = std::fmod(a, 2.0 * kPi);
    if (w < 0.0) w += 2.0 * kPi;
    if (w >= 2.0 * kPi) w = 0.0;
    return w;
}

double phase_distance(double a, double b) {
    const double d = wrap_phase(a - b);
    return std::min(d, 2.0 * kPi - d);
}

std::complex<double> influence_sum(const AutobalancerParameters& p, double Omega, bool damped) {
    const double M = p.M();
    const double cx = damped ? p.c_x : 0.0, cy = damped ? p.c_y : 0.0;
    const std::complex<double> dx(p.k_x - M * Omega * Omega, cx * Omega), dy(p.k_y - M * Omega * Omega, cy * Omega);
    if (std::abs(dx) == 0.0 || std::abs(dy) == 0.0)
        throw InputError(fmt::format("autobalancer: speed {} rad/s is an undamped natural frequency; the "
                                     "influence coefficients are infinite there", Omega));
    return 1.0 / dx + 1.0 / dy;
}

std::vector<double> vibration_torques(const AutobalancerParameters& p, double Omega, const std::vector<double>& alpha,
                                      bool damped) {
    const std::complex<double> H = influence_sum(p, Omega, damped);
    std::vector<double> f;
    forces(p, Omega, f);
    std::vector<double> V(alpha.size(), 0.0);
    for (std::size_t i = 1; i < f.size(); ++i) {
        double s = 0.0;
        for (std::size_t k = 0; k < f.size(); ++k) {
            const double d = phase_of(alpha, i) - phase_of(alpha, k);
            s += f[k] * (H.real() * std::sin(d) - H.imag() * std::cos(d));
        }
        V[i - 1] = 0.5 * f[i] * s;
    }
    return V;
}

std::vector<double> vibration_torque_jacobian(const AutobalancerParameters& p, double Omega,
                                              const std::vector<double>& alpha, bool damped) {
    const std::complex<double> H = influence_sum(p, Omega, damped);
    std::vector<double> f;
    forces(p, Omega, f);
    const std::size_t n = alpha.size();
    std::vector<double> D(n * n, 0.0);
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t k = 0; k <= n; ++k) {
            if (k == i) continue;
            const double d = phase_of(alpha, i) - phase_of(alpha, k);
            const double g = 0.5 * f[i] * f[k] * (H.real() * std::cos(d) + H.imag() * std::sin(d));
            D[(i - 1) * n + (i - 1)] += g;
            if (k >= 1) D[(i - 1) * n + (k - 1)] -= g;
        }
    return D;
}

std::vector<SynchronousState> synchronous_states(const AutobalancerParameters& p) {
    const double U0 = p.m0 * p.eps0;
    if (!(U0 > 0.0))
        throw InputError("autobalancer: synchronous states need a rotor unbalance m0 * eps0 > 0");
    std::vector<SynchronousState> out;
    if (p.rollers.size() == 1) {
        out.push_back({"0", {0.0}, false});
        out.push_back({"pi", {kPi}, p.rollers[0].unbalance() == U0});
        return out;
    }
    if (p.rollers.size() != 2) return out;
    // The f_i scale alike with Omega^2: work with the unbalances.
    const double f0 = U0, f1 = p.rollers[0].unbalance(), f2 = p.rollers[1].unbalance();
    // Strict triangle inequality (41): otherwise (43)/(44) coincide with a type-2 state.
    if (f0 < f1 + f2 && f1 < f0 + f2 && f2 < f0 + f1) {
        const double g1 = std::acos(std::clamp((f0 * f0 + f1 * f1 - f2 * f2) / (2.0 * f0 * f1), -1.0, 1.0));
        const double g2 = std::acos(std::clamp((f0 * f0 - f1 * f1 + f2 * f2) / (2.0 * f0 * f2), -1.0, 1.0));
        out.push_back({"43", {kPi - g1, kPi + g2}, true});
        out.push_back({"44", {kPi + g1, kPi - g2}, true});
    }
    out.push_back({"45", {0.0, 0.0}, false});
    out.push_back({"46", {kPi, kPi}, f1 + f2 == f0});
    out.push_back({"48", {kPi, 0.0}, f1 == f0 + f2});
    out.push_back({"47", {0.0, kPi}, f2 == f0 + f1});
    return out;
}

std::vector<SpeedInterval> speed_intervals(const AutobalancerParameters& p) {
    const double wx = p.omega_x(), wy = p.omega_y();
    const double inf = std::numeric_limits<double>::infinity();
    if (std::fabs(wx - wy) <= 1e-12 * std::max(wx, wy)) {
        return {{0.0, wx, "Omega < omega", 0.5 * wx}, {wx, inf, "Omega > omega", 2.0 * wx}};
    }
    const bool xlow = wx < wy;
    const double wl = std::min(wx, wy), wh = std::max(wx, wy);
    const double w0 = std::sqrt(0.5 * (wx * wx + wy * wy));
    const std::string lo = xlow ? "omega_x" : "omega_y", hi = xlow ? "omega_y" : "omega_x";
    auto mid = [](double a, double b) { return std::sqrt(0.5 * (a * a + b * b)); };
    return {{0.0, wl, "Omega < " + lo, 0.5 * wl},
            {wl, w0, lo + " < Omega < omega_0", mid(wl, w0)},
            {w0, wh, "omega_0 < Omega < " + hi, mid(w0, wh)},
            {wh, inf, hi + " < Omega", 2.0 * wh}};
}

bool stable_by_criterion(const AutobalancerParameters& p, const std::vector<double>& alpha, double Omega) {
    const double A = influence_sum(p, Omega, false).real();
    const double f0 = p.f_unbalance(0, Omega);
    if (alpha.size() == 1) {
        const double k = A * f0 * std::cos(alpha[0]);
        return k > 1e-12 * std::fabs(A) * f0;
    }
    if (alpha.size() != 2) return false;
    const double f1 = p.f_unbalance(1, Omega), f2 = p.f_unbalance(2, Omega);
    const double a1 = alpha[0], a2 = alpha[1], c12 = std::cos(a1 - a2);
    // K of eq. (52); not symmetric, so "K > 0" means positive leading principal minors.
    const double K11 = A * (f0 * std::cos(a1) + f2 * c12), K12 = -A * f2 * c12;
    const double K21 = -A * f1 * c12, K22 = A * (f0 * std::cos(a2) + f1 * c12);
    const double scale = std::fabs(A) * std::max({f0, f1, f2});
    return K11 > 1e-12 * scale && K11 * K22 - K12 * K21 > 1e-12 * scale * scale;
}

std::vector<std::complex<double>> slow_eigenvalues(const AutobalancerParameters& p, double Omega,
                                                   const std::vector<double>& alpha, bool damped) {
    const std::size_t n = alpha.size();
    if (n == 0) return {};
    const std::vector<double> D = vibration_torque_jacobian(p, Omega, alpha, damped);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const Roller& r = p.rollers[i];
        A(i, n + i) = 1.0;
        for (std::size_t j = 0; j < n; ++j) A(n + i, j) = -D[i * n + j] / r.J_ii();
        A(n + i, n + i) = -r.beta / r.J_ii();
    }
    Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
    if (es.info() != Eigen::Success) throw SolverError("autobalancer: eigenvalues of the slow equations did not converge");
    std::vector<std::complex<double>> ev(es.eigenvalues().data(), es.eigenvalues().data() + 2 * n);
    std::sort(ev.begin(), ev.end(), [](auto a, auto b) { return a.real() > b.real(); });
    return ev;
}

bool stable_by_eigenvalues(const std::vector<std::complex<double>>& ev) {
    double mx = 0.0, mr = -std::numeric_limits<double>::infinity();
    for (const auto& l : ev) {
        mx = std::max(mx, std::abs(l));
        mr = std::max(mr, l.real());
    }
    return !ev.empty() && mr < -1e-10 * mx;
}

std::vector<StateStability> state_stability_ranges(const AutobalancerParameters& p) {
    std::vector<StateStability> out;
    const auto ranges = speed_intervals(p);
    for (const auto& s : synchronous_states(p))
        for (const auto& r : ranges) {
            StateStability e;
            e.state = s;
            e.range = r;
            e.stable_criterion = stable_by_criterion(p, s.alpha, r.sample);
            const auto ev = slow_eigenvalues(p, r.sample, s.alpha, false);
            e.stable_eigen = stable_by_eigenvalues(ev);
            e.max_real_eigenvalue = ev.empty() ? 0.0 : ev.front().real();
            out.push_back(e);
        }
    return out;
}

std::vector<double> damped_equilibrium(const AutobalancerParameters& p, double Omega, std::vector<double> a) {
    const std::size_t n = a.size();
    if (n == 0) return a;
    for (int it = 0; it < 60; ++it) {
        const auto V = vibration_torques(p, Omega, a, true);
        const auto D = vibration_torque_jacobian(p, Omega, a, true);
        Eigen::MatrixXd J(n, n);
        Eigen::VectorXd r(n);
        for (std::size_t i = 0; i < n; ++i) {
            r(i) = V[i];
            for (std::size_t j = 0; j < n; ++j) J(i, j) = D[i * n + j];
        }
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(J);
        if (!lu.isInvertible())
            throw SolverError(fmt::format("autobalancer: the damped slow equations are singular at {} rad/s", Omega));
        const Eigen::VectorXd step = lu.solve(r);
        double big = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            // Limit the step so Newton cannot jump to a different state.
            const double d = std::clamp(step(i), -0.3, 0.3);
            a[i] -= d;
            big = std::max(big, std::fabs(d));
        }
        if (big < 1e-13) {
            for (auto& x : a) x = wrap_phase(x);
            return a;
        }
    }
    throw SolverError(fmt::format("autobalancer: Newton's method for the damped synchronous state did not "
                                  "converge at {} rad/s; the bearing damping may be too large for the slow model",
                                  Omega));
}

NearestState nearest_stable_state(const AutobalancerParameters& p, double Omega, const std::vector<double>& alpha) {
    NearestState best;
    if (p.rollers.empty() || !(p.m0 * p.eps0 > 0.0)) return best;
    for (const auto& s : synchronous_states(p)) {
        std::vector<double> a;
        try {
            a = damped_equilibrium(p, Omega, s.alpha);
        } catch (const SolverError&) {
            continue;   // no damped equilibrium near this state
        }
        if (!stable_by_eigenvalues(slow_eigenvalues(p, Omega, a, true))) continue;
        double d = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, phase_distance(a[i], alpha[i]));
        if (d < best.distance) best = {s.label, a, d};
    }
    return best;
}

void slow_rhs(const AutobalancerParameters& p, double Omega, bool damped, const double* s, double* dsdt) {
    const std::size_t n = p.rollers.size();
    std::vector<double> a(n);
    for (std::size_t i = 0; i < n; ++i) a[i] = s[2 * i];
    const auto V = vibration_torques(p, Omega, a, damped);
    for (std::size_t i = 0; i < n; ++i) {
        const Roller& r = p.rollers[i];
        dsdt[2 * i] = s[2 * i + 1];
        dsdt[2 * i + 1] = -(r.beta * s[2 * i + 1] + V[i]) / r.J_ii();
    }
}

}  // namespace gyrokit

namespace gyrokit {

std::vector<RangeVerdict> range_verdicts(const std::vector<StateStability>& table) {
    std::vector<RangeVerdict> out;
    for (const auto& e : table) {
        auto it = std::find_if(out.begin(), out.end(), [&](const RangeVerdict& v) { return v.range.name == e.range.name; });
        if (it == out.end()) it = out.insert(out.end(), RangeVerdict{e.range, {}, {}, {}});
        if (e.stable_criterion != e.stable_eigen)
            it->disputed.push_back(e.state.label);
        else if (e.stable_eigen)
            (e.state.compensating ? it->compensating : it->other).push_back(e.state.label);
    }
    return out;
}

}  // namespace gyrokit
