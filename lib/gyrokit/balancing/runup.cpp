#include <gyrokit/balancing/runup.hpp>

#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <fmt/format.h>

namespace gyrokit {

namespace {

double circular_mean(const std::vector<double>& a) {
    std::complex<double> z = 0.0;
    for (double x : a) z += std::polar(1.0, x);
    return std::abs(z) > 0.0 ? wrap_phase(std::arg(z)) : 0.0;
}

}  // namespace

void RunupSettings::validate() const {
    auto bad = [](double v) { return !std::isfinite(v); };
    if (bad(max_speed) || !(max_speed > 0.0))
        throw InputError(fmt::format("runup: max_speed = {}: allowed: > 0 rad/s", max_speed));
    if (bad(rise) || !(rise > 0.0)) throw InputError(fmt::format("runup: rise = {}: allowed: > 0 s", rise));
    if (bad(hold) || !(hold > 0.0)) throw InputError(fmt::format("runup: hold = {}: allowed: > 0 s", hold));
    if (bad(fall) || !(fall >= 0.0)) throw InputError(fmt::format("runup: fall = {}: allowed: >= 0 s", fall));
    if (!(ode.abs_tol > 0.0 && ode.abs_tol < 1.0) || !(ode.rel_tol > 0.0 && ode.rel_tol < 1.0))
        throw InputError(fmt::format("runup: abs_tol = {}, rel_tol = {}: allowed: 0 < tolerance < 1", ode.abs_tol,
                                     ode.rel_tol));
    if (history_points < 2 || !(hold_window > 0.0 && hold_window <= 1.0))
        throw InputError("runup: history_points >= 2 and 0 < hold_window <= 1 are required");
}

double runup_nominal_speed(const RunupSettings& s, double t) {
    const double W = s.max_speed;
    if (t <= 0.0) return 0.0;
    if (t < s.rise) return 0.5 * W * (1.0 - std::cos(kPi * t / s.rise));
    const double t1 = s.rise + s.hold;
    if (t <= t1) return W;
    if (s.fall > 0.0 && t < t1 + s.fall) return 0.5 * W * (1.0 + std::cos(kPi * (t - t1) / s.fall));
    return 0.0;
}

double runup_nominal_angle(const RunupSettings& s, double t) {
    const double W = s.max_speed;
    if (t <= 0.0) return 0.0;
    const double tr = std::min(t, s.rise);
    double a = 0.5 * W * (tr - s.rise / kPi * std::sin(kPi * tr / s.rise));
    if (t <= s.rise) return a;
    const double t1 = s.rise + s.hold;
    a += W * (std::min(t, t1) - s.rise);
    if (t <= t1 || s.fall <= 0.0) return a;
    const double tf = std::min(t - t1, s.fall);
    return a + 0.5 * W * (tf + s.fall / kPi * std::sin(kPi * tf / s.fall));
}

RunupResult simulate_runup(const AutobalancerParameters& p, const RunupSettings& s) {
    s.validate();
    if (p.drive != Drive::Motor) throw InputError("runup: the run-up needs the motor drive (L0, beta0)");
    AutobalancerModel model(p);
    model.set_nominal_profile({[s](double t) { return runup_nominal_speed(s, t); },
                               [s](double t) { return runup_nominal_angle(s, t); }});
    const int nr = model.rollers();
    std::vector<double> alpha = s.alpha;
    if (alpha.empty()) alpha.assign(static_cast<std::size_t>(nr), 0.0);
    std::vector<double> y = model.initial_state(alpha);
    y[5] = 0.0;   // from rest

    const double T = s.duration(), tw1 = s.rise + s.hold, tw0 = tw1 - s.hold_window * s.hold;
    std::vector<double> times;
    for (int k = 1; k <= s.history_points; ++k) times.push_back(T * k / s.history_points);
    const int nwin = 400;
    for (int k = 0; k <= nwin; ++k) times.push_back(tw0 + (tw1 - tw0) * k / nwin);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end(), [](double a, double b) { return std::fabs(a - b) < 1e-12; }),
                times.end());

    RunupResult r;
    r.roller_speed.assign(static_cast<std::size_t>(nr), {});
    r.alpha.assign(static_cast<std::size_t>(nr), {});
    std::vector<double> ds(model.state_size());
    double ang0_w0 = 0.0, ang0_w1 = 0.0, angr_w0 = 0.0, angr_w1 = 0.0, amp_sum = 0.0;
    int amp_n = 0;
    std::vector<double> win_diff;
    std::vector<std::vector<double>> win_alpha(static_cast<std::size_t>(nr));
    auto record = [&](double t, const double* st) {
        const char* why = nullptr;
        if (!model.rhs(t, st, ds.data(), &why)) throw SolverError(fmt::format("runup: at t = {} s: {}", t, why));
        const double phi0 = model.rotor_angle(t, st), w0 = model.rotor_speed(st);
        const double xdd = ds[2], ydd = ds[3];
        r.t.push_back(t);
        r.nominal.push_back(runup_nominal_speed(s, t));
        r.rotor_speed.push_back(w0);
        r.amplitude.push_back(std::hypot(st[0], st[1]));
        const double U0 = p.m0 * p.eps0;
        r.torque_rotor.push_back(-U0 * (xdd * std::sin(phi0) - ydd * std::cos(phi0)));
        double tr = 0.0, roller_angle = 0.0;
        for (int i = 0; i < nr; ++i) {
            const std::size_t iu = static_cast<std::size_t>(i);
            const double a = st[model.alpha_index(i)], phi = phi0 + a;
            tr += -p.rollers[iu].unbalance() * (xdd * std::sin(phi) - ydd * std::cos(phi));
            r.roller_speed[iu].push_back(w0 + st[model.alpha_rate_index(i)]);
            r.alpha[iu].push_back(a);
            roller_angle += phi / nr;
        }
        r.torque_rollers.push_back(tr);
        const double diff = nr == 2 ? phase_distance(st[model.alpha_index(0)], st[model.alpha_index(1)]) : 0.0;
        r.phase_difference.push_back(diff);
        if (t >= tw0 - 1e-12 && t <= tw1 + 1e-12) {
            if (std::fabs(t - tw0) < 1e-12) { ang0_w0 = phi0; angr_w0 = roller_angle; }
            if (std::fabs(t - tw1) < 1e-12) { ang0_w1 = phi0; angr_w1 = roller_angle; }
            amp_sum += r.amplitude.back();
            ++amp_n;
            if (nr == 2) win_diff.push_back(st[model.alpha_index(0)] - st[model.alpha_index(1)]);
            for (int i = 0; i < nr; ++i) win_alpha[static_cast<std::size_t>(i)].push_back(st[model.alpha_index(i)]);
        }
    };
    record(0.0, y.data());
    const OdeRhs f = [&model](double t, const double* st, double* d, const char** why) { return model.rhs(t, st, d, why); };
    // The steps follow the fastest oscillation: the rotation once it is fast, the
    // bearings' natural frequency before.
    OdeOptions ode = s.ode;
    const double wn = std::max(p.omega_x(), p.omega_y());
    ode.work = [s, wn](double t) { return runup_nominal_angle(s, t) + wn * t; };
    integrate_ode(f, y, 0.0, times, ode, record, &r.stats);

    const double dt = tw1 - tw0;
    r.held_nominal = s.max_speed;
    r.held_rotor_speed = (ang0_w1 - ang0_w0) / dt;
    r.held_roller_speed = nr > 0 ? (angr_w1 - angr_w0) / dt : 0.0;
    r.held_amplitude = amp_n > 0 ? amp_sum / amp_n : 0.0;
    if (nr == 2) r.held_phase_difference = phase_distance(circular_mean(win_diff), 0.0);
    for (int i = 0; i < nr; ++i) r.held_alpha.push_back(circular_mean(win_alpha[static_cast<std::size_t>(i)]));
    r.final_rotor_speed = r.rotor_speed.back();
    return r;
}

