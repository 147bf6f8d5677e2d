// Mesh convergence against a closed form: a uniform pinned-pinned Euler-Bernoulli shaft
// (no shear, no rotary inertia: no gyroscopic moments) has w_1 = (pi / L)^2 sqrt(EI / rho A);
// the study's meshes converge to it as h^4 (cubic Hermite elements), each change is the
// values' own, and the mesh chosen is the coarsest whose every later change is below the
// tolerance. Bad options are refused with their names.
#include <gyrokit/core/constants.hpp>
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <fmt/format.h>

using namespace gyrokit;

namespace {

// L = 1 m, d = 50 mm steel, 2 elements, pinned at both ends; speeds to 1.2 w_1 (rad/s).
std::string shaft_text(double top) {
    return fmt::format(R"(
[model]
type = "fe_rotor"
material = "steel"
shear_deformation = false
rotary_inertia = false
[[model.shaft]]
length = 1.0
elements = 2
outer_diameter = 0.05
[[model.support]]
z = 0
type = "pinned"
[[model.support]]
z = 1.0
type = "pinned"
[speeds]
from = 0
to = {}
count = 41
)",
                       top);
}

double first_frequency() {
    const double e = 211e9, rho = 7810, d = 0.05;
    const double i = kPi * std::pow(d, 4) / 64, a = kPi * d * d / 4;
    return kPi * kPi * std::sqrt(e * i / (rho * a));
}

}  // namespace

TEST_CASE("Mesh convergence of a pinned-pinned shaft to its closed-form first frequency", "[mesh]") {
    const double w1 = first_frequency();
    const Scene sc = parse_scene(shaft_text(1.2 * w1), "shaft.toml", ".");
    MeshConvergenceRequest r;
    r.tolerance = 2e-6;
    r.levels = 5;
    const MeshConvergenceStudy s = mesh_convergence_study(sc, r);
    REQUIRE(s.levels.size() >= 3);
    CHECK(s.levels[0].elements == 2);
    CHECK(s.levels[1].elements == 4);
    // The critical speed (no gyroscopic split: each whirl crosses at w_1) and the frequency converge to w_1.
    const MeshQuantity* crit = nullptr;
    for (const MeshQuantity& q : s.quantities)
        if (q.name == "critical speed 1") crit = &q;
    REQUIRE(crit != nullptr);
    const double finest = crit->values.back();
    CHECK(std::fabs(finest - w1) <= 1e-6 * w1);
    // Each change is the values' own, and shrinks as h^4: by about 16 per doubling.
    for (std::size_t i = 0; i < crit->change.size(); ++i)
        CHECK(crit->change[i] == Approx(std::fabs(crit->values[i + 1] - crit->values[i]) / crit->values[i + 1])
                                     .epsilon(1e-12));
    for (std::size_t i = 0; i + 1 < crit->change.size(); ++i)
        if (crit->change[i + 1] > 1e-12) CHECK(crit->change[i] / crit->change[i + 1] > 10);
    // The chosen mesh: the coarsest from which every change of every quantity is below 2e-6.
    int chosen = 0;
    for (const MeshQuantity& q : s.quantities) {
        int from = static_cast<int>(q.change.size());
        while (from > 0 && q.change[from - 1] < 2e-6) --from;
        CHECK(q.converged == (from < static_cast<int>(q.change.size()) ? from : -1));
        chosen = std::max(chosen, from);
    }
    CHECK(s.chosen == chosen);
    REQUIRE(s.chosen >= 0);
    CHECK(s.section_elements == std::vector<int>{2 * s.levels[static_cast<std::size_t>(s.chosen)].factor});
}

TEST_CASE("Mesh convergence: bad options and models refused with their names", "[mesh]") {
    const Scene sc = parse_scene(shaft_text(1000), "shaft.toml", ".");
    MeshConvergenceRequest r;
    r.tolerance = 0.7;
    CHECK_THROWS_WITH(mesh_convergence_study(sc, r), Catch::Contains("tolerance") && Catch::Contains("(0, 0.5)"));
    r.tolerance.reset();
    r.levels = 1;
    CHECK_THROWS_WITH(mesh_convergence_study(sc, r), Catch::Contains("levels") && Catch::Contains("[2, 8]"));
    const Scene gyrostat = load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml");
    CHECK_THROWS_WITH(mesh_convergence_study(gyrostat), Catch::Contains("allowed: fe_rotor"));
}
