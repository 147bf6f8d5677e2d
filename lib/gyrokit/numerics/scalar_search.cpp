#include <gyrokit/numerics/scalar_search.hpp>

#include <gyrokit/core/error.hpp>

#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>

namespace gyrokit {

namespace {

// The function and the first exception it threw: an exception must not unwind
// through GSL's C frames (the solver would leak, or the program end), so it is
// kept here, GSL gets a NaN, and the search rethrows it after freeing the solver.
struct Call {
    const std::function<double(double)>* f;
    std::exception_ptr failure;
};

double trampoline(double x, void* params) {
    auto* c = static_cast<Call*>(params);
    if (c->failure) return std::numeric_limits<double>::quiet_NaN();
    try {
        return (*c->f)(x);
    } catch (...) {
        c->failure = std::current_exception();
        return std::numeric_limits<double>::quiet_NaN();
    }
}

}  // namespace

double find_root(const std::function<double(double)>& f, double a, double b, double rel_tol) {
    const double fa = f(a), fb = f(b);
    if (fa == 0.0) return a;
    if (fb == 0.0) return b;
    if ((fa > 0) == (fb > 0))
        throw SolverError(fmt::format("root search on [{}, {}] has no sign change", a, b));
    // Errors are reported through return codes below; set once, since root
    // searches may run on several threads.
    static std::once_flag quiet;
    std::call_once(quiet, [] { gsl_set_error_handler_off(); });
    Call call{&f, nullptr};
    gsl_function F{&trampoline, &call};
    gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s) throw SolverError("could not allocate the GSL root solver");
    gsl_root_fsolver_set(s, &F, a, b);
    int status = GSL_CONTINUE;
    double x = 0.5 * (a + b);
    for (int it = 0; it < 200 && status == GSL_CONTINUE; ++it) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) break;
        x = gsl_root_fsolver_root(s);
        status = gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0.0, rel_tol);
        if (gsl_root_fsolver_x_upper(s) - gsl_root_fsolver_x_lower(s) <= 4e-16 * std::fabs(x)) status = GSL_SUCCESS;
    }
    gsl_root_fsolver_free(s);
    if (call.failure) std::rethrow_exception(call.failure);
    if (status != GSL_SUCCESS)
        throw SolverError(fmt::format("Brent root search on [{}, {}] did not converge to relative "
                                      "tolerance {}; use a finer speed grid",
                                      a, b, rel_tol));
    return x;
}

double find_minimum(const std::function<double(double)>& f, double a, double b, double rel_tol,
                    const std::function<bool(double, double)>& give_up) {
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = f(c), fd = f(d);
    for (int it = 0; it < 400 && (b - a) > rel_tol * std::max(1.0, std::fabs(c)); ++it) {
        if (give_up && give_up(b - a, std::min(fc, fd))) break;
        if (fc <= fd) {
            b = d; d = c; fd = fc;
            c = b - g * (b - a); fc = f(c);
        } else {
            a = c; c = d; fc = fd;
            d = a + g * (b - a); fd = f(d);
        }
    }
    return fc <= fd ? c : d;
}

double smooth_minimum_resolution(double x, double rel_tol) {
    return std::max(rel_tol, 4.0 * std::sqrt(2.2e-16)) * std::max(1.0, std::fabs(x));
}

double find_smooth_minimum(const std::function<double(double)>& f, double a, double m, double b, double rel_tol) {
    const double fa = f(a), fm = f(m), fb = f(b);
    if (!(fm < fa && fm < fb) || !std::isfinite(fm)) return find_minimum(f, a, b, rel_tol);
    static std::once_flag quiet;
    std::call_once(quiet, [] { gsl_set_error_handler_off(); });
    Call call{&f, nullptr};
    gsl_function F{&trampoline, &call};
    gsl_min_fminimizer* s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    if (!s) throw SolverError("could not allocate the GSL minimizer");
    int status = gsl_min_fminimizer_set_with_values(s, &F, m, fm, a, fa, b, fb);
    double x = m;
    for (int it = 0; it < 200 && status == GSL_SUCCESS; ++it) {
        if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS) {
            status = GSL_FAILURE;
            break;
        }
        x = gsl_min_fminimizer_x_minimum(s);
        const double lo = gsl_min_fminimizer_x_lower(s), hi = gsl_min_fminimizer_x_upper(s);
        // Brent never steps closer than sqrt(eps) |x|: a tighter bracket is never reached.
        if (hi - lo <= smooth_minimum_resolution(x, rel_tol)) break;
    }
    gsl_min_fminimizer_free(s);
    if (call.failure) std::rethrow_exception(call.failure);
    return status == GSL_SUCCESS ? x : find_minimum(f, a, b, rel_tol);
}

}  // namespace gyrokit
