// Proportional shaft damping: on a shaft alone every mode has zeta = alpha / (2 w) + beta w / 2.
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/scene/scene_writer.hpp>
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

TEST_CASE("modal shaft damping: each mode of a shaft alone has its own zeta, both planes alike") {
    // zeta 0.01 for the first bending mode, 0.02 for the second, 0.03 for every mode above.
    RotorModel m = pinned_shaft(0.0, 0.0);
    m.shaft_damping.modal = {0.01, 0.02, 0.03};
    const Scene sc = rotor_scene(m);
    REQUIRE(sc.system.damping.size() == 1);
    const QuadraticSpectrum sp = solve_at_speed(sc.system, 0.0);
    // Standstill, shaft alone: the undamped modes diagonalise D, so zeta = -Re lambda / |lambda| exactly;
    // modes by frequency, in pairs (the x and y planes).
    std::vector<const Mode*> oscillating;
    for (const Mode& md : sp.modes)
        if (md.lambda.imag() > 0) oscillating.push_back(&md);
    REQUIRE(oscillating.size() >= 12);
    for (std::size_t k = 0; k < 12; ++k) {
        const Mode& md = *oscillating[k];
        const double zeta = k < 2 ? 0.01 : k < 4 ? 0.02 : 0.03;
        CAPTURE(k, md.lambda);
        CHECK(std::abs(md.damping_ratio() - zeta) <= 2 * md.error_bound / std::abs(md.lambda) + 1e-14);
    }
    // The same frequencies as without damping: |lambda| = w, within the two error bounds.
    m.shaft_damping.modal.clear();
    const QuadraticSpectrum undamped = solve_at_speed(rotor_scene(m).system, 0.0);
    for (std::size_t k = 0; k < 12; ++k)
        CHECK(std::abs(std::abs(oscillating[k]->lambda) - undamped.modes[k].lambda.imag()) <=
              oscillating[k]->error_bound + undamped.modes[k].error_bound);
    // Written and read back; out of range refused with the key and the range.
    m.shaft_damping.modal = {0.01, 0.02, 0.03};
    const Scene back = parse_scene(scene_text(rotor_scene(m)), "written", ".");
    CHECK(Eigen::MatrixXd(back.system.damping[0].D) == Eigen::MatrixXd(sc.system.damping[0].D));
    m.shaft_damping.modal = {0.01, 1.5};
    CHECK_THROWS_WITH(rotor_scene(m), Catch::Contains("shaft damping zeta[1] = 1.5: out of range; allowed: 0 <= zeta < 1"));
    std::string text = scene_text(sc);
    text.replace(text.find("damping_zeta = ["), 16, "damping_zeta = [-0.1, ");
    CHECK_THROWS_WITH(parse_scene(text, "bad.toml", "."), Catch::Contains("[model] damping_zeta[0] = -0.1: out of range"));
}
