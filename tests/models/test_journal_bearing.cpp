// Fluid-film journal bearing (short bearing, Gümbel cavitation) against an
// independent computation: the film force integrated from the short-bearing
// pressure at a chosen journal position and velocity (the cavitated half found
// exactly, the rest by adaptive quadrature), its load, eccentricity and attitude,
// and its 8 coefficients by central differences; and the oil-whip threshold of
// a point mass on the bearing against the exact 2-DOF stability boundary.
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/journal_bearing.hpp>

#include <catch2/catch.hpp>

#include "test_helpers.hpp"
#include <gsl/gsl_integration.h>

#include <cmath>
#include <fstream>

using namespace gyrokit;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Film {
    double R = 0.025, L = 0.02, c = 60e-6, eta = 0.025, Omega = 500.0;
};

// Force of the film on the journal at centre (X, Y), velocity (Xd, Yd).
// Short-bearing Reynolds equation d/dz (h^3/(12 eta) dp/dz) = G(theta),
// G = (Omega/2) dh/dtheta + dh/dt, h = c - X cos - Y sin, p(+-L/2) = 0:
// p = 6 eta G (z^2 - L^2/4) / h^3, so int p dz = -eta L^3 G / h^3, positive
// where G < 0; G = A sin(theta) + B cos(theta) is negative on one half turn
// (Gümbel: the other half cavitates, p = 0). F = -R int p (cos, sin) dtheta.
Eigen::Vector2d film_force(const Film& f, double X, double Y, double Xd, double Yd) {
    const double A = 0.5 * f.Omega * X - Yd, B = -0.5 * f.Omega * Y - Xd;
    // G = rho sin(theta + psi) < 0 for theta + psi in (pi, 2 pi).
    const double psi = std::atan2(B, A), from = kPi - psi, to = 2 * kPi - psi;
    struct P {
        const Film* f;
        double X, Y, A, B;
        int axis;
    } p{&f, X, Y, A, B, 0};
    gsl_function F;
    F.function = [](double t, void* v) {
        const P& q = *static_cast<P*>(v);
        const double h = q.f->c - q.X * std::cos(t) - q.Y * std::sin(t);
        const double G = q.A * std::sin(t) + q.B * std::cos(t);
        const double pz = -q.f->eta * std::pow(q.f->L, 3) * G / (h * h * h);
        return -q.f->R * pz * (q.axis == 0 ? std::cos(t) : std::sin(t));
    };
    F.params = &p;
    gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
    Eigen::Vector2d out;
    for (int axis = 0; axis < 2; ++axis) {
        p.axis = axis;
        double result = 0, err = 0;
        gsl_integration_qag(&F, from, to, 0.0, 1e-13, 1000, GSL_INTEG_GAUSS61, w, &result, &err);
        out(axis) = result;
    }
    gsl_integration_workspace_free(w);
    return out;
}

}  // namespace

TEST_CASE("journal bearing: load, eccentricity, attitude and 8 coefficients against the integrated film",
          "[journal_bearing]") {
    const Film f;
    for (const double eps : {0.1, 0.3, 0.5, 0.7, 0.85}) {
        for (const double at_deg : {-90.0, 10.0}) {   // direction of the line of centres, from +x
            CAPTURE(eps, at_deg);
            const double at = at_deg * kPi / 180.0, X = eps * f.c * std::cos(at), Y = eps * f.c * std::sin(at);
            const Eigen::Vector2d F0 = film_force(f, X, Y, 0, 0);
            // The load that this position carries: W = -F.
            JournalBearing b;
            b.diameter = 2 * f.R;
            b.length = f.L;
            b.clearance = f.c;
            b.viscosity = f.eta;
            b.load = F0.norm();
            b.load_angle = std::atan2(-F0(1), -F0(0));
            const JournalBearingState s = short_bearing(b, f.Omega);
            CHECK(s.eccentricity == Approx(eps).epsilon(1e-10));
            // The line of centres leads the load line by the attitude angle, with the spin.
            CHECK(std::remainder(at - b.load_angle, 2 * kPi) == Approx(s.attitude_angle).epsilon(1e-10));
            // Coefficients by central differences: force = -K (x, y) - C (x', y').
            Eigen::Matrix2d K, C;
            const double dx = 1e-5 * f.c, dv = 1e-5 * f.c * f.Omega;
            for (int j = 0; j < 2; ++j) {
                const double ex = j == 0, ey = j == 1;
                K.col(j) = -(film_force(f, X + dx * ex, Y + dx * ey, 0, 0) - film_force(f, X - dx * ex, Y - dx * ey, 0, 0)) /
                           (2 * dx);
                C.col(j) = -(film_force(f, X, Y, dv * ex, dv * ey) - film_force(f, X, Y, -dv * ex, -dv * ey)) / (2 * dv);
            }
            // Central differences: error (dx/c)^2 / (1 - eps)^2 relative; quadrature 1e-13.
            const double kscale = b.load / b.clearance, cscale = kscale / f.Omega;
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                    CAPTURE(i, j);
                    CHECK(s.coefficients.K(i, j) == Approx(K(i, j)).margin(1e-6 * kscale));
                    CHECK(s.coefficients.C(i, j) == Approx(C(i, j)).margin(1e-6 * cscale));
                }
        }
    }
}

