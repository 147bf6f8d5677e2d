// Materials by name, disks from their geometry and speeds in rpm or Hz in a
// scene: each equal to the explicit form it stands for.
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/materials.hpp>

#include <catch2/catch.hpp>

#include "test_helpers.hpp"

#include <cmath>
#include <fmt/format.h>
#include <string>

using namespace gyrokit;

namespace {

const double pi = std::acos(-1.0);

std::string rotor(const std::string& model_keys, const std::string& disk, const std::string& speeds = "") {
    return "[model]\ntype = \"fe_rotor\"\n" + model_keys +
           "\n[[model.shaft]]\nlength = 1.2\nelements = 12\nouter_diameter = 0.06\n"
           "[[model.disk]]\nz = 0.6\n" + disk +
           "\n[[model.bearing]]\nz = 0.0\nk = 1e7\nc = 100\n[[model.bearing]]\nz = 1.2\nk = 1e7\nc = 100\n" + speeds;
}

// Every matrix of two systems equal to rounding of their largest entry.
void check_same(const GyroscopicSystem& a, const GyroscopicSystem& b, double tol) {
    REQUIRE(a.size() == b.size());
    CHECK((a.M - b.M).norm() <= tol * a.M.norm());
    CHECK((a.K - b.K).norm() <= tol * a.K.norm());
    CHECK((a.G - b.G).norm() <= tol * a.G.norm());
}

}  // namespace

TEST_CASE("a hollow-cylinder disk: m, Id, Ip in closed form", "[materials]") {
    const DiskInertia d = disk_inertia(0.28, 0.05, 0.07, 7810.0);
    const double R = 0.14, r = 0.025, w = 0.07;
    const double m = 7810.0 * pi * (R * R - r * r) * w;
    CHECK(d.mass == Approx(m).epsilon(1e-15));
    CHECK(d.polar_inertia == Approx(m * (R * R + r * r) / 2).epsilon(1e-15));
    CHECK(d.diametral_inertia == Approx(m * (3 * (R * R + r * r) + w * w) / 12).epsilon(1e-15));
    // A thin disk: Id -> Ip / 2.
    const DiskInertia thin = disk_inertia(0.3, 0.0, 1e-6, 7810.0);
    CHECK(thin.diametral_inertia == Approx(thin.polar_inertia / 2).epsilon(1e-9));
}

TEST_CASE("material = steel equals its E, poisson and density, a section's and the scene's own materials",
          "[materials]") {
    const Material steel = find_material("steel", {}, "test");
    CHECK(steel.youngs_modulus == 211e9);
    CHECK(steel.density == 7810.0);
    CHECK(steel.poisson_ratio == Approx(211.0 / 162.4 - 1).epsilon(1e-15));
    const std::string disk = "mass = 20.0\nId = 0.1\nIp = 0.2";
    const Scene named = parse_scene(rotor("material = \"steel\"", disk), "named.toml");
    const Scene spelled = parse_scene(
        rotor(fmt::format("E = {:.17g}\npoisson = {:.17g}\ndensity = {:.17g}", steel.youngs_modulus,
                          steel.poisson_ratio, steel.density),
              disk),
        "spelled.toml");
    check_same(named.system, spelled.system, 1e-15);
    // A key next to the material overrides it; a section may name its own material.
    const Scene lighter = parse_scene(rotor("material = \"steel\"\ndensity = 7000", disk), "lighter.toml");
    CHECK(lighter.system.M.norm() < named.system.M.norm());
    const std::string own = "material = \"mine\"\n[[model.materials]]\nname = \"mine\"\nE = 1e11\ndensity = 5000";
    const Scene mine = parse_scene(rotor(own, disk), "mine.toml");
    const Scene mine_spelled = parse_scene(rotor("E = 1e11\ndensity = 5000\npoisson = 0.3", disk), "ms.toml");
    check_same(mine.system, mine_spelled.system, 1e-15);
    const Scene alu = parse_scene(
        "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n[[model.shaft]]\nlength = 1.2\nelements = 12\n"
        "outer_diameter = 0.06\nmaterial = \"aluminium\"\n[[model.support]]\nz = 0.0\n[[model.support]]\nz = 1.2\n",
        "alu.toml");
    CHECK(alu.fe_rotor()->elements.front().density == 2700.0);
    CHECK(alu.fe_rotor()->elements.front().youngs_modulus == 68.9e9);
}

TEST_CASE("a disk from outer_diameter, inner_diameter, width and material equals its m, Id, Ip", "[materials]") {
    const DiskInertia d = disk_inertia(0.28, 0.05, 0.07, 7810.0);
    const Scene geometric = parse_scene(
        rotor("material = \"steel\"", "outer_diameter = 0.28\ninner_diameter = 0.05\nwidth = 0.07"), "g.toml");
    const Scene spelled = parse_scene(
        rotor("material = \"steel\"", fmt::format("mass = {:.17g}\nId = {:.17g}\nIp = {:.17g}", d.mass,
                                                    d.diametral_inertia, d.polar_inertia)),
        "s.toml");
    check_same(geometric.system, spelled.system, 1e-15);
    // The disk's own material.
    const Scene alu = parse_scene(
        rotor("material = \"steel\"", "outer_diameter = 0.28\nwidth = 0.07\nmaterial = \"aluminium\""), "a.toml");
    CHECK(alu.fe_rotor()->disks.front().mass == Approx(disk_inertia(0.28, 0.0, 0.07, 2700.0).mass).epsilon(1e-15));
}

