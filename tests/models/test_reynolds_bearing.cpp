// Finite-length fluid-film bearing (finite-difference Reynolds solution, Gümbel
// cavitation) against independent computations: the assembled five-point
// equations solved by sparse LU; a spectral solution (Fourier-Galerkin in
// theta, exact cosine modes in z) of the same continuous problem with its
// coefficients from the perturbation equations; the short-bearing closed forms
// as L/D -> 0 and the long-bearing (Sommerfeld, Gümbel) forces as L/D -> inf;
// the equilibrium and the (x, y) coefficients against central differences of
// the dimensional film force; failures; and the option in an fe_rotor scene.
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/journal_bearing.hpp>
#include <gyrokit/models/reynolds_bearing.hpp>

#include <catch2/catch.hpp>

#include "test_helpers.hpp"
#include <Eigen/Sparse>
#include <gsl/gsl_sf_zeta.h>

#include <array>
#include <cmath>
#include <complex>
#include <vector>

using namespace gyrokit;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Dimensionless state: Sommerfeld number, attitude angle, a and b in (u, v).
struct Dimless {
    double S = 0, phi = 0;
    Eigen::Matrix2d a, b;
};

Dimless of(const JournalBearingState& s) { return {s.sommerfeld, s.attitude_angle, s.a, s.b}; }

// Largest difference: relative in S, absolute in phi (rad), relative to the largest
// entry in a and in b.
double difference(const Dimless& x, const Dimless& ref) {
    return std::max({std::fabs(x.S / ref.S - 1.0), std::fabs(x.phi - ref.phi),
                     (x.a - ref.a).cwiseAbs().maxCoeff() / ref.a.cwiseAbs().maxCoeff(),
                     (x.b - ref.b).cwiseAbs().maxCoeff() / ref.b.cwiseAbs().maxCoeff()});
}

