#include <gyrokit/balancing/simulation.hpp>

#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

namespace gyrokit {

namespace {

struct Method {
    OdeMethod m;
    const char* name;
    const gsl_odeiv2_step_type* const* type;
    bool implicit;
};

const std::vector<Method>& methods() {
    static const std::vector<Method> ms = {
        {OdeMethod::Rk2, "rk2", &gsl_odeiv2_step_rk2, false},
        {OdeMethod::Rk4, "rk4", &gsl_odeiv2_step_rk4, false},
        {OdeMethod::Rkf45, "rkf45", &gsl_odeiv2_step_rkf45, false},
        {OdeMethod::Rkck, "rkck", &gsl_odeiv2_step_rkck, false},
        {OdeMethod::Rk8pd, "rk8pd", &gsl_odeiv2_step_rk8pd, false},
        {OdeMethod::Msadams, "msadams", &gsl_odeiv2_step_msadams, false},
        {OdeMethod::Rk4imp, "rk4imp", &gsl_odeiv2_step_rk4imp, true},
        {OdeMethod::Bsimp, "bsimp", &gsl_odeiv2_step_bsimp, true},
        {OdeMethod::Msbdf, "msbdf", &gsl_odeiv2_step_msbdf, true},
    };
    return ms;
}

const Method& method(OdeMethod m) {
    for (const auto& x : methods())
        if (x.m == m) return x;
    throw Error("unknown ODE method");
}

struct Context {
    const OdeRhs* f = nullptr;
    std::size_t n = 0;
    unsigned long evaluations = 0;
    const char* why = nullptr;
    std::vector<double> work1, work2;
    // Watching the run: interrupts, progress, and the projected step count.
    const OdeOptions* options = nullptr;
    const gsl_odeiv2_driver* driver = nullptr;
    double t0 = 0.0, t_end = 0.0;
    std::chrono::steady_clock::time_point start, last_report;
    bool interrupted = false, reported = false;
    std::string hopeless;   // why the run was given up early
    double steps_ref = -1.0, done_ref = 0.0;   // at the first report: the start's transient left out
    std::exception_ptr failure;   // thrown by the right-hand side or the progress callback
};

constexpr double kOdeReportSeconds = 0.5;
constexpr double kOdeProjectAfterSeconds = 2.0;
constexpr double kOdeProjectFactor = 1.5;

// Every 1024 right-hand sides: an interrupt stops the run; every half second, the
// progress callback, and a run whose steps since the first half second project
// more than 1.5 x max_steps stops then, not at the limit hours later (a run-up to
// 1e9 rad/s).
bool watch(Context* c, double t);

bool keep_going(Context* c, double t) {
    if ((c->evaluations & 1023u) != 0) return true;
    try {   // nothing may unwind through GSL's C frames
        return watch(c, t);
    } catch (...) {
        c->failure = std::current_exception();
        c->why = "the progress callback or the work function failed";
        return false;
    }
}

bool watch(Context* c, double t) {
    if (interrupt_requested()) {
        c->interrupted = true;
        c->why = "interrupted";
        return false;
    }
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - c->last_report).count() < kOdeReportSeconds) return true;
    c->last_report = now;
    const double span = c->t_end - c->t0;
    const double fraction = span > 0.0 ? std::clamp((t - c->t0) / span, 0.0, 1.0) : 1.0;
    if (c->options->progress) {
        c->options->progress(fraction);
        c->reported = true;
    }
    const double wall = std::chrono::duration<double>(now - c->start).count();
    const double steps = static_cast<double>(c->driver->e->count);
    double done = fraction;
    if (c->options->work) {
        const auto& w = c->options->work;
        const double w0 = w(c->t0), total = w(c->t_end) - w0;
        done = total > 0.0 ? std::clamp((w(t) - w0) / total, 0.0, 1.0) : fraction;
    }
    if (c->steps_ref < 0.0) {
        c->steps_ref = steps;
        c->done_ref = done;
        return true;
    }
    const double projected =
        done > c->done_ref ? c->steps_ref + (steps - c->steps_ref) / (done - c->done_ref) * (1.0 - c->done_ref) : 0.0;
    if (wall > kOdeProjectAfterSeconds && projected > kOdeProjectFactor * static_cast<double>(c->options->max_steps)) {
        c->hopeless = fmt::format(
            "after {:.3g} s of {:.6g} s, {:.0f} steps project about {:.2g} steps for the run, more than "
            "max_steps = {}; shorten the run, lower the speed, loosen the tolerances or raise max_steps",
            t - c->t0, span, steps, projected, c->options->max_steps);
        c->why = c->hopeless.c_str();
        return false;
    }
    return true;
}

