// The model summary: its numbers against the model's own description.
#include <gyrokit/reports/reports.hpp>
#include <gyrokit/scene/scene.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace gyrokit;

namespace {

const Cell& value(const Table& t, const std::string& quantity) {
    for (std::size_t i = 0; i < t.rows(); ++i)
        if (std::get<std::string>(t.row(i)[0]) == quantity) return t.row(i)[1];
    FAIL("no row " << quantity);
    throw;
}

}  // namespace

TEST_CASE("model summary of the FE rotor: translating mass = shaft + disks, rigid-body count", "[model]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/fe_rotor.toml");
    const Table t = model_summary(sc);
    // Hermite beam elements move their full mass in a rigid translation: r^T M r is the total mass.
    const double shaft = 7810 * M_PI * 0.05 * 0.05 / 4 * 1.5;
    CHECK(std::get<double>(value(t, "shaft_mass")) == Approx(shaft).epsilon(1e-14));
    CHECK(std::get<double>(value(t, "translating_mass")) == Approx(shaft + 2 * 33.657).epsilon(1e-13));
    CHECK(std::get<double>(value(t, "total_mass")) == Approx(shaft + 2 * 33.657).epsilon(1e-14));
    CHECK(std::get<long long>(value(t, "dofs")) == 100);
    CHECK(std::get<long long>(value(t, "nodes")) == 25);
    CHECK(std::get<double>(value(t, "length")) == Approx(1.5).epsilon(1e-15));
    CHECK(std::get<long long>(value(t, "rigid_body_eigenvalues_at_rest")) == 0);
    CHECK(std::get<double>(value(t, "bearing2_z")) == Approx(1.5).epsilon(1e-15));
    // The disks of 280 mm diameter and 70 mm width come back from their m, Id, Ip (given to
    // five digits). The width comes from w^2 = 12 Id/m - 3 r^2 = 0.0636 - 0.0588, a difference
    // that turns the data's 1e-4 rounding into about 1 % of w.
    const Figure f = fe_rotor_figure(*sc.fe_rotor(), sc.system, sc.title);
    for (const auto& s : f.panels.front().series)
        if (s.label.rfind("disks", 0) == 0) {
            CHECK(s.y[1] == Approx(0.14).epsilon(2e-4));
            CHECK(s.x[2] - s.x[0] == Approx(0.07).epsilon(2e-2));
        }
}

TEST_CASE("model summary of the exported ROSS rotor counts its four rigid-body eigenvalues", "[model]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/ross_rotor_example/scene.toml");
    const Table t = model_summary(sc);
    CHECK(std::get<long long>(value(t, "dofs")) == 42);
    CHECK(std::get<long long>(value(t, "rigid_body_eigenvalues_at_rest")) == 4);
}

// A tapered section, a coupling and a pedestal: the shaft mass is the frustum's (exact),
// a rigid translation moves shaft, coupling and disk (not the pedestal, which is not on
// the axis), and the pedestal is listed.
TEST_CASE("model summary of a rotor with a cone, a coupling and a pedestal", "[model][pedestal][coupling]") {
    const Scene sc = parse_scene(R"(
[model]
type = "fe_rotor"
material = "steel"
length_unit = "mm"
[[model.shaft]]
length = 600
elements = 6
outer_diameter = 50
outer_diameter_end = 40
inner_diameter = 10
[[model.shaft]]
type = "coupling"
length = 50
k_lateral = 1e6
k_bending = 1e4
mass = 1.5
[[model.shaft]]
length = 300
elements = 3
outer_diameter = 40
[[model.disk]]
z = 300
mass = 10
[[model.pedestal]]
z = 0
mass = 20
k = 5e7
c = 100
[[model.bearing]]
z = 0
speeds = [0, 1000]
k = [3e7, 3e7]
[[model.bearing]]
z = 950
k = 2e7
)",
                                 "cone.toml");
    const Table t = model_summary(sc);
    const double cone = 7810 * M_PI / 4 * 0.6 * ((0.05 * 0.05 + 0.05 * 0.04 + 0.04 * 0.04) / 3 - 0.01 * 0.01);
    const double shaft = cone + 1.5 + 7810 * M_PI / 4 * 0.04 * 0.04 * 0.3;
    CHECK(std::get<double>(value(t, "shaft_mass")) == Approx(shaft).epsilon(1e-14));
    CHECK(std::get<double>(value(t, "total_mass")) == Approx(shaft + 10).epsilon(1e-14));
    CHECK(std::get<double>(value(t, "translating_mass")) == Approx(shaft + 10).epsilon(1e-13));
    CHECK(std::get<long long>(value(t, "couplings")) == 1);
    CHECK(std::get<double>(value(t, "pedestal1_mass")) == 20.0);
    // Bearings by their place in the scene: the table first (z = 0), the constant one second.
    CHECK(std::get<double>(value(t, "bearing1_z")) == Approx(0.0).margin(1e-15));
    CHECK(std::get<double>(value(t, "bearing2_z")) == Approx(950.0).epsilon(1e-15));
    // Lengths as the scene states them (length_unit = "mm"): 40 mm, not 0.04 m.
    CHECK(std::get<double>(value(t, "shaft_outer_diameter_min")) == Approx(40.0).epsilon(1e-14));
    for (std::size_t i = 0; i < t.rows(); ++i)
        if (std::get<std::string>(t.row(i)[0]) == "shaft_outer_diameter_min") CHECK(std::get<std::string>(t.row(i)[2]) == "mm");
}