// Spectral solution of the same film (journal at X = e, Y = 0). The film thickness
// does not depend on z, so P = sum_m cos(k_m zeta) P_m(theta), k_m = (m + 1/2) pi,
// separates exactly, with 1 = sum_m c_m cos(k_m zeta) on [0, 1), c_m = 2 (-1)^m / k_m:
//   (H^3 P_m')' - (D/L)^2 k_m^2 H^3 P_m = 12 c_m g(theta).
// In theta a Fourier-Galerkin method on the modes |n| <= K: H^3 is a trigonometric
// polynomial of degree 3, so the Galerkin equations are exact products of Fourier
// series and converge exponentially (rate (1 - sqrt(1 - e^2)) / e per mode). P is odd
// about theta = 0: the static film is positive on (pi, 2 pi) and its force is
//   f = sum_m (int_0^1 cos(k_m zeta)) int_pi^2pi P_m (cos, sin) dtheta
// with exact Fourier integrals. The derivatives of the Gümbel force: where the
// boundary moves P = 0, so df = int_{P>0} dP, and dP solves the perturbation equation
//   (H^3 dP_m')' - (D/L)^2 k_m^2 H^3 dP_m = 12 c_m dg - (3 H^2 dH P_m')' + (D/L)^2 k_m^2 3 H^2 dH P_m
// (position: dH = -cos, -sin; dg = sin / 2, -cos / 2; velocity: dH = 0, dg = -cos, -sin).
// The m-series falls like (m + 1/2)^-4 (each mode tends to its short-bearing form): 40
// terms, and the tail A (m + 1/2)^-4 + B (m + 1/2)^-6 fitted to the last two, summed with
// Hurwitz's zeta. More Fourier modes and terms change the result by < 1e-11.
Dimless spectral(double ld, double e, int K = 64, int terms = 40) {
    using cd = std::complex<double>;
    using Poly = std::vector<cd>;   // Fourier coefficients -d..d of a trigonometric polynomial
    const auto mul = [](const Poly& a, const Poly& b) {
        const int na = static_cast<int>(a.size() - 1) / 2, nb = static_cast<int>(b.size() - 1) / 2;
        Poly c(2 * (na + nb) + 1, 0.0);
        for (int i = -na; i <= na; ++i)
            for (int j = -nb; j <= nb; ++j) c[i + j + na + nb] += a[i + na] * b[j + nb];
        return c;
    };
    const auto scaled = [](Poly p, cd s) {
        for (auto& v : p) v *= s;
        return p;
    };
    const cd I(0, 1);
    const Poly cosine{0.5, 0.0, 0.5}, sine{0.5 * I, 0.0, -0.5 * I};   // e^{-i}, 1, e^{i}
    const Poly H{-0.5 * e, 1.0, -0.5 * e}, H2 = mul(H, H), H3 = mul(H2, H);
    const Poly dHx = scaled(cosine, -1.0), dHy = scaled(sine, -1.0);
    const Poly Bx = scaled(mul(H2, dHx), 3.0), By = scaled(mul(H2, dHy), 3.0);
    const int n = 2 * K + 1;
    const auto op = [&](const Poly& a, double kap2) {   // (a P')' - kap2 a P on e^{i l theta}
        const int na = static_cast<int>(a.size() - 1) / 2;
        Eigen::MatrixXcd M = Eigen::MatrixXcd::Zero(n, n);
        for (int p = -K; p <= K; ++p)
            for (int l = -K; l <= K; ++l)
                if (std::abs(p - l) <= na) M(p + K, l + K) = (-double(p) * l - kap2) * a[p - l + na];
        return M;
    };
    const auto vec = [&](const Poly& a) {
        const int na = static_cast<int>(a.size() - 1) / 2;
        Eigen::VectorXcd v = Eigen::VectorXcd::Zero(n);
        for (int k = -na; k <= na; ++k) v(k + K) = a[k + na];
        return v;
    };
    // int_pi^2pi e^{i k theta} dtheta
    const auto J = [](int k) -> cd { return k == 0 ? cd(kPi) : (1.0 - std::pow(-1.0, k)) / cd(0, k); };
    const auto integrate = [&](const Eigen::VectorXcd& P) {
        cd fx = 0, fy = 0;
        for (int k = -K; k <= K; ++k) {
            fx += P(k + K) * 0.5 * (J(k + 1) + J(k - 1));
            fy += P(k + K) * (J(k + 1) - J(k - 1)) / (2.0 * I);
        }
        return Eigen::Vector2d(fx.real(), fy.real());
    };
    const Eigen::VectorXcd gs = vec(scaled(sine, 0.5 * e)), gx = vec(scaled(sine, 0.5)),
                           gy = vec(scaled(cosine, -0.5)), gxd = vec(dHx), gyd = vec(dHy);
    using Out = Eigen::Matrix<double, 10, 1>;   // f, df/dX, df/dY, df/dXd, df/dYd
    std::vector<Out> t;
    for (int m = 0; m < terms; ++m) {
        const double km = (m + 0.5) * kPi, sign = m % 2 == 0 ? 1.0 : -1.0, cm = 2.0 * sign / km, wm = sign / km;
        const double kap2 = km * km / (ld * ld);
        const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(op(H3, kap2));
        const Eigen::VectorXcd P = lu.solve(12.0 * cm * gs);
        Out o;
        o.segment<2>(0) = wm * integrate(P);
        o.segment<2>(2) = wm * integrate(lu.solve(12.0 * cm * gx - op(Bx, kap2) * P));
        o.segment<2>(4) = wm * integrate(lu.solve(12.0 * cm * gy - op(By, kap2) * P));
        o.segment<2>(6) = wm * integrate(lu.solve(12.0 * cm * gxd));
        o.segment<2>(8) = wm * integrate(lu.solve(12.0 * cm * gyd));
        t.push_back(o);
    }
    Out sum = Out::Zero();
    for (const Out& o : t) sum += o;
    const double x1 = terms - 1.5, x2 = terms - 0.5;
    Eigen::Matrix2d fit;
    fit << std::pow(x1, -4), std::pow(x1, -6), std::pow(x2, -4), std::pow(x2, -6);
    const auto lu = fit.partialPivLu();
    for (int q = 0; q < 10; ++q) {
        const Eigen::Vector2d ab = lu.solve(Eigen::Vector2d(t[terms - 2](q), t[terms - 1](q)));
        sum(q) += ab(0) * gsl_sf_hzeta(4, terms + 0.5) + ab(1) * gsl_sf_hzeta(6, terms + 0.5);
    }
    const Eigen::Vector2d f = sum.segment<2>(0);
    Eigen::Matrix2d D, Dv;
    D << sum(2), sum(4), sum(3), sum(5);
    Dv << sum(6), sum(8), sum(7), sum(9);
    Dimless r;
    const double fn = f.norm();
    r.phi = -std::atan2(f(1), f(0));
    r.S = ld * ld / fn;
    Eigen::Matrix2d Q;   // rows e_u, e_v in the frame of the line of centres
    Q << std::sin(r.phi), std::cos(r.phi), -std::cos(r.phi), std::sin(r.phi);
    r.a = Q * (D / fn) * Q.transpose();
    r.b = Q * (Dv / fn) * Q.transpose();
    return r;
}