// Friswell, Penny, Garvey, Lees, "Dynamics of Rotating Machines" (2010), Example 5.5.1: a
// short bearing of D = 100 mm, L = 30 mm, c = 0.1 mm, eta = 0.1 Pa s at 1500 rev/min
// (157.1 rad/s) carrying 525 N. The book prints e = 0.2663 and the coefficients to four
// significant digits (x horizontal, y vertical, the load along -y), computed with e as
// printed: the tolerance is 1e-3 relative (half a unit of the fourth digit, 5e-4 of 1.0,
// plus the coefficients' sensitivity to e rounded to 4 digits, |dk/de| e / k < 2 here,
// times 2e-4).
TEST_CASE("journal bearing: Friswell et al. Example 5.5.1, eccentricity and 8 coefficients as printed",
          "[journal_bearing][validation]") {
    JournalBearing b;
    b.diameter = 0.1;
    b.length = 0.03;
    b.clearance = 0.1e-3;
    b.viscosity = 0.1;
    b.load = 525.0;
    const JournalBearingState s = short_bearing(b, 157.1);
    CHECK(s.eccentricity == Approx(0.2663).epsilon(2e-4));
    const Eigen::Matrix2d K = s.coefficients.K / 1e6, C = s.coefficients.C / 1e3;   // MN/m, kN s/m
    const double k_book[2][2] = {{12.81, 16.39}, {-25.06, 8.815}}, c_book[2][2] = {{232.9, -81.92}, {-81.92, 294.9}};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            INFO("entry " << i << j << " K " << K(i, j) << " C " << C(i, j));
            CHECK(K(i, j) == Approx(k_book[i][j]).epsilon(1e-3));
            CHECK(C(i, j) == Approx(c_book[i][j]).epsilon(1e-3));
        }
}

TEST_CASE("journal bearing: the Sommerfeld number falls from infinity to 0 and the speed inverts it",
          "[journal_bearing]") {
    // Short bearing: S_s = (1 - e^2)^2 / (e sqrt(16 e^2 + pi^2 (1 - e^2))); e -> 0: S_s ~ 1 / (pi e).
    CHECK(short_bearing_sommerfeld(1e-6) * kPi * 1e-6 == Approx(1.0).epsilon(1e-9));
    CHECK(short_bearing_sommerfeld(0.5) == Approx(0.5625 / (0.5 * std::sqrt(4.0 + kPi * kPi * 0.75))).epsilon(1e-15));
    JournalBearing b;
    b.diameter = 0.1, b.length = 0.04, b.clearance = 1e-4, b.viscosity = 0.03, b.load = 5000;
    double last = 1.0;
    for (double w = 1.0; w < 1e5; w *= 3.7) {
        const double e = short_bearing(b, w).eccentricity;
        CHECK(e < last);   // faster: a thicker film
        last = e;
        CHECK(journal_bearing_speed_at(b, e) == Approx(w).epsilon(1e-9));
    }
}

TEST_CASE("journal bearing: oil whip of a point mass at the exact 2-DOF stability boundary", "[journal_bearing]") {
    // m x'' + C(W) x' + K(W) x = 0 has the eigenvalue i nu at its threshold, which gives
    // K_eq = (kxx cyy + kyy cxx - kxy cyx - kyx cxy) / (cxx + cyy) = m nu^2 and
    // nu^2 = ((K_eq - kxx)(K_eq - kyy) - kxy kyx) / (cxx cyy - cxy cyx): one equation in W.
    JournalBearing b;
    b.diameter = 0.05, b.length = 0.025, b.clearance = 50e-6, b.viscosity = 0.02, b.load = 400;
    const double m = b.load / 9.81;
    const auto boundary = [&](double w) {
        const BearingCoefficients c = short_bearing(b, w).coefficients;
        const auto& k = c.K;
        const auto& d = c.C;
        const double keq = (k(0, 0) * d(1, 1) + k(1, 1) * d(0, 0) - k(0, 1) * d(1, 0) - k(1, 0) * d(0, 1)) /
                           (d(0, 0) + d(1, 1));
        const double nu2 = ((keq - k(0, 0)) * (keq - k(1, 1)) - k(0, 1) * k(1, 0)) /
                           (d(0, 0) * d(1, 1) - d(0, 1) * d(1, 0));
        return m * nu2 - keq;
    };
    GyroscopicSystem s;
    s.M = m * Eigen::Matrix2d::Identity();
    s.K = Eigen::Matrix2d::Zero();
    s.dofs.names = {"x", "y"};
    s.whirl_pairs = {{0, 1}};
    s.bearings.push_back(journal_bearing_table(b, "journal", 0, 1));
    const auto max_re = [&](double w) {
        double r = -1e300;
        for (const auto& mode : solve_at_speed(s, w).modes) r = std::max(r, mode.lambda.real());
        return r;
    };
    // Stable at low speed (a heavily loaded film), unstable at high speed.
    REQUIRE(max_re(20.0) < 0);
    REQUIRE(max_re(5000.0) > 0);
    const double lo = 20.0, hi = 5000.0;
    REQUIRE(boundary(lo) * boundary(hi) < 0);
    const double exact = find_root(boundary, lo, hi, 1e-14);
    const double found = find_root(max_re, lo, hi, 1e-12);
    CHECK(found == Approx(exact).epsilon(1e-8));
    // Whirl at the threshold near half the speed (oil whirl), between 0.34 and 0.52 for e < 0.75.
    double nu = 0;
    for (const auto& mode : solve_at_speed(s, exact).modes) nu = std::max(nu, mode.lambda.imag());
    CHECK(nu / exact > 0.3);
    CHECK(nu / exact < 0.55);
}

