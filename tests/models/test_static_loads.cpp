// Static bearing loads from the rotor's weight (fe_gravity_reactions, fluid-film
// load = "auto") against the statics of beams: the lever rule of a statically
// determinate rotor and the three-moment result of a continuous beam on three supports.
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/gravity_loads.hpp>
#include <gyrokit/models/journal_bearing.hpp>

#include "test_helpers.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace gyrokit;

namespace {
constexpr double g = 9.80665;
}

// A shaft of mass m_s on supports at z = 0 and z = L with a disk m_d at z = a: the
// reactions are m_s g / 2 + m_d g (L - a) / L and m_s g / 2 + m_d g a / L, whatever the
// stiffness (statically determinate). Consistent loads (M times the rigid lift) make the
// FE reactions exact, so rounding alone (1e-12) remains. Overhung (a > L) the left
// reaction turns negative.
TEST_CASE("static loads: a shaft with a disk on two bearings, the lever rule", "[fe_rotor][static_loads][validation]") {
    const double L = 1.2, d = 0.06, rho = 7850.0, md = 40.0;
    const double ms = rho * M_PI * d * d / 4 * L;
    for (const int disk_node : {3, 6, 9}) {
        FeRotor r = fe_uniform_shaft(L, 12, d, 0.0, 2.1e11, 0.3, rho);
        r.motion = FeMotion::all;   // the axial and torsional DOFs carry no weight
        r.disks.push_back({disk_node, md, 0.3, 0.5, 0.0, 0.0});
        const double a = L * disk_node / 12;
        const std::vector<double> R = fe_gravity_reactions(r, {0, 12});
        INFO("disk at " << a);
        CHECK(R[0] == Approx(ms * g / 2 + md * g * (L - a) / L).epsilon(1e-12));
        CHECK(R[1] == Approx(ms * g / 2 + md * g * a / L).epsilon(1e-12));
    }
    // Overhung: supports at nodes 0 and 8 (z = 0.8 m), the disk at the free end (1.2 m).
    FeRotor r = fe_uniform_shaft(L, 12, d, 0.0, 2.1e11, 0.3, rho);
    r.disks.push_back({12, md, 0.3, 0.5, 0.0, 0.0});
    const double l = 0.8, c = L / 2;   // span, shaft's centre of mass
    const std::vector<double> R = fe_gravity_reactions(r, {0, 8});
    CHECK(R[0] == Approx((ms * g * (l - c) + md * g * (l - L)) / l).epsilon(1e-12));
    CHECK(R[0] < 0.0);
    CHECK(R[0] + R[1] == Approx((ms + md) * g).epsilon(1e-12));
}

// A uniform Euler-Bernoulli beam on three equally spaced rigid supports (two spans l,
// load w per length): reactions 3wl/8, 10wl/8, 3wl/8 (three-moment equation). Cubic
// elements with consistent loads give the exact nodal statics of a uniform load, so the
// reactions hold to rounding, for any element count.
TEST_CASE("static loads: a continuous beam on three supports, 3/16, 5/8, 3/16 of its weight",
          "[fe_rotor][static_loads][validation]") {
    const double L = 2.0, d = 0.05, rho = 7800.0;
    const double W = rho * M_PI * d * d / 4 * L * g;
    for (const int count : {2, 8, 20}) {
        FeRotor r = fe_uniform_shaft(L, count, d, 0.0, 2.1e11, 0.3, rho);
        r.shear_deformation = false;
        const std::vector<double> R = fe_gravity_reactions(r, {0, count / 2, count});
        INFO(count << " elements");
        CHECK(R[0] == Approx(3.0 / 16 * W).epsilon(1e-10));
        CHECK(R[1] == Approx(10.0 / 16 * W).epsilon(1e-10));
        CHECK(R[2] == Approx(3.0 / 16 * W).epsilon(1e-10));
    }
    // On springs instead (a constant bearing k in the middle): the middle takes less.
    FeRotor r = fe_uniform_shaft(L, 20, d, 0.0, 2.1e11, 0.3, rho);
    r.shear_deformation = false;
    r.bearings.push_back({10, 1e5, 0, 0, 1e5, 0, 0, 0, 0});
    const std::vector<double> R = fe_gravity_reactions(r, {0, 20});
    CHECK(R[0] + R[1] < W);
    CHECK(R[0] > 0.0);
}

// A scene's fluid films with load = "auto" equal films given those loads by hand.
TEST_CASE("static loads: fluid films with load = auto in a scene", "[fe_rotor][static_loads][journal_bearing]") {
    const std::string film = "type = \"fluid_film\"\ndiameter = 50\nlength = 25\nclearance = 0.05\n"
                             "viscosity = 0.02\nload = \"auto\"\n";
    const std::string head = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\nlength_unit = \"mm\"\n"
                             "[[model.shaft]]\nlength = 1000\nelements = 10\nouter_diameter = 50\n"
                             "[[model.disk]]\nz = 300\nmass = 25.0\nId = 0.1\nIp = 0.2\n";
    const Scene sc = parse_scene(head + "[[model.bearing]]\nz = 0\n" + film + "[[model.bearing]]\nz = 1000\n" + film,
                                 "auto.toml");
    REQUIRE(sc.system.bearings.size() == 2);
    const double ms = 7810.0 * M_PI * 0.05 * 0.05 / 4 * 1.0;   // steel: 7810 kg/m^3 (docs/fe_rotor.md)
    const double loads[2] = {ms * g / 2 + 25.0 * g * 0.7, ms * g / 2 + 25.0 * g * 0.3};
    for (int k = 0; k < 2; ++k) {
        JournalBearing b;
        b.diameter = 0.05, b.length = 0.025, b.clearance = 50e-6, b.viscosity = 0.02, b.load = loads[k];
        for (const double w : {100.0, 1000.0}) {
            const BearingCoefficients want = short_bearing(b, w).coefficients, got = sc.system.bearings[k].at(w);
            CHECK((got.K - want.K).norm() <= 1e-9 * want.K.norm());
            CHECK((got.C - want.C).norm() <= 1e-9 * want.C.norm());
        }
    }
    // Bad input: a word other than auto, a rotor the films cannot hold, a bearing lifted off.
    CHECK_THAT(test::scene_error(head + "[[model.bearing]]\nz = 0\n" + film + "load = \"heavy\"\n"),
               Catch::Contains("load"));
    CHECK_THAT(test::scene_error(head + "[[model.bearing]]\nz = 0\n" + film),
               Catch::Contains("free to fall or tip") && Catch::Contains("load = a number"));
    const std::string overhung = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\nlength_unit = \"mm\"\n"
                                 "[[model.shaft]]\nlength = 1000\nelements = 10\nouter_diameter = 50\n"
                                 "[[model.disk]]\nz = 1000\nmass = 200.0\n"
                                 "[[model.bearing]]\nz = 0\n" + film + "[[model.bearing]]\nz = 500\n" + film;
    CHECK_THAT(test::scene_error(overhung),
               Catch::Contains("[model.bearing[0]] load = \"auto\"") && Catch::Contains("lifts the journal off"));
}