Dimless short_limit(double e) {
    JournalBearing b;
    b.diameter = 0.1, b.length = 0.04, b.clearance = 1e-4, b.viscosity = 0.03, b.load = 5000;
    return of(short_bearing(b, journal_bearing_speed_at(b, e)));
}

double order(double coarse, double fine) { return std::log2(coarse / fine); }

// A bearing of diameter 0.1 m with L/D = ld and the speed at which the spectral
// solution has eccentricity e (its Sommerfeld number), on the grid N x A.
struct AtSpeed {
    JournalBearing b;
    double w = 0;
};
AtSpeed at_speed(double ld, const Dimless& exact, int N, int A) {
    AtSpeed r;
    r.b.diameter = 0.1, r.b.length = 0.1 * ld, r.b.clearance = 1e-4, r.b.viscosity = 0.03, r.b.load = 2000;
    r.b.solution = FilmSolution::finite_difference;
    r.b.grid_circumferential = N, r.b.grid_axial = A;
    r.w = exact.S / (r.b.viscosity * 0.05 * std::pow(r.b.length, 3) / (4 * r.b.load * r.b.clearance * r.b.clearance));
    return r;
}

// What an analysis sees at a given load and speed: the largest difference in e
// (relative), phi (rad), a and b (relative to their largest entry).
double difference_at_speed(const JournalBearingState& s, double e, const Dimless& ref) {
    return std::max({std::fabs(s.eccentricity / e - 1.0), std::fabs(s.attitude_angle - ref.phi),
                     (s.a - ref.a).cwiseAbs().maxCoeff() / ref.a.cwiseAbs().maxCoeff(),
                     (s.b - ref.b).cwiseAbs().maxCoeff() / ref.b.cwiseAbs().maxCoeff()});
}

}  // namespace

TEST_CASE("reynolds bearing: the separated solver solves the assembled five-point equations",
          "[journal_bearing][reynolds]") {
    // The full length -L/2..L/2 (no symmetry), an off-axis journal with velocity and a
    // rotated grid, assembled node by node and solved by sparse LU.
    const int N = 24, A = 8, M = A / 2;
    const double ld = 0.7, X = 0.3, Y = -0.45, Xd = 0.1, Yd = -0.05, t0 = 0.3;
    const ReynoldsFilm film(ld, N, A);
    const Eigen::MatrixXd P = film.factor(X, Y, t0).pressure(Xd, Yd);
    const double dt = 2 * kPi / N, dz = 1.0 / M, dl2 = 1.0 / (ld * ld);
    const auto H = [&](double t) { return 1.0 - X * std::cos(t) - Y * std::sin(t); };
    const int rows = 2 * M - 1;   // zeta_j = j dz, j = -M+1..M-1
    const auto id = [&](int i, int j) { return ((i + N) % N) * rows + (j + M - 1); };
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::VectorXd rhs(N * rows);
    for (int i = 0; i < N; ++i) {
        const double t = t0 + i * dt, hp = std::pow(H(t + dt / 2), 3), hm = std::pow(H(t - dt / 2), 3);
        const double h3 = std::pow(H(t), 3);
        const double g = 0.5 * (X * std::sin(t) - Y * std::cos(t)) - Xd * std::cos(t) - Yd * std::sin(t);
        for (int j = -M + 1; j <= M - 1; ++j) {
            const int r = id(i, j);
            trip.emplace_back(r, id(i + 1, j), hp / (dt * dt));
            trip.emplace_back(r, id(i - 1, j), hm / (dt * dt));
            trip.emplace_back(r, r, -(hp + hm) / (dt * dt) - 2 * dl2 * h3 / (dz * dz));
            if (j + 1 <= M - 1) trip.emplace_back(r, id(i, j + 1), dl2 * h3 / (dz * dz));
            if (j - 1 >= -M + 1) trip.emplace_back(r, id(i, j - 1), dl2 * h3 / (dz * dz));
            rhs(r) = 12 * g;
        }
    }
    Eigen::SparseMatrix<double> S(N * rows, N * rows);
    S.setFromTriplets(trip.begin(), trip.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(S);
    REQUIRE(lu.info() == Eigen::Success);
    const Eigen::VectorXd p = lu.solve(rhs);
    // Both are direct solves of one system with condition about (N / 2 pi)^2 (Hmax / Hmin)^3
    // < 1e4: rounding 1e-12 of the largest pressure.
    const double scale = p.cwiseAbs().maxCoeff();
    double worst = 0;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < M; ++j) {
            worst = std::max(worst, std::fabs(P(i, j) - p(id(i, j))));
            worst = std::max(worst, std::fabs(P(i, j) - p(id(i, -j))));   // even in zeta
        }
    CHECK(worst <= 1e-12 * scale);
    CHECK(scale > 0.1);
}

