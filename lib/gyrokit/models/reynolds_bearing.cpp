#include <gyrokit/models/reynolds_bearing.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <string>

namespace gyrokit {

namespace {

// Relative step of the central differences in position and velocity, times
// s = min(e, 1 - e), the distance over which the film force changes by its own
// size (to the centre, where the pressure pattern turns with the journal, and to
// the wall, where H -> 0). Truncation: the clipped force is smooth except where a
// node's pressure changes sign inside the step (the cavitation boundary crosses
// a node), which leaves a first-order term; measured at the default grid it is
// up to 0.2 step / s of a coefficient, 2e-7 at this step (the O(step^2) part of a
// smooth function is 1e-12). Rounding: one force carries a relative error of
// about 1e-14 (a few hundred Thomas steps, N M summed terms), which the
// difference divides by the step: 1e-14 / 1e-6 = 1e-8. Steps of 1e-5 to 1e-7
// agree to 1e-6 of the largest coefficient; 1e-6 balances the two terms and keeps
// both four orders below the discretisation error of the default grid (about
// 1e-3, docs/fe_rotor.md).
constexpr double kRelativeStep = 1e-6;

// Modified Sommerfeld number per unit speed, eta R L^3 / (4 W c^2).
double sommerfeld_per_speed(const JournalBearing& b) {
    return b.viscosity * 0.5 * b.diameter * std::pow(b.length, 3) / (4.0 * b.load * b.clearance * b.clearance);
}

std::string grid_text(const ReynoldsFilm& f) {
    return fmt::format("finite-difference grid {} x {}", f.circumferential(), f.axial());
}

}  // namespace

ReynoldsFilm::ReynoldsFilm(double length_over_diameter, int circumferential, int axial)
    : ld_(length_over_diameter), n_(circumferential), m_(axial / 2) {
    if (!(std::isfinite(ld_) && ld_ > 0.0))
        throw InputError(fmt::format("Reynolds film: length / diameter = {}; allowed: a finite number > 0", ld_));
    if (circumferential < 16 || circumferential > 2880 || circumferential % 2 != 0)
        throw InputError(fmt::format(
            "Reynolds film: grid_circumferential = {}; allowed: an even number from 16 to 2880", circumferential));
    if (axial < 4 || axial > 256 || axial % 4 != 0)
        throw InputError(fmt::format("Reynolds film: grid_axial = {}; allowed: a multiple of 4 from 4 to 256", axial));
    // Second difference in zeta on j = 0..M-1 with P_{-1} = P_1 (symmetry) and P_M = 0:
    // eigenvectors cos(beta_k j), beta_k = (2k+1) pi / (2M), eigenvalues -4 M^2 sin^2(beta_k / 2).
    const int m = m_;
    const double dl2 = 1.0 / (ld_ * ld_);
    modes_.resize(m, m);
    eig_.resize(m);
    for (int k = 0; k < m; ++k) {
        const double beta = (2 * k + 1) * kPi / (2.0 * m);
        for (int j = 0; j < m; ++j) modes_(j, k) = std::cos(beta * j);
        const double s = std::sin(0.5 * beta);
        eig_(k) = -dl2 * 4.0 * m * m * s * s;
    }
    unit_ = modes_.partialPivLu().solve(Eigen::VectorXd::Ones(m));
    simpson_.resize(m);
    const double dz = 1.0 / m;
    for (int j = 0; j < m; ++j) simpson_(j) = (j == 0 ? 1.0 : (j % 2 == 1 ? 4.0 : 2.0)) * dz / 3.0;
}

Eigen::VectorXd ReynoldsFilm::theta(double theta0) const {
    Eigen::VectorXd t(n_);
    for (int i = 0; i < n_; ++i) t(i) = theta0 + 2.0 * kPi * i / n_;
    return t;
}

ReynoldsFilm::Operator ReynoldsFilm::factor(double X, double Y, double theta0) const {
    Operator op;
    op.film_ = this;
    op.X_ = X;
    op.Y_ = Y;
    op.theta0_ = theta0;
    const int n = n_, m = m_;
    const double dt = 2.0 * kPi / n;
    Eigen::VectorXd h3(n);
    op.h3_half_.resize(n);
    for (int i = 0; i < n; ++i) {
        const double t = theta0 + dt * i, th = t + 0.5 * dt;
        const double h = 1.0 - X * std::cos(t) - Y * std::sin(t), hh = 1.0 - X * std::cos(th) - Y * std::sin(th);
        if (!(h > 0.0 && hh > 0.0 && std::isfinite(h) && std::isfinite(hh)))
            throw SolverError(fmt::format("Reynolds film: the film thickness is not positive at theta = {} rad "
                                          "(journal at X = {}, Y = {} clearances); allowed: eccentricity below 1",
                                          t, X, Y));
        h3(i) = h * h * h;
        op.h3_half_(i) = hh * hh * hh;
    }
    // Row i of mode k (times dtheta^2): e_{i-1} P_{i-1} + d_i P_i + e_i P_{i+1} = dtheta^2 rhs_i with
    // e_i = H^3(theta_{i+1/2}), d_i = -(e_i + e_{i-1}) + dtheta^2 lambda_k H_i^3 and indices mod N:
    // symmetric and strictly diagonally dominant (lambda_k < 0), so Thomas needs no pivoting. The
    // corners e_{N-1} (periodicity) go into a rank-one correction A = B + u v^T, u = (gamma, 0, ..., 0,
    // e_{N-1}), v = (1, 0, ..., 0, e_{N-1} / gamma), gamma = -d_0 (B stays diagonally dominant).
    op.inv_pivot_.resize(m);
    op.upper_.resize(m);
    op.corr_.resize(m);
    op.corr_den_.resize(m);
    op.corner_over_gamma_.resize(m);
    const Eigen::VectorXd& e = op.h3_half_;
    const double corner = e(n - 1);
    Eigen::VectorXd d(n), u = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < m; ++k) {
        for (int i = 0; i < n; ++i) d(i) = -(e(i) + e((i + n - 1) % n)) + dt * dt * eig_(k) * h3(i);
        const double gamma = -d(0);
        d(0) -= gamma;
        d(n - 1) -= corner * corner / gamma;
        Eigen::VectorXd& ip = op.inv_pivot_[k];
        Eigen::VectorXd& up = op.upper_[k];
        ip.resize(n);
        up.resize(n);
        for (int i = 0; i < n; ++i) {
            const double w = i == 0 ? d(0) : d(i) - e(i - 1) * up(i - 1);
            if (!(std::fabs(w) > 0.0 && std::isfinite(w)))
                throw SolverError("Reynolds film: singular film operator (a zero pivot)");
            ip(i) = 1.0 / w;
            up(i) = i < n - 1 ? e(i) * ip(i) : 0.0;
        }
        u(0) = gamma;
        u(n - 1) = corner;
        op.corr_[k] = op.solve_tridiagonal(k, u);
        op.corner_over_gamma_[k] = corner / gamma;
        const double den = 1.0 + op.corr_[k](0) + op.corner_over_gamma_[k] * op.corr_[k](n - 1);
        if (!(std::fabs(den) > 1e-300 && std::isfinite(den)))
            throw SolverError("Reynolds film: singular film operator (its periodic correction)");
        op.corr_den_[k] = den;
    }
    return op;
}