TEST_CASE("journal bearing: critical mass parameter m c W^2 / W of a rigid rotor on short bearings",
          "[journal_bearing]") {
    // Reference values from an independent 30-digit computation (the film force integrated
    // by tanh-sinh quadrature, coefficients by finite differences, the threshold from the
    // 4x4 eigenvalues): M_crit = K_eq / gamma^2 in units of W / c, gamma = whirl ratio.
    // e -> 0: 24 / pi; gamma^2 = 0 at e = 0.756030386471 (stable for any mass above it).
    const auto critical_mass = [](double e) {
        JournalBearing b;
        b.diameter = 0.1, b.length = 0.04, b.clearance = 1e-4, b.viscosity = 0.03, b.load = 5000;
        const JournalBearingState s = short_bearing(b, journal_bearing_speed_at(b, e));
        const auto& a = s.a;
        const auto& d = s.b;
        const double keq = (a(0, 0) * d(1, 1) + a(1, 1) * d(0, 0) - a(0, 1) * d(1, 0) - a(1, 0) * d(0, 1)) /
                           (d(0, 0) + d(1, 1));
        const double g2 = ((keq - a(0, 0)) * (keq - a(1, 1)) - a(0, 1) * a(1, 0)) / (d(0, 0) * d(1, 1) - d(0, 1) * d(1, 0));
        return std::pair{keq / g2, g2};
    };
    const std::vector<std::pair<double, double>> reference{
        {0.05, 7.60738845417}, {0.1, 7.51460856079}, {0.3, 6.79011978092},
        {0.5, 6.46039575233},  {0.7, 13.1610970081}, {0.75, 94.9481224636}};
    for (const auto& [e, m] : reference) {
        CAPTURE(e);
        CHECK(critical_mass(e).first == Approx(m).epsilon(1e-9));
    }
    CHECK(critical_mass(1e-4).first == Approx(24 / kPi).epsilon(1e-6));
    const double et = find_root([&](double e) { return critical_mass(e).second; }, 0.7, 0.8, 1e-14);
    CHECK(et == Approx(0.756030386471).epsilon(1e-10));
}

TEST_CASE("journal bearing: bad input is refused with the key, value and range", "[journal_bearing]") {
    JournalBearing b;
    b.diameter = 0.05, b.length = 0.025, b.clearance = 50e-6, b.viscosity = 0.02, b.load = 400;
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
    x.clearance = -1e-6;
    refused(x, "clearance = -1e-06");
    x = b;
    x.clearance = 0.03;
    refused(x, "clearance < diameter / 2");
    x = b;
    x.max_eccentricity = 1.0;
    refused(x, "max_eccentricity = 1");
    x = b;
    x.viscosity = 0;
    refused(x, "viscosity = 0");
    x = b;
    x.load = std::nan("");
    refused(x, "load = nan");
}

namespace {

// A steel shaft on two fluid-film bearings (the load of each: half the weight).
std::string film_rotor(const std::string& bearing_extra = "") {
    const std::string b = "type = \"fluid_film\"\ndiameter = 0.05\nlength = 0.025\nclearance = 50e-6\n"
                          "viscosity = 0.02\nload = 200\n" + bearing_extra;
    return "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n"
           "[[model.shaft]]\nlength = 1.0\nelements = 10\nouter_diameter = 0.05\n"
           "[[model.disk]]\nz = 0.5\nmass = 25.0\nId = 0.1\nIp = 0.2\n"
           "[[model.bearing]]\nz = 0.0\n" + b + "[[model.bearing]]\nz = 1.0\n" + b;
}

}  // namespace