TEST_CASE("reynolds bearing: second-order grid convergence to an independent spectral solution",
          "[journal_bearing][reynolds]") {
    // Circumferential and axial intervals refined together (h = 2 pi / N, 2 / A): the
    // symmetric differences, the midpoint H^3 and Simpson's rule leave an error
    // C2 h^2 + C4 h^4, so the observed order between h and h/2 is 2 + O(h^2); with the
    // pressure peak's width (about sqrt(2 (1 - e)), > 0.6 rad at e <= 0.8) as the
    // scale of C4 / C2 the shift is below 0.02 on the two finest pairs: 2 +- 0.1.
    // The spectral reference is exact to < 1e-11 (see `spectral`), far below the
    // finest grid's error (> 1e-6).
    const std::vector<std::pair<int, int>> grids{{60, 8}, {120, 16}, {240, 32}, {480, 64}};
    for (const double ld : {0.5, 1.0}) {
        for (const double e : {0.2, 0.5, 0.8}) {
            CAPTURE(ld, e);
            const Dimless ref = spectral(ld, e);
            std::vector<double> err;
            std::vector<Dimless> fd;
            for (const auto& [N, A] : grids) {
                fd.push_back(of(reynolds_film_state(ld, e, N, A)));
                err.push_back(difference(fd.back(), ref));
            }
            // Error against the reference: order 2 on successive refinements.
            CHECK(order(err[1], err[2]) == Approx(2.0).margin(0.1));
            CHECK(order(err[2], err[3]) == Approx(2.0).margin(0.1));
            // Self-convergence without the reference: successive differences of S.
            CHECK(order(std::fabs(fd[1].S - fd[2].S), std::fabs(fd[2].S - fd[3].S)) == Approx(2.0).margin(0.1));
        }
    }
    // The spectral reference itself: more Fourier modes and z terms change nothing.
    const Dimless r1 = spectral(1.0, 0.8), r2 = spectral(1.0, 0.8, 96, 80);
    CHECK(difference(r1, r2) < 1e-11);
}

TEST_CASE("reynolds bearing: the default grid keeps e, attitude and coefficients within 1e-3",
          "[journal_bearing][reynolds]") {
    // The documented accuracy of the default grid (240 x 32) at a given load and speed,
    // for e <= 0.9 and L/D from 0.25 to 2, against the spectral solution.
    for (const double ld : {0.25, 1.0, 2.0}) {
        for (const double e : {0.2, 0.5, 0.9}) {
            CAPTURE(ld, e);
            const Dimless exact = spectral(ld, e);
            const AtSpeed x = at_speed(ld, exact, JournalBearing{}.grid_circumferential, JournalBearing{}.grid_axial);
            CHECK(difference_at_speed(reynolds_bearing(x.b, x.w), e, exact) < 1e-3);
        }
    }
}