int c_rhs(double t, const double y[], double dydt[], void* params) {
    auto* c = static_cast<Context*>(params);
    ++c->evaluations;
    if (!keep_going(c, t)) return GSL_EBADFUNC;
    const char* why = nullptr;
    try {
        if (!(*c->f)(t, y, dydt, &why)) {
            c->why = why ? why : "the right-hand side could not be evaluated";
            return GSL_EBADFUNC;
        }
    } catch (...) {   // rethrown after the driver is freed, never through GSL's C frames
        c->failure = std::current_exception();
        c->why = "the right-hand side failed";
        return GSL_EBADFUNC;
    }
    return GSL_SUCCESS;
}

// Forward-difference Jacobian for the implicit steppers.
int c_jac(double t, const double y[], double* dfdy, double dfdt[], void* params) {
    auto* c = static_cast<Context*>(params);
    const std::size_t n = c->n;
    c->work1.resize(n);
    c->work2.resize(n);
    std::vector<double> yp(y, y + n);
    if (c_rhs(t, y, c->work1.data(), params) != GSL_SUCCESS) return GSL_EBADFUNC;
    const double sq = 1.4901161193847656e-08;
    for (std::size_t j = 0; j < n; ++j) {
        const double h = sq * std::max(std::fabs(y[j]), 1e-6);
        yp[j] = y[j] + h;
        if (c_rhs(t, yp.data(), c->work2.data(), params) != GSL_SUCCESS) return GSL_EBADFUNC;
        for (std::size_t i = 0; i < n; ++i) dfdy[i * n + j] = (c->work2[i] - c->work1[i]) / h;
        yp[j] = y[j];
    }
    const double ht = sq * std::max(std::fabs(t), 1e-3);
    if (c_rhs(t + ht, y, c->work2.data(), params) != GSL_SUCCESS) return GSL_EBADFUNC;
    for (std::size_t i = 0; i < n; ++i) dfdt[i] = (c->work2[i] - c->work1[i]) / ht;
    return GSL_SUCCESS;
}

}  // namespace

OdeMethod parse_ode_method(const std::string& name) {
    for (const auto& m : methods())
        if (name == m.name) return m.m;
    std::string list;
    for (const auto& m : methods()) list += (list.empty() ? "" : ", ") + std::string(m.name);
    throw InputError(fmt::format("ODE method '{}': allowed: {}", name, list));
}

std::string ode_method_name(OdeMethod m) { return method(m).name; }

const std::vector<std::string>& ode_method_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const auto& m : methods()) v.push_back(m.name);
        return v;
    }();
    return names;
}