TEST_CASE("journal bearing in an fe_rotor scene: the bearings' coefficients at every speed", "[journal_bearing]") {
    const Scene sc = parse_scene(film_rotor(), "film.toml");
    REQUIRE(sc.system.bearings.size() == 2);
    JournalBearing b;
    b.diameter = 0.05, b.length = 0.025, b.clearance = 50e-6, b.viscosity = 0.02, b.load = 200;
    for (const double w : {10.0, 300.0, 3000.0}) {
        const BearingCoefficients want = short_bearing(b, w).coefficients, got = sc.system.bearings[0].at(w);
        CHECK((got.K - want.K).norm() <= 1e-15 * want.K.norm());
        CHECK((got.C - want.C).norm() <= 1e-15 * want.C.norm());
    }
    // Below the speed of e = 0.95 the coefficients there hold, and the notes say so.
    const double w95 = journal_bearing_speed_at(b, 0.95);
    CHECK(short_bearing(b, w95).eccentricity == Approx(0.95).epsilon(1e-12));
    CHECK((sc.system.bearings[0].at(0.0).K - short_bearing(b, w95).coefficients.K).norm() == 0.0);
    const auto notes = extrapolation_notes(sc.system.bearings, 0.0, 100.0);
    REQUIRE(notes.size() == 2);
    CHECK(notes[0].find("below") != std::string::npos);
    CHECK(extrapolation_notes(sc.system.bearings, w95, 100.0).empty());
    // Two at one node: distinct names (each one's damping is a component of its own).
    std::string two = film_rotor();
    two.replace(two.find("z = 1.0\ntype"), 7, "z = 0.0");
    const Scene both = parse_scene(two, "two.toml");
    REQUIRE(both.system.bearings.size() == 2);
    CHECK(both.system.bearings[0].name == "fluid_film_0");
    CHECK(both.system.bearings[1].name == "fluid_film_0_2");
}

TEST_CASE("journal bearing in a scene: bad input names the key, value and range", "[journal_bearing]") {
    const auto message = test::scene_error;
    std::string neg = film_rotor();
    neg.replace(neg.find("clearance = 50e-6"), 17, "clearance = -5e-6");
    CHECK(message(neg).find("[model.bearing[0]] clearance = -5e-06: out of range; allowed: > 0 (m)") !=
          std::string::npos);
    std::string wide = film_rotor();
    wide.replace(wide.find("clearance = 50e-6"), 17, "clearance = 0.03");
    CHECK(message(wide).find("clearance = 0.03 m with diameter = 0.05 m; allowed: 0 < clearance < diameter / 2") !=
          std::string::npos);
    CHECK(message(film_rotor("max_eccentricity = 1.0\n")).find("max_eccentricity = 1") != std::string::npos);
    CHECK(message(film_rotor("k = 1e6\n")).find("unknown key 'k'") != std::string::npos);
    CHECK(message(film_rotor("load_angle = 1e308\n")).find("load_angle = 1e+308; allowed: -360 to 360 (deg)") !=
          std::string::npos);
    CHECK(message(film_rotor("max_eccentricity = 0.9999999\n")).find("allowed: 0.01 to 0.999") != std::string::npos);
    std::string thin = film_rotor();
    thin.replace(thin.find("viscosity = 0.02"), 16, "viscosity = 1e-300");
    CHECK(message(thin).find("give no usable film") != std::string::npos);
    CHECK(message(film_rotor().replace(film_rotor().find("load = 200"), 10, "load = 0")).find("load = 0") !=
          std::string::npos);
    CHECK(message(film_rotor().replace(film_rotor().find("\"fluid_film\""), 12, "\"magnetic\"")).find(
              "type = 'magnetic': allowed: fluid_film, linear") != std::string::npos);
    // A scene in mm: the message speaks the scene's unit.
    const std::string mm = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\nlength_unit = \"mm\"\n"
                           "[[model.shaft]]\nlength = 500\nelements = 2\nouter_diameter = 50\n"
                           "[[model.bearing]]\nz = 0\ntype = \"fluid_film\"\ndiameter = 50\nlength = 20\n"
                           "viscosity = 0.02\nload = 200\nclearance = ";
    CHECK(message(mm + "30\n").find("clearance = 30 mm with diameter = 50 mm; allowed: 0 < clearance < diameter / 2") !=
          std::string::npos);
    CHECK(message(mm + "0.05\n") == "no error");
    std::string thin_mm = mm + "0.05\n";
    thin_mm.replace(thin_mm.find("viscosity = 0.02"), 16, "viscosity = 1e-300");
    CHECK(message(thin_mm).find("diameter = 50 mm, length = 20 mm, clearance = 0.05 mm") != std::string::npos);
}