TEST_CASE("reynolds bearing: the short-bearing limit, differences falling like (L/D)^2",
          "[journal_bearing][reynolds]") {
    // At fixed e, the finite bearing's S, phi, a, b differ from the closed forms by
    // d = A x^2 (1 + B x^2 + ...), x = L/D: the observed order between x and x/2 is
    // 2 + log2((1 + B x^2) / (1 + B x^2 / 4)) ~ 2 + 1.08 B x^2, whose deviation from 2
    // falls 4 times per halving of x once B x^2 is small (at least 2 times while the
    // next term still counts). The check: the order between 0.1 and 0.05 is within
    // max(0.05, half the deviation between 0.2 and 0.1) of 2. The 0.05 covers the grid:
    // 960 x 16 (the axial profile tends to the parabola that three-point differences and
    // Simpson's rule resolve exactly) leaves an error below 1 % of d at L/D = 0.05 (its
    // halving is checked below), which moves an order by < 0.03.
    const auto approaches_two = [](double p2, double p3) {
        CAPTURE(p2, p3);
        CHECK(std::fabs(p3 - 2.0) <= std::max(0.05, 0.5 * std::fabs(p2 - 2.0)));
        CHECK(p3 > 1.75);
        CHECK(p3 < 2.1);
    };
    const std::vector<double> lds{0.4, 0.2, 0.1, 0.05};
    for (const double e : {0.2, 0.5, 0.8}) {
        CAPTURE(e);
        const Dimless lim = short_limit(e);
        std::vector<std::array<double, 4>> d;
        for (const double ld : lds) {
            const Dimless x = of(reynolds_film_state(ld, e, 960, 16));
            d.push_back({std::fabs(x.S / lim.S - 1), std::fabs(x.phi - lim.phi),
                         (x.a - lim.a).cwiseAbs().maxCoeff() / lim.a.cwiseAbs().maxCoeff(),
                         (x.b - lim.b).cwiseAbs().maxCoeff() / lim.b.cwiseAbs().maxCoeff()});
        }
        const Dimless coarse = of(reynolds_film_state(0.05, e, 480, 16)),
                      fine = of(reynolds_film_state(0.05, e, 960, 16));
        for (int q = 0; q < 4; ++q) {
            CAPTURE(q);
            approaches_two(order(d[1][q], d[2][q]), order(d[2][q], d[3][q]));
            CHECK(d[3][q] < 0.02);
        }
        // Grid error at L/D = 0.05 (a halving of the circumferential step removes 3/4 of it).
        CHECK(difference(coarse, fine) / 3 < 0.01 * d[3][0]);
    }
    // At a fixed Sommerfeld number (the short bearing's at e0), the eccentricity and the
    // attitude of the finite bearing tend to the short bearing's in the same way (the
    // attitude's two x^2 parts, at fixed e and through the shift of e, partly cancel at
    // e0 = 0.8, so its order approaches 2 from further below: 1.4, 1.8, 1.9).
    for (const double e0 : {0.2, 0.5, 0.8}) {
        CAPTURE(e0);
        std::vector<double> de, dphi;
        for (const double ld : lds) {
            JournalBearing b;
            b.diameter = 0.1, b.length = 0.1 * ld, b.clearance = 1e-4, b.viscosity = 0.03, b.load = 5000;
            b.solution = FilmSolution::finite_difference;
            b.grid_circumferential = 960, b.grid_axial = 16;
            const double w = journal_bearing_speed_at(b, e0);
            const JournalBearingState fd = reynolds_bearing(b, w), sb = short_bearing(b, w);
            CHECK(fd.sommerfeld == sb.sommerfeld);
            CHECK(fd.eccentricity > e0);   // the finite bearing carries less at equal e
            de.push_back(fd.eccentricity - e0);
            dphi.push_back(std::fabs(fd.attitude_angle - sb.attitude_angle));
        }
        approaches_two(order(de[1], de[2]), order(de[2], de[3]));
        approaches_two(order(dphi[1], dphi[2]), order(dphi[2], dphi[3]));
    }
}