Eigen::VectorXd ReynoldsFilm::Operator::solve_tridiagonal(int k, const Eigen::VectorXd& rhs) const {
    const int n = static_cast<int>(rhs.size());
    const Eigen::VectorXd& ip = inv_pivot_[k];
    const Eigen::VectorXd& up = upper_[k];
    const Eigen::VectorXd& e = h3_half_;
    Eigen::VectorXd y(n);
    y(0) = rhs(0) * ip(0);
    for (int i = 1; i < n; ++i) y(i) = (rhs(i) - e(i - 1) * y(i - 1)) * ip(i);
    for (int i = n - 2; i >= 0; --i) y(i) -= up(i) * y(i + 1);
    return y;
}

Eigen::MatrixXd ReynoldsFilm::Operator::solve(const Eigen::VectorXd& g) const {
    const ReynoldsFilm& f = *film_;
    const int n = f.n_, m = f.m_;
    if (g.size() != n) throw SolverError("Reynolds film: right-hand side of the wrong length");
    const double dt = 2.0 * kPi / n;
    const Eigen::VectorXd rhs = (12.0 * dt * dt) * g;
    // P_ij = sum_k cos(beta_k j) Q_ik, column k of Q: mode k of the constant 1 times the solve.
    Eigen::MatrixXd Q(n, m);
    for (int k = 0; k < m; ++k) {
        Eigen::VectorXd y = solve_tridiagonal(k, f.unit_(k) * rhs);
        const double t = (y(0) + corner_over_gamma_[k] * y(n - 1)) / corr_den_[k];
        Q.col(k) = y - t * corr_[k];
    }
    Eigen::MatrixXd P = Q * f.modes_.transpose();
    if (!P.allFinite()) throw SolverError("Reynolds film: the pressure is not finite");
    return P;
}

