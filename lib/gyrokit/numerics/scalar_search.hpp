// One-dimensional searches shared by the analyses: a root of a sign-changing
// function (GSL Brent) and the minimum of a unimodal function (golden section,
// which also converges to the kink of a V-shaped minimum).
#pragma once

#include <functional>

namespace gyrokit {

// Root of f in [a, b] with f(a) f(b) <= 0, to relative tolerance `rel_tol`.
// Throws SolverError if GSL does not converge.
double find_root(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-13);

// Minimizer of f on [a, b] by golden section, until the bracket is below
// rel_tol * max(1, |x|), or until give_up(bracket width, smallest value) says
// the search cannot reach what the caller looks for.
double find_minimum(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-14,
                    const std::function<bool(double, double)>& give_up = {});

// Minimizer of a smooth f on [a, b] from a point m inside with f(m) < f(a) and
// f(m) < f(b), by GSL's Brent minimizer (golden section with parabolic steps),
// to max(rel_tol, 4 sqrt(eps)) * max(1, |x|): Brent's steps stop at sqrt(eps) |x|,
// where a smooth minimum's value is already exact to rounding.
// Without such an m (equal values), or if GSL fails, golden section.
double find_smooth_minimum(const std::function<double(double)>& f, double a, double m, double b,
                           double rel_tol = 1e-12);

// The bracket width at which find_smooth_minimum stops near x: the uncertainty
// of the minimizer it returns.
double smooth_minimum_resolution(double x, double rel_tol = 1e-12);

}  // namespace gyrokit