TEST_CASE("reynolds bearing: the long-bearing limit, the Sommerfeld forces with Gümbel's condition",
          "[journal_bearing][reynolds]") {
    // L/D -> inf: P -> the long-bearing pressure with p = 0 on the diverging half, whose
    // force is |f_r| = 12 e^2 / ((2 + e^2)(1 - e^2)) along the line of centres and
    // |f_t| = 6 pi e / ((2 + e^2) sqrt(1 - e^2)) across it (F = -eta Omega R L (R/c)^2 f).
    // The ends lose pressure over a length of order D: the difference falls like D/L,
    // d = A/x + B/x^2, whose observed order between 8 and 16 is 1 + O(1/x) (1.00 in the
    // spectral solution); with 256 axial intervals the grid error is below 0.5 % of d.
    for (const double e : {0.5, 0.8}) {
        CAPTURE(e);
        const Eigen::Vector2d lim(12 * e * e / ((2 + e * e) * (1 - e * e)),
                                  -6 * kPi * e / ((2 + e * e) * std::sqrt(1 - e * e)));
        std::vector<double> d;
        for (const double ld : {4.0, 8.0, 16.0}) {
            const ReynoldsFilm film(ld, 120, 256);
            const Eigen::Vector2d f = film.force(film.factor(e, 0, 0).pressure(0, 0), 0.0);
            d.push_back((f - lim).norm() / lim.norm());
        }
        CHECK(order(d[1], d[2]) == Approx(1.0).margin(0.05));
        CHECK(order(d[0], d[1]) == Approx(1.0).margin(0.1));
        CHECK(d[2] < 0.06);
    }
}

TEST_CASE("reynolds bearing: the equilibrium balances the load and the (x, y) coefficients are its film's",
          "[journal_bearing][reynolds]") {
    for (const double load_deg : {-90.0, 10.0}) {
        CAPTURE(load_deg);
        JournalBearing b;
        b.diameter = 0.06, b.length = 0.03, b.clearance = 60e-6, b.viscosity = 0.015, b.load = 998;
        b.load_angle = load_deg * kPi / 180;
        b.solution = FilmSolution::finite_difference;
        for (const double w : {30.0, 300.0, 3000.0}) {
            CAPTURE(w);
            const JournalBearingState s = reynolds_bearing(b, w);
            CHECK(s.sommerfeld == short_bearing(b, w).sommerfeld);
            CHECK(s.eccentricity > short_bearing(b, w).eccentricity);
            CHECK(reynolds_bearing_speed_at(b, s.eccentricity) == Approx(w).epsilon(1e-10));
            // The film force at the equilibrium, dimensional, with the grid along the line of
            // centres (which leads the load line by the attitude angle).
            const ReynoldsFilm film(b.length / b.diameter, b.grid_circumferential, b.grid_axial);
            const double R = b.diameter / 2, c = b.clearance, t0 = b.load_angle + s.attitude_angle;
            const double scale = b.viscosity * w * R * b.length * (R / c) * (R / c);
            const auto force = [&](double x, double y, double xd, double yd) -> Eigen::Vector2d {
                return -scale * film.force(film.factor(x / c, y / c, t0).pressure(xd / (c * w), yd / (c * w)), t0);
            };
            const double x0 = s.eccentricity * c * std::cos(t0), y0 = s.eccentricity * c * std::sin(t0);
            const Eigen::Vector2d F = force(x0, y0, 0, 0);
            const Eigen::Vector2d W(b.load * std::cos(b.load_angle), b.load * std::sin(b.load_angle));
            // The balance: |log|f| - log target| <= 1e-12; the direction is exact by construction.
            CHECK((F + W).norm() <= 1e-10 * b.load);
            // K = -dF/dx, C = -dF/dx' by central differences (steps 1e-5 c min(e, 1 - e) and that
            // times w: the differences' error is up to 2e-6 of the coefficients, the clipped
            // force's first-order term, 0.2 step / (c min(e, 1 - e))).
            const double dx = 1e-5 * c * std::min(s.eccentricity, 1 - s.eccentricity), dv = dx * w;
            Eigen::Matrix2d K, C;
            for (int j = 0; j < 2; ++j) {
                const double ex = j == 0, ey = j == 1;
                K.col(j) = -(force(x0 + dx * ex, y0 + dx * ey, 0, 0) - force(x0 - dx * ex, y0 - dx * ey, 0, 0)) /
                           (2 * dx);
                C.col(j) = -(force(x0, y0, dv * ex, dv * ey) - force(x0, y0, -dv * ex, -dv * ey)) / (2 * dv);
            }
            const double kscale = b.load / c, cscale = kscale / w;
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                    CAPTURE(i, j);
                    CHECK(s.coefficients.K(i, j) == Approx(K(i, j)).margin(1e-5 * kscale * s.a.cwiseAbs().maxCoeff()));
                    CHECK(s.coefficients.C(i, j) == Approx(C(i, j)).margin(1e-5 * cscale * s.b.cwiseAbs().maxCoeff()));
                }
        }
    }
}

