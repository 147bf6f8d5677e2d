// Mode shapes: orbits in closed form, eigenvectors against an independent
// eigensolver (MAC), the whirl of every orbit against the sign rule, and the
// pinned-pinned beam's shapes sin(k pi z / L).
#include "test_helpers.hpp"

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/mode_shapes.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/gyrostat.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

using namespace gyrokit;
using cd = std::complex<double>;

namespace {

const double pi = std::acos(-1.0);

// Eigenpairs of the first-order form [0 I; -M^-1 K, -M^-1 C] by Eigen's complex
// Schur solver: another algorithm than the library's scaled QZ on the pencil.
void state_eigenpairs(const QuadraticPencil& p, Eigen::VectorXcd& values, Eigen::MatrixXcd& vectors) {
    const int n = static_cast<int>(p.M.rows());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    const Eigen::MatrixXd Minv = p.M.inverse();
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -Minv * p.K;
    A.bottomRightCorner(n, n) = -Minv * p.C;
    Eigen::ComplexEigenSolver<Eigen::MatrixXcd> es(A.cast<cd>());
    values = es.eigenvalues();
    vectors = es.eigenvectors().topRows(n);
}

}  // namespace

TEST_CASE("orbits of simple motions in closed form", "[modes]") {
    const cd i(0.0, 1.0);
    // x = cos t, y = sin t: a forward unit circle.
    Orbit o = orbit_of(1.0, -i);
    CHECK(o.major == Approx(1.0).epsilon(1e-15));
    CHECK(o.minor == Approx(1.0).epsilon(1e-15));
    CHECK(o.whirl == Whirl::Forward);
    CHECK(orbit_of(1.0, i).whirl == Whirl::Backward);
    // A line at 45 degrees: planar, semi-axis sqrt(2).
    o = orbit_of(1.0, 1.0);
    CHECK(o.whirl == Whirl::Planar);
    CHECK(o.major == Approx(std::sqrt(2.0)).epsilon(1e-15));
    CHECK(o.minor == Approx(0.0).margin(1e-15));
    CHECK(o.angle == Approx(pi / 4).epsilon(1e-14));
    // The ellipse (2 cos t, sin t) turned by 30 degrees: semi-axes 2 and 1, forward.
    const double a = pi / 6;
    o = orbit_of(2 * std::cos(a) + i * std::sin(a), 2 * std::sin(a) - i * std::cos(a));
    CHECK(o.major == Approx(2.0).epsilon(1e-14));
    CHECK(o.minor == Approx(1.0).epsilon(1e-14));
    CHECK(o.angle == Approx(a).epsilon(1e-13));
    CHECK(o.whirl == Whirl::Forward);
    // Backward, turned by -60 degrees.
    o = orbit_of(std::polar(1.0, 0.3) * (2 * std::cos(-2 * a) + i * std::sin(-2 * a)),
                 std::polar(1.0, 0.3) * (2 * std::sin(-2 * a) - i * std::cos(-2 * a)));
    CHECK(o.major == Approx(2.0).epsilon(1e-14));
    CHECK(o.angle == Approx(-2 * a).margin(1e-13));
    CHECK(orbit_of(0.0, 0.0).whirl == Whirl::None);
    // The ellipse traced, sampled: no point farther than the major semi-axis, one on it.
    const cd u = 0.3 + 1.1 * i, v = -0.7 + 0.2 * i;
    o = orbit_of(u, v);
    double far = 0.0, near = 1e300;
    for (int k = 0; k < 100000; ++k) {
        const cd e = std::polar(1.0, 2 * pi * k / 100000);
        const double r = std::hypot((u * e).real(), (v * e).real());
        far = std::max(far, r);
        near = std::min(near, r);
    }
    CHECK(far == Approx(o.major).epsilon(1e-8));
    CHECK(near == Approx(o.minor).epsilon(1e-8));
}

TEST_CASE("gyrostat mode shapes match an independent eigensolver (MAC >= 0.9999) and the whirl sign rule",
          "[modes]") {
    // The centrifuge and an anisotropic cage (elliptic orbits), at standstill and spinning.
    GyrostatParameters iso = test::centrifuge(), aniso = test::centrifuge();
    aniso.B_G = 3.5;
    aniso.c_G = 500.0;
    for (const auto& p : {iso, aniso})
        for (const double w : {5.0, 100.0, 400.0}) {
            const GyroscopicSystem sys = make_system(p);
            const std::vector<ModeShape> shapes = mode_shapes(sys, w);
            REQUIRE(shapes.size() == 6);
            Eigen::VectorXcd values;
            Eigen::MatrixXcd vectors;
            state_eigenpairs(sys.at_speed(w), values, vectors);
            for (const auto& s : shapes) {
                Eigen::Index best = 0;
                (values.array() - s.mode.lambda).abs().minCoeff(&best);
                CHECK(std::abs(values(best) - s.mode.lambda) <= 1e-8 * std::abs(s.mode.lambda));
                CHECK(mac(s.shape, vectors.col(best)) >= 0.9999);
                CHECK(std::abs(s.shape(s.reference) - 1.0) <= 1e-14);
                CHECK(sys.dofs.units[static_cast<size_t>(s.reference)] == "m");
                // Each orbit's whirl from the independent vector: Im(x_u conj(x_v)) > 0 is forward.
                for (const auto& o : s.orbits) {
                    const cd xu = vectors(o.u, best), xv = vectors(o.v, best);
                    const double turn = std::imag(xu * std::conj(xv)) / (std::norm(xu) + std::norm(xv));
                    if (std::abs(turn) > 1e-6) CHECK(o.orbit.whirl == (turn > 0 ? Whirl::Forward : Whirl::Backward));
                    const double scale = std::abs(vectors(s.reference, best));
                    CHECK(o.orbit.major * scale ==
                          Approx(orbit_of(xu, xv).major).epsilon(1e-6).margin(1e-9 * scale));
                }
            }
        }
}