Eigen::MatrixXd ReynoldsFilm::Operator::pressure(double Xd, double Yd) const {
    const Eigen::VectorXd t = film_->theta(theta0_);
    Eigen::VectorXd g(t.size());
    for (int i = 0; i < t.size(); ++i) {
        const double c = std::cos(t(i)), s = std::sin(t(i));
        g(i) = 0.5 * (X_ * s - Y_ * c) - Xd * c - Yd * s;
    }
    return solve(g);
}

Eigen::Vector2d ReynoldsFilm::force(const Eigen::MatrixXd& P, double theta0) const {
    const int n = n_, m = m_;
    if (P.rows() != n || P.cols() != m || !P.allFinite())
        throw SolverError(fmt::format("Reynolds film: the pressure is not a finite {} x {} field", n, m));
    const double dt = 2.0 * kPi / n;
    const Eigen::VectorXd t = theta(theta0);
    Eigen::VectorXd c(n), s(n);
    for (int i = 0; i < n; ++i) c(i) = std::cos(t(i)), s(i) = std::sin(t(i));
    Eigen::Vector2d f = Eigen::Vector2d::Zero();
    for (int j = 0; j < m; ++j) {
        // Trapezoidal rule on max(P, 0) of the piecewise-linear P: a cell with a sign change
        // keeps its positive part up to the linear zero (weight 0 there).
        double fx = 0.0, fy = 0.0;
        for (int i = 0; i < n; ++i) {
            const int i1 = (i + 1) % n;
            const double a = P(i, j), b = P(i1, j);
            if (a >= 0.0 && b >= 0.0) {
                fx += a * c(i) + b * c(i1);
                fy += a * s(i) + b * s(i1);
            } else if (a > 0.0) {
                const double w = a / (a - b);
                fx += w * a * c(i);
                fy += w * a * s(i);
            } else if (b > 0.0) {
                const double w = b / (b - a);
                fx += w * b * c(i1);
                fy += w * b * s(i1);
            }
        }
        f(0) += simpson_(j) * 0.5 * dt * fx;
        f(1) += simpson_(j) * 0.5 * dt * fy;
    }
    return f;
}