TEST_CASE("reynolds bearing: failures throw SolverError naming the speed and what to change, never a NaN",
          "[journal_bearing][reynolds]") {
    JournalBearing b;
    b.diameter = 0.06, b.length = 0.03, b.clearance = 60e-6, b.viscosity = 0.015, b.load = 998;
    b.solution = FilmSolution::finite_difference;
    const auto message = [&](double w) -> std::string {
        try {
            reynolds_bearing(b, w);
        } catch (const SolverError& e) {
            return e.what();
        }
        return "no error";
    };
    const std::string standstill = message(0.0);
    CHECK(standstill.find("at 0 rad/s") != std::string::npos);
    CHECK(standstill.find("allowed: a speed > 0") != std::string::npos);
    CHECK(message(std::nan("")).find("at nan rad/s") != std::string::npos);
    // At 1e-4 rad/s the film would need e > 1 - 1e-9.
    const std::string slow = message(1e-4);
    CHECK(slow.find("beyond eccentricity 1 - 1e-9") != std::string::npos);
    CHECK(slow.find("use a higher speed or a lower load") != std::string::npos);
    // Through the bearing table: the bearing's name first; below the speed of
    // max_eccentricity the coefficients there hold (finite).
    const BearingTable t = journal_bearing_table(b, "fluid_film_3", 0, 1);
    REQUIRE(t.speeds.size() == 1);
    CHECK(reynolds_bearing(b, t.speeds[0]).eccentricity == Approx(0.95).epsilon(1e-10));
    CHECK(t.at(1e-6).K.allFinite());
    CHECK((t.at(1e-6).K - reynolds_bearing(b, t.speeds[0]).coefficients.K).norm() == 0.0);
    try {
        t.model(-1.0);
        FAIL("accepted");
    } catch (const SolverError& e) {
        CHECK(std::string(e.what()).rfind("bearing fluid_film_3: fluid-film bearing (finite-difference grid 240 x 32) "
                                          "at -1 rad/s",
                                          0) == 0);
    }
    // Bad data are refused by validate with the key, the value and the range.
    const auto refused = [&](JournalBearing x, const std::string& what) {
        CAPTURE(what);
        try {
            x.validate("bearing 1");
            FAIL("accepted");
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find(what) != std::string::npos);
        }
    };
    JournalBearing x = b;
    x.grid_circumferential = 15;
    refused(x, "bearing 1: grid_circumferential = 15; allowed: an even number from 16 to 2880");
    x = b;
    x.grid_axial = 30;
    refused(x, "bearing 1: grid_axial = 30; allowed: a multiple of 4 from 4 to 256");
    x = b;
    x.solution = static_cast<FilmSolution>(7);
    refused(x, "bearing 1: solution = 7; allowed: short, finite_difference");
    CHECK_THROWS_AS(ReynoldsFilm(0.5, 240, 2), InputError);
    CHECK_THROWS_AS(ReynoldsFilm(std::nan(""), 240, 32), InputError);
    CHECK_THROWS_AS(ReynoldsFilm(0.5, 240, 32).factor(1.0, 0.0, 0.0), SolverError);
}