void integrate_ode(const OdeRhs& f, std::vector<double>& y, double t0, const std::vector<double>& t_out,
                   const OdeOptions& o, const std::function<void(double, const double*)>& on_output,
                   OdeStats* stats) {
    if (!(o.abs_tol > 0.0) || !(o.rel_tol > 0.0) || !std::isfinite(o.abs_tol) || !std::isfinite(o.rel_tol))
        throw InputError(fmt::format("ODE tolerances abs = {}, rel = {}: allowed: finite numbers > 0", o.abs_tol,
                                     o.rel_tol));
    const auto start = std::chrono::steady_clock::now();
    gsl_set_error_handler_off();   // failures come back as status codes and are reported below
    Context c;
    c.f = &f;
    c.n = y.size();
    c.options = &o;
    c.t0 = t0;
    c.t_end = t_out.empty() ? t0 : t_out.back();
    c.start = c.last_report = start;
    const Method& m = method(o.method);
    gsl_odeiv2_system sys{&c_rhs, m.implicit ? &c_jac : nullptr, y.size(), &c};
    double h0 = o.h0;
    if (!(h0 > 0.0)) h0 = t_out.empty() ? 1e-6 : std::max(1e-12, 1e-3 * std::fabs(t_out.front() - t0));
    // Freed on every way out, an exception of on_output or the progress callback included.
    const std::unique_ptr<gsl_odeiv2_driver, void (*)(gsl_odeiv2_driver*)> owner(
        gsl_odeiv2_driver_alloc_y_new(&sys, *m.type, h0, o.abs_tol, o.rel_tol), &gsl_odeiv2_driver_free);
    gsl_odeiv2_driver* const d = owner.get();
    if (!d) throw SolverError("could not allocate the GSL ODE driver");
    gsl_odeiv2_driver_set_nmax(d, o.max_steps);
    c.driver = d;
    double t = t0;
    for (double t1 : t_out) {
        // The driver counts steps per call; the limit is meant for the whole run.
        const unsigned long used = d->e->count;
        int status = GSL_SUCCESS;
        if (t1 > t) {
            if (used >= o.max_steps) {
                status = GSL_EMAXITER;
            } else {
                gsl_odeiv2_driver_set_nmax(d, o.max_steps - used);
                status = gsl_odeiv2_driver_apply(d, &t, t1, y.data());
            }
        }
        if (status != GSL_SUCCESS && (c.interrupted || c.failure)) {
            if (c.failure) std::rethrow_exception(c.failure);
            throw Interrupted();
        }
        if (status != GSL_SUCCESS) {
            std::string why;
            switch (status) {
                case GSL_EBADFUNC: why = c.why ? c.why : "the right-hand side could not be evaluated"; break;
                case GSL_EMAXITER:
                    why = fmt::format("the step limit ({} steps) was reached; loosen the tolerances or shorten "
                                      "the run", o.max_steps);
                    break;
                case GSL_ENOPROG: why = "no progress: the step size underflowed; try a stiff method (msbdf, bsimp) "
                                        "or looser tolerances"; break;
                case GSL_FAILURE: why = "the step size fell below the minimum; try looser tolerances or another "
                                        "method"; break;
                default: why = gsl_strerror(status);
            }
            throw SolverError(fmt::format("ODE integration ({}, abs_tol {}, rel_tol {}) failed at t = {:.9g} s: {}",
                                          m.name, o.abs_tol, o.rel_tol, t, why));
        }
        on_output(t, y.data());
    }
    if (c.reported) o.progress(1.0);
    if (stats) {
        stats->steps = d->e->count;
        stats->evaluations = c.evaluations;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
}

namespace {

// Output times: history_points uniform samples before the final window, then
// samples_per_revolution per revolution over the window. Returns the index
// where the window starts.
std::size_t output_times(const SimulationSettings& s, double Omega, std::vector<double>& times) {
    if (!(s.duration > 0.0) || !std::isfinite(s.duration))
        throw InputError(fmt::format("simulation duration {} s: allowed: > 0", s.duration));
    if (!(Omega > 0.0))
        throw InputError("simulation: the reference speed must be > 0 rad/s");
    if (s.samples_per_revolution < 4 || s.history_points < 2 || !(s.average_revolutions > 0.0))
        throw InputError("simulation: samples_per_revolution >= 4, history_points >= 2 and "
                         "average_revolutions > 0 are required");
    const double rev = 2.0 * kPi / Omega;
    const long nwin_rev = std::max(1L, std::lround(std::min(s.average_revolutions, std::floor(s.duration / rev / 2))));
    const double t_win = s.duration - static_cast<double>(nwin_rev) * rev;
    times.clear();
    for (int k = 1; k <= s.history_points; ++k) {
        const double t = s.duration * k / s.history_points;
        if (t < t_win) times.push_back(t);
    }
    const std::size_t w = times.size();
    const long nw = nwin_rev * s.samples_per_revolution;
    for (long k = 0; k <= nw; ++k) times.push_back(t_win + static_cast<double>(k) * (s.duration - t_win) / nw);
    return w;
}

}  // namespace

SimulationResult simulate(const AutobalancerParameters& p, const SimulationSettings& s) {
    const AutobalancerModel model(p);
    const int nr = model.rollers();
    const double Omega = p.reference_speed();
    std::vector<double> times;
    const std::size_t w = output_times(s, Omega, times);
    std::vector<double> y = model.initial_state(s.alpha, s.x, s.y);
    SimulationResult r;
    r.alpha.assign(static_cast<std::size_t>(nr), {});
    auto record = [&](double t, const double* st) {
        r.t.push_back(t);
        r.speed.push_back(model.rotor_speed(st));
        r.radius.push_back(std::hypot(st[0], st[1]));
        for (int i = 0; i < nr; ++i) r.alpha[static_cast<std::size_t>(i)].push_back(st[model.alpha_index(i)]);
    };
    record(0.0, y.data());
    const OdeRhs f = [&model](double t, const double* st, double* ds, const char** why) {
        return model.rhs(t, st, ds, why);
    };
    integrate_ode(f, y, 0.0, times, s.ode, record, &r.stats);
    // Means over whole revolutions (rectangle rule on a periodic signal: the last sample closes the period).
    const std::size_t a = w + 1, b = r.t.size() - 1;
    const double cnt = static_cast<double>(b - a);
    r.final_alpha.assign(static_cast<std::size_t>(nr), 0.0);
    double sp = 0.0, r2 = 0.0, rmax = 0.0;
    for (std::size_t k = a; k < b; ++k) {
        sp += r.speed[k];
        r2 += r.radius[k] * r.radius[k];
        for (int i = 0; i < nr; ++i) r.final_alpha[static_cast<std::size_t>(i)] += r.alpha[static_cast<std::size_t>(i)][k];
    }
    for (std::size_t k = a; k <= b; ++k) rmax = std::max(rmax, r.radius[k]);
    for (auto& x : r.final_alpha) x = wrap_phase(x / cnt);
    r.final_speed = sp / cnt;
    r.residual_rms = std::sqrt(r2 / cnt);
    r.residual_max = rmax;
    r.revolutions = (model.rotor_angle(s.duration, y.data())) / (2.0 * kPi);
    // Keep only the history part plus the window's end for the caller's plots.
    return r;
}

SimulationResult simulate_averaged(const AutobalancerParameters& p, const SimulationSettings& s) {
    p.validate();
    const std::size_t nr = p.rollers.size();
    const double Omega = p.reference_speed();
    if (s.alpha.size() != nr)
        throw InputError(fmt::format("autobalancer: {} initial phases given for {} rollers", s.alpha.size(), nr));
    std::vector<double> times;
    output_times(s, Omega, times);
    std::vector<double> y(2 * nr, 0.0);
    for (std::size_t i = 0; i < nr; ++i) y[2 * i] = s.alpha[i];
    SimulationResult r;
    r.alpha.assign(nr, {});
    auto record = [&](double t, const double* st) {
        r.t.push_back(t);
        r.speed.push_back(Omega);
        for (std::size_t i = 0; i < nr; ++i) r.alpha[i].push_back(st[2 * i]);
    };
    record(0.0, y.data());
    const OdeRhs f = [&p, Omega](double, const double* st, double* ds, const char** why) {
        slow_rhs(p, Omega, true, st, ds);
        for (std::size_t i = 0; i < 2 * p.rollers.size(); ++i)
            if (!std::isfinite(ds[i])) {
                *why = "the slow right-hand side is not finite";
                return false;
            }
        return true;
    };
    integrate_ode(f, y, 0.0, times, s.ode, record, &r.stats);
    r.final_alpha.resize(nr);
    for (std::size_t i = 0; i < nr; ++i) r.final_alpha[i] = wrap_phase(y[2 * i]);
    r.final_speed = Omega;
    // Steady vibration for these phases: x = Re(H_x F e^{i Omega t}), y = Re(-i H_y F e^{i Omega t}).
    const double M = p.M();
    const std::complex<double> Hx = 1.0 / std::complex<double>(p.k_x - M * Omega * Omega, p.c_x * Omega);
    const std::complex<double> Hy = 1.0 / std::complex<double>(p.k_y - M * Omega * Omega, p.c_y * Omega);
    std::complex<double> F = p.f_unbalance(0, Omega);
    for (std::size_t i = 0; i < nr; ++i) F += p.f_unbalance(static_cast<int>(i + 1), Omega) * std::polar(1.0, y[2 * i]);
    double r2 = 0.0, rmax = 0.0;
    for (int k = 0; k < 64; ++k) {
        const std::complex<double> e = std::polar(1.0, 2.0 * kPi * k / 64.0);
        const double xx = (Hx * F * e).real(), yy = (std::complex<double>(0, -1) * Hy * F * e).real();
        r2 += xx * xx + yy * yy;
        rmax = std::max(rmax, std::hypot(xx, yy));
    }
    r.residual_rms = std::sqrt(r2 / 64.0);
    r.residual_max = rmax;
    r.radius.assign(r.t.size(), 0.0);
    r.revolutions = Omega * s.duration / (2.0 * kPi);
    return r;
}

}  // namespace gyrokit