namespace {

// Static film force at eccentricity e along theta = 0 (grid aligned with the line of centres).
Eigen::Vector2d static_force(const ReynoldsFilm& film, double e) {
    return film.force(film.factor(e, 0.0, 0.0).pressure(0.0, 0.0), 0.0);
}

// The dimensionless state at eccentricity e: the film aligned with the line of centres
// (theta0 = 0, journal at (e, 0)); rotating journal and grid together rotates the force,
// so this is the state at any angle, turned into the load's (u, v) axes.
JournalBearingState film_state(const ReynoldsFilm& film, double e) {
    JournalBearingState st;
    st.eccentricity = e;
    const ReynoldsFilm::Operator op = film.factor(e, 0.0, 0.0);
    const Eigen::VectorXd t = film.theta(0.0);
    const int n = static_cast<int>(t.size());
    Eigen::VectorXd gs(n), gx(n), gy(n);
    for (int i = 0; i < n; ++i) {
        gs(i) = 0.5 * e * std::sin(t(i));
        gx(i) = -std::cos(t(i));   // dg / dXd
        gy(i) = -std::sin(t(i));   // dg / dYd
    }
    const Eigen::MatrixXd Ps = op.solve(gs), Px = op.solve(gx), Py = op.solve(gy);
    const Eigen::Vector2d f0 = film.force(Ps, 0.0);
    const double fn = f0.norm();
    // The load W = -F is along f; the line of centres (theta = 0) leads it by the attitude angle.
    st.attitude_angle = -std::atan2(f0(1), f0(0));
    st.sommerfeld = film.length_over_diameter() * film.length_over_diameter() / fn;
    const double step = kRelativeStep * std::min(e, 1.0 - e);
    Eigen::Matrix2d D, Dv;   // df/dX, df/dXd in the frame of the line of centres
    for (int j = 0; j < 2; ++j) {
        const double ex = j == 0 ? step : 0.0, ey = j == 1 ? step : 0.0;
        const Eigen::Vector2d fp = film.force(film.factor(e + ex, ey, 0.0).pressure(0.0, 0.0), 0.0);
        const Eigen::Vector2d fm = film.force(film.factor(e - ex, -ey, 0.0).pressure(0.0, 0.0), 0.0);
        D.col(j) = (fp - fm) / (2.0 * step);
        const Eigen::MatrixXd& Pv = j == 0 ? Px : Py;
        Dv.col(j) = (film.force(Ps + step * Pv, 0.0) - film.force(Ps - step * Pv, 0.0)) / (2.0 * step);
    }
    // K = -dF/dx = (eta Omega R L (R/c)^2 / c) df/dX and W = eta Omega R L (R/c)^2 |f|: a = (df/dX) / |f|.
    // (u, v): the load along -v, the spin turning u into v; in the frame of the line of centres
    // e_u = (sin phi, cos phi), e_v = (-cos phi, sin phi).
    const double sp = std::sin(st.attitude_angle), cp = std::cos(st.attitude_angle);
    Eigen::Matrix2d Qm;
    Qm << sp, cp, -cp, sp;
    st.a = Qm * (D / fn) * Qm.transpose();
    st.b = Qm * (Dv / fn) * Qm.transpose();
    if (!(std::isfinite(st.sommerfeld) && std::isfinite(st.attitude_angle) && st.a.allFinite() && st.b.allFinite() &&
          fn > 0.0))
        throw SolverError(fmt::format("Reynolds film at eccentricity {}: a result is not finite", e));
    return st;
}

double logit(double e) { return std::log(e) - std::log1p(-e); }
double from_logit(double q) { return 1.0 / (1.0 + std::exp(-q)); }

// The eccentricity whose static force is |f| = target: log|f| increases monotonically with
// q = log(e / (1 - e)), with slope near 1 for e -> 0 (|f| ~ e) and near 2 for e -> 1, so secant
// steps in q converge from the short bearing's guess; a bracket, once found, keeps every step
// inside it (bisection otherwise). Converged when |log|f| - log target| <= 1e-12: the force
// balances the load to 1e-12 of W (the rounding of |f| is about 1e-14).
double equilibrium(const ReynoldsFilm& film, double target, double guess, const std::string& where) {
    const double qmin = logit(1e-300), qmax = logit(1.0 - 1e-9), log_target = std::log(target);
    const double target_sommerfeld = film.length_over_diameter() * film.length_over_diameter() / target;
    const auto G = [&](double q) { return std::log(static_force(film, from_logit(q)).norm()) - log_target; };
    double q = std::clamp(logit(guess), qmin, qmax), g = G(q);
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    double qp = std::nan(""), gp = std::nan("");
    for (int it = 0; it < 200; ++it) {
        if (!std::isfinite(g))
            throw SolverError(fmt::format("{}: the film force is not finite at eccentricity {}; use the short-bearing "
                                          "solution or a finer grid",
                                          where, from_logit(q)));
        if (std::fabs(g) <= 1e-12) return from_logit(q);
        (g < 0.0 ? lo : hi) = q;
        if (hi - lo <= 1e-15 * std::max(1.0, std::fabs(q))) break;
        double slope = std::isfinite(qp) ? (g - gp) / (q - qp) : 1.5;
        if (!(slope > 0.0 && std::isfinite(slope))) slope = 1.5;
        double qn = q - g / slope;
        if (std::isfinite(lo) && std::isfinite(hi)) {
            if (!(qn > lo && qn < hi)) qn = 0.5 * (lo + hi);
        } else {
            qn = std::clamp(qn, q - 8.0, q + 8.0);
        }
        qn = std::clamp(qn, qmin, qmax);
        if (qn == q) {
            if (q == qmax && g < 0.0)
                throw SolverError(fmt::format("{}: the film carries the load only beyond eccentricity 1 - 1e-9 "
                                              "(Sommerfeld number {:.3g} too small); use a higher speed or a lower "
                                              "load",
                                              where, target_sommerfeld));
            if (q == qmin && g > 0.0)
                throw SolverError(fmt::format("{}: the film carries the load only below eccentricity 1e-300 "
                                              "(Sommerfeld number {:.3g} too large); use a lower speed",
                                              where, target_sommerfeld));
            break;
        }
        qp = q, gp = g;
        q = qn;
        g = G(q);
    }
    if (std::fabs(g) <= 1e-9) return from_logit(q);
    throw SolverError(fmt::format("{}: the static equilibrium did not converge (force balance residual {:.3g} of the "
                                  "load at eccentricity {}); use a finer grid or the short-bearing solution",
                                  where, std::expm1(std::fabs(g)), from_logit(q)));
}

}  // namespace