TEST_CASE("model summary names the shaft's own damping as the scene gives it", "[model]") {
    const std::string rotor = R"(
[model]
type = "fe_rotor"
material = "steel"
%s
[[model.shaft]]
length = 1.0
elements = 4
outer_diameter = 0.05
[[model.support]]
z = 0
[[model.support]]
z = 1.0
)";
    const auto with = [&](const std::string& keys) {
        std::string text = rotor;
        text.replace(text.find("%s"), 2, keys);
        return model_summary(parse_scene(text, "shaft damping"));
    };
    const Table p = with("damping_alpha = 2.0\ndamping_beta = 1e-5");
    CHECK(std::get<double>(value(p, "shaft_damping_alpha")) == 2.0);
    CHECK(std::get<double>(value(p, "shaft_damping_beta")) == 1e-5);
    CHECK(std::get<std::string>(value(with("damping_zeta = [0.01, 0.02]"), "shaft_damping_zeta")) == "0.01, 0.02");
}

TEST_CASE("the model drawing shows a disk given by its geometry as that hollow cylinder", "[model]") {
    // data/three_disk_rotor.toml: disks of 320/100 x 50, 400/100 x 70 and 320/100 x 50 mm, drawn
    // with their bore (a box from the inner to the outer radius above and below the axis), not as
    // the solid cylinder of the same m, Id, Ip; a disk given by m, Id, Ip keeps that one.
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const Figure f = fe_rotor_figure(sc);
    const Series* disks = nullptr;
    for (const auto& s : f.panels.front().series)
        if (s.label == "disks") disks = &s;
    REQUIRE(disks != nullptr);
    // Six boxes of five corners and a break each.
    REQUIRE(disks->y.size() == 36);
    const double outer[3] = {0.16, 0.20, 0.16}, width[3] = {0.05, 0.07, 0.05}, z[3] = {0.35, 0.6, 0.85};
    for (int k = 0; k < 3; ++k) {
        const std::size_t above = 12 * k, below = 12 * k + 6;
        INFO("disk " << k);
        CHECK(disks->y[above] == 0.05);
        CHECK(disks->y[above + 1] == outer[k]);
        CHECK(disks->y[below] == -outer[k]);
        CHECK(disks->y[below + 1] == -0.05);
        CHECK(disks->x[above + 2] - disks->x[above] == Approx(width[k]).epsilon(1e-12));
        CHECK(0.5 * (disks->x[above + 2] + disks->x[above]) == Approx(z[k]).epsilon(1e-12));
    }
    // The same scene through the description-free overload: the equivalent solid cylinders.
    const Figure bare = fe_rotor_figure(*sc.fe_rotor(), sc.system, sc.title);
    bool solid = false;
    for (const auto& s : bare.panels.front().series)
        solid = solid || s.label == "disks (solid cylinders of their m, Id, Ip)";
    CHECK(solid);
}