TEST_CASE("[speeds] in rpm or Hz are converted to rad/s", "[materials][speeds]") {
    const std::string disk = "mass = 20.0\nId = 0.1\nIp = 0.2";
    const Scene rpm = parse_scene(rotor("material = \"steel\"", disk, "[speeds]\nfrom = 0\nto = 6000\ncount = 7\nunits = \"rpm\""),
                                  "rpm.toml");
    const Scene hz = parse_scene(rotor("material = \"steel\"", disk, "[speeds]\nfrom = 0\nto = 100\ncount = 3\nunits = \"HZ\""),
                                 "hz.toml");
    REQUIRE(rpm.speeds);
    CHECK(rpm.speeds->to == 6000);   // as written, in the scene's unit
    CHECK(rpm.speed_unit.name == "rpm");
    CHECK(rpm.speed_points().back() == Approx(6000 * 2 * pi / 60).epsilon(1e-15));
    CHECK(rpm.speed_points()[1] == Approx(1000 * 2 * pi / 60).epsilon(1e-15));
    CHECK(hz.speed_unit.name == "Hz");
    CHECK(hz.speed_points().back() == Approx(200 * pi).epsilon(1e-15));
}

TEST_CASE("materials, disk geometry and speed units: bad input names the key, value and what is allowed",
          "[materials]") {
    const std::string disk = "mass = 20.0\nId = 0.1\nIp = 0.2";
    const auto message = test::scene_error;
    CHECK(message(rotor("material = \"unobtainium\"", disk)) ==
          "bad.toml: [model] material = 'unobtainium' is unknown; allowed: steel, stainless, aluminium, titanium");
    CHECK(message(rotor("material = \"steel\"", "outer_diameter = 0.2\ninner_diameter = 0.2\nwidth = 0.05")) ==
          "bad.toml: [model.disk[0]] inner_diameter = 0.2 is not below outer_diameter = 0.2; allowed: 0 <= inner < outer (m)");
    CHECK(message(rotor("material = \"steel\"", "outer_diameter = 0.2\nwidth = 0.05\nmass = 3")).find(
              "[model.disk[0]] mass is given together with outer_diameter") != std::string::npos);
    CHECK(message(rotor("material = \"steel\"", "outer_diameter = 0.2")).find("[model.disk[0]] key 'width' is missing") !=
          std::string::npos);
    CHECK(message(rotor("material = \"steel\"", "outer_diameter = 0.2\nwidth = -0.05")).find(
              "[model.disk[0]] width = -0.05: out of range") != std::string::npos);
    CHECK(message(rotor("material = \"steel\"", "width = 0.05\nmass = 3")).find("width needs outer_diameter") !=
          std::string::npos);
    CHECK(message(rotor("material = \"steel\"", disk, "[speeds]\nfrom = 0\nto = 10\ncount = 3\nunits = \"deg/s\"")) ==
          "bad.toml: [speeds] units = 'deg/s': allowed: rad/s, Hz, rpm");
    const std::string twice = "material = \"a\"\n[[model.materials]]\nname = \"a\"\nE = 1e11\ndensity = 5000\n"
                              "[[model.materials]]\nname = \"a\"\nE = 2e11\ndensity = 6000";
    CHECK(message(rotor(twice, disk)) == "bad.toml: [model.materials[1]] name = 'a' names a material twice; allowed: "
                                         "each name once");
    // A range in rpm is checked in rpm.
    CHECK(message(rotor("material = \"steel\"", disk, "[speeds]\nfrom = 3000\nto = 1000\ncount = 3\nunits = \"rpm\""))
              .find("FROM = 3000 is greater than TO = 1000") != std::string::npos);
    // A disk off the shaft (the rotor is 1.2 m long).
    std::string off = rotor("material = \"steel\"", disk);
    off.replace(off.find("z = 0.6\n"), 8, "z = 1.9\n");
    CHECK(message(off).find("[model.disk[0]] z = 1.9 m is not a node of the mesh") != std::string::npos);
    // Hostile sizes: sections whose elements add up past the limit are refused before any is stored.
    const std::string big = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n"
                            "[[model.shaft]]\nlength = 1\nelements = 2\nouter_diameter = 0.05\n"
                            "[[model.shaft]]\nlength = 1\nelements = 4999998\nouter_diameter = 0.05\n";
    CHECK(message(big) == "bad.toml: [model.shaft[1]] elements = 4999998 makes 5000000 elements in all; allowed: at "
                          "most 4999999 (20,000,000 DOFs)");
}