RunupSummary summarize_runup(const AutobalancerParameters& p, const RunupResult& r) {
    const SommerfeldAnalysis a = analyse_sommerfeld(p);
    const SommerfeldSystem& s = a.system;
    RunupSummary out;
    out.omega_krit = s.omega_krit;
    out.jump_up = a.has_jump ? a.jump_up.point.nominal : 0.0;
    const double held = s.n == 0 ? r.held_rotor_speed : r.held_roller_speed;
    const StationaryPoint* best = nullptr;
    const std::vector<StationaryPoint> states = stationary_states(a, r.held_nominal);
    for (int pass = 0; pass < 2 && !best; ++pass)
        for (const auto& q : states) {
            if (pass == 0 && !q.stable) continue;
            const double v = s.n == 0 ? q.rotor_speed : q.roller_speed;
            if (!best || std::fabs(v - held) < std::fabs((s.n == 0 ? best->rotor_speed : best->roller_speed) - held))
                best = &q;
        }
    if (!best) throw SolverError("runup: no stationary state at the held nominal speed");
    out.branch = best->branch;
    out.stationary_rotor_speed = best->rotor_speed;
    out.stationary_roller_speed = best->roller_speed;
    if (best->branch == "resonance" && r.held_nominal > s.omega_krit) {
        out.captured = true;
        out.outcome = "captured";
    } else {
        out.outcome = held > s.omega_krit ? "passed" : "subcritical";
    }
    return out;
}

}  // namespace gyrokit