JournalBearingState reynolds_film_state(double length_over_diameter, double eccentricity, int circumferential,
                                        int axial) {
    if (!(eccentricity > 0.0 && eccentricity < 1.0))
        throw InputError(fmt::format("Reynolds film: eccentricity = {}; allowed: 0 < e < 1", eccentricity));
    return film_state(ReynoldsFilm(length_over_diameter, circumferential, axial), eccentricity);
}

double reynolds_bearing_speed_at(const JournalBearing& b, double e) {
    if (!(e > 0.0 && e < 1.0))
        throw InputError(fmt::format("fluid-film bearing: eccentricity = {}; allowed: 0 < e < 1", e));
    const ReynoldsFilm film(b.length / b.diameter, b.grid_circumferential, b.grid_axial);
    const double s = film.length_over_diameter() * film.length_over_diameter() / static_force(film, e).norm();
    const double w = s / sommerfeld_per_speed(b);
    if (!(std::isfinite(w) && w > 0.0))
        throw SolverError(fmt::format("fluid-film bearing ({}): no finite speed gives eccentricity {}",
                                      grid_text(film), e));
    return w;
}

JournalBearingState reynolds_bearing(const JournalBearing& b, double w) {
    const ReynoldsFilm film(b.length / b.diameter, b.grid_circumferential, b.grid_axial);
    const std::string where = fmt::format("fluid-film bearing ({}) at {} rad/s", grid_text(film), w);
    const double S = sommerfeld_per_speed(b) * w;
    if (!(w > 0.0 && std::isfinite(w) && std::isfinite(S) && S > 0.0))
        throw SolverError(fmt::format("{}: Sommerfeld number {}; allowed: a speed > 0 (at standstill the film "
                                      "carries no load)",
                                      where, S));
    // Starting guess: the short bearing at this Sommerfeld number (it carries more at equal e).
    double guess = 0.5;
    try {
        guess = short_bearing(b, w).eccentricity;
    } catch (const Error&) {
    }
    guess = std::clamp(guess, 1e-300, 1.0 - 1e-9);
    const double ld = film.length_over_diameter();
    JournalBearingState st;
    try {
        st = film_state(film, equilibrium(film, ld * ld / S, guess, where));
    } catch (const SolverError& x) {
        const std::string what = x.what();
        if (what.rfind(where, 0) == 0) throw;
        throw SolverError(fmt::format("{}: {}; use a finer grid or the short-bearing solution", where, what));
    }
    const double e = st.eccentricity;
    st.sommerfeld = S;
    st.coefficients = journal_bearing_coefficients(b, w, st.a, st.b);
    if (!(st.coefficients.K.allFinite() && st.coefficients.C.allFinite()))
        throw SolverError(fmt::format("{}: the coefficients are not finite (eccentricity {}); use the short-bearing "
                                      "solution",
                                      where, e));
    return st;
}

}  // namespace gyrokit