TEST_CASE("pinned-pinned beam: shapes along the axis are sin(k pi z / L), circular orbits", "[modes]") {
    const double L = 1.0, E = 2.11e11, nu = 0.3, rho = 7810.0;
    const int count = 20;
    FeRotor r = fe_uniform_shaft(L, count, 0.05, 0.0, E, nu, rho);
    r.supports.push_back({0, true, true, false, false});
    r.supports.push_back({count, true, true, false, false});
    r.shear_deformation = false;
    r.rotary_inertia = false;
    const GyroscopicSystem sys = make_system(r);
    SolverOptions so;
    so.modes = 6;
    const std::vector<ModeShape> shapes = mode_shapes(sys, 0.0, so);
    REQUIRE(shapes.size() == 6);
    for (int k = 1; k <= 3; ++k)
        for (int twin = 0; twin < 2; ++twin) {   // each bending mode is double at standstill: x and y planes
            const ModeShape& s = shapes[static_cast<size_t>(2 * (k - 1) + twin)];
            // Nodes 1 .. count - 1: the pinned ends have no free (x, y) pair. A circular
            // orbit has |u| = |v| at every node, so each plane alone carries the shape:
            // both are checked (choosing the larger per node would let rounding decide).
            Eigen::VectorXcd along_u(count - 1), along_v(count - 1), exact(count - 1);
            int i = 0;
            for (const auto& o : s.orbits) {
                if (o.unit != "m") continue;
                REQUIRE(o.node == i + 1);
                CHECK(o.z == Approx(L * (i + 1) / count).epsilon(1e-14));
                along_u(i) = s.shape(o.u);
                along_v(i) = s.shape(o.v);
                exact(i) = std::sin(k * pi * o.z / L);
                // Circular (the double eigenvalue's plane turned into the whirl extremes).
                if (o.orbit.major > 1e-6) CHECK(o.orbit.minor == Approx(o.orbit.major).epsilon(1e-6));
                ++i;
            }
            REQUIRE(i == count - 1);
            CHECK(mac(along_u, exact) >= 0.99999);
            CHECK(mac(along_v, exact) >= 0.99999);
            CHECK(s.shape.cwiseAbs().maxCoeff() >= 1.0);
        }
}

TEST_CASE("a pure tilt mode (s = 0: translation and tilt uncoupled) is scaled by its tilt, not by rounding in x",
          "[modes]") {
    GyrostatParameters p = test::centrifuge();
    p.s = 0.0;
    const GyroscopicSystem sys = make_system(p);
    int tilt_modes = 0;
    for (const ModeShape& m : mode_shapes(sys, 50.0)) {
        CHECK(m.shape.allFinite());
        CHECK(m.shape.cwiseAbs().maxCoeff() <= 1e3);
        const double x = std::max(std::abs(m.mode.right(2)), std::abs(m.mode.right(3)));
        if (x < 1e-10 * m.mode.right.cwiseAbs().maxCoeff()) {
            ++tilt_modes;
            CHECK(sys.dofs.units[static_cast<size_t>(m.reference)] == "rad");
            CHECK(m.shape.cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-14));
        }
    }
    CHECK(tilt_modes >= 2);
}

TEST_CASE("mode shapes of a model without units or nodes: every DOF counts, no axis", "[modes]") {
    GyroscopicSystem sys = make_system(test::centrifuge());
    sys.dofs.units.clear();
    sys.dofs.nodes.clear();
    const ModeShape s = mode_shapes(sys, 50.0).front();
    // The reference is the first entry tied (to kTieTolerance) with the largest: a rule, not rounding.
    const double top = s.shape.cwiseAbs().maxCoeff();
    Eigen::Index first = 0;
    while (std::abs(s.shape(first)) < (1.0 - kTieTolerance) * top) ++first;
    CHECK(first == s.reference);
    CHECK(std::abs(s.shape(s.reference)) == Approx(1.0).epsilon(1e-15));
    for (const auto& o : s.orbits) CHECK(o.node == -1);
    CHECK_THROWS_AS(mode_shapes(sys, -1.0), InputError);
    // Units and nodes of a wrong length are refused by validate.
    sys.dofs.units = {"m"};
    CHECK_THROWS_AS(sys.validate("test"), InputError);
}