namespace {

// The rotor of test_journal_bearing.cpp with the bearing lines given.
std::string fd_rotor(const std::string& bearing_extra) {
    const std::string b = "type = \"fluid_film\"\ndiameter = 0.05\nlength = 0.025\nclearance = 50e-6\n"
                          "viscosity = 0.02\nload = 200\n" + bearing_extra;
    return "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n"
           "[[model.shaft]]\nlength = 1.0\nelements = 10\nouter_diameter = 0.05\n"
           "[[model.disk]]\nz = 0.5\nmass = 25.0\nId = 0.1\nIp = 0.2\n"
           "[[model.bearing]]\nz = 0.0\n" + b + "[[model.bearing]]\nz = 1.0\n" + b;
}

}  // namespace

TEST_CASE("reynolds bearing in an fe_rotor scene: solution = finite_difference and its grid",
          "[journal_bearing][reynolds]") {
    JournalBearing b;
    b.diameter = 0.05, b.length = 0.025, b.clearance = 50e-6, b.viscosity = 0.02, b.load = 200;
    b.solution = FilmSolution::finite_difference;
    {
        const Scene sc = parse_scene(fd_rotor("solution = \"finite_difference\"\n"), "fd.toml");
        REQUIRE(sc.system.bearings.size() == 2);
        CHECK(sc.system.bearings[0].speeds[0] == reynolds_bearing_speed_at(b, 0.95));
        for (const double w : {50.0, 300.0, 3000.0}) {
            const BearingCoefficients want = reynolds_bearing(b, w).coefficients, got = sc.system.bearings[1].at(w);
            CHECK((got.K - want.K).norm() <= 1e-15 * want.K.norm());
            CHECK((got.C - want.C).norm() <= 1e-15 * want.C.norm());
            // Not the short bearing's.
            CHECK((got.K - short_bearing(b, w).coefficients.K).norm() > 1e-3 * want.K.norm());
        }
    }
    {
        const Scene sc = parse_scene(
            fd_rotor("solution = \"finite_difference\"\ngrid_circumferential = 120\ngrid_axial = 16\n"), "fd.toml");
        b.grid_circumferential = 120, b.grid_axial = 16;
        const BearingCoefficients want = reynolds_bearing(b, 300.0).coefficients, got = sc.system.bearings[0].at(300.0);
        CHECK((got.K - want.K).norm() <= 1e-15 * want.K.norm());
        CHECK((got.C - want.C).norm() <= 1e-15 * want.C.norm());
    }
    {
        // "short" is the default and gives the closed form.
        const Scene sc = parse_scene(fd_rotor("solution = \"short\"\n"), "short.toml");
        JournalBearing s = b;
        s.solution = FilmSolution::short_bearing;
        CHECK((sc.system.bearings[0].at(300.0).K - short_bearing(s, 300.0).coefficients.K).norm() == 0.0);
    }
    // Bad input: one line naming the key, the value and the range.
    const auto refused = [](const std::string& extra, const std::string& what) {
        CAPTURE(extra);
        const std::string m = test::scene_error(fd_rotor(extra));
        CHECK(m.find(what) != std::string::npos);
        CHECK(m.find('\n') == std::string::npos);
    };
    refused("solution = \"exact\"\n", "[model.bearing[0]] solution = 'exact': allowed: finite_difference, short");
    refused("solution = \"finite_difference\"\ngrid_circumferential = 8\n",
            "[model.bearing[0]] grid_circumferential = 8: out of range; allowed: [16, 2880]");
    refused("solution = \"finite_difference\"\ngrid_circumferential = 121\n",
            "[model.bearing[0]]: grid_circumferential = 121; allowed: an even number from 16 to 2880");
    refused("solution = \"finite_difference\"\ngrid_axial = 2\n",
            "[model.bearing[0]] grid_axial = 2: out of range; allowed: [4, 256]");
    refused("solution = \"finite_difference\"\ngrid_axial = 30\n",
            "[model.bearing[0]]: grid_axial = 30; allowed: a multiple of 4 from 4 to 256");
    refused("solution = \"finite_difference\"\ngrid_axial = 32.0\n",
            "[model.bearing[0]] grid_axial must be a whole number in [4, 256]");
    refused("grid_axial = 32\n", "[model.bearing[0]] grid_axial is given with solution = \"short\"");
}
