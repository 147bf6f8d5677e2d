// Proportional shaft damping: on a shaft alone every mode has zeta = alpha / (2 w) + beta w / 2.
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/io/scene.hpp>
#include <gyrokit/io/scene_writer.hpp>
#include <gyrokit/models/rotor_model.hpp>

#include <catch2/catch.hpp>
#include <cmath>

using namespace gyrokit;

namespace {

RotorModel pinned_shaft(double alpha, double beta) {
    RotorModel m;
    RotorSection s;
    s.shape.length = 1.0;
    s.shape.outer_diameter = 0.05;
    s.shape.youngs_modulus = 2.1e11;
    s.shape.density = 7800;
    s.elements = 20;
    m.sections = {s};
    for (double z : {0.0, 1.0}) {
        RotorSupport sup;
        sup.z = z;
        m.supports.push_back(sup);
    }
    m.shaft_damping = {alpha, beta};
    return m;
}

}  // namespace

TEST_CASE("shaft damping: a shaft's modes have zeta = alpha / (2 w) + beta w / 2") {
    const double alpha = 2.0, beta = 2e-5;
    const Scene sc = rotor_scene(pinned_shaft(alpha, beta));
    REQUIRE(sc.system.damping.size() == 1);
    CHECK(sc.system.damping[0].name == "shaft");
    // At standstill M, K (and D) of the shaft alone: the undamped modes diagonalise D,
    // lambda = -zeta w +- i w sqrt(1 - zeta^2), so |lambda| = w exactly.
    const QuadraticSpectrum sp = solve_at_speed(sc.system, 0.0);
    int checked = 0;
    for (const Mode& m : sp.modes) {
        const double w = std::abs(m.lambda);
        if (m.lambda.imag() <= 0 || w > 2e4) continue;   // the lowest modes; zeta < 1 there
        const double zeta = alpha / (2 * w) + beta * w / 2;
        // zeta = -Re lambda / |lambda|: within the eigenvalue's error bound, relative to |lambda|.
        CHECK(std::abs(m.damping_ratio() - zeta) <= 2 * m.error_bound / w + 1e-14);
        ++checked;
    }
    CHECK(checked >= 8);
    // The scene keys, and the written scene, give the same component.
    const Scene back = parse_scene(scene_text(sc), "written", ".");
    CHECK(Eigen::MatrixXd(back.system.damping[0].D) == Eigen::MatrixXd(sc.system.damping[0].D));
    CHECK_THROWS_WITH(rotor_scene(pinned_shaft(-1.0, 0.0)), Catch::Contains("shaft damping alpha = -1"));
}
