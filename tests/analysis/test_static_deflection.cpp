// Static analysis of an FE rotor against closed forms: a simply supported uniform
// shaft with a central disk under gravity (Euler-Bernoulli and Timoshenko), a
// horizontal point load, reactions and internal forces, and a rotor not held.
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/reports/model_reports.hpp>
#include <gyrokit/reports/static_reports.hpp>
#include <gyrokit/study/static_study.hpp>
#include <fmt/format.h>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/analysis/static_deflection.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <map>

using namespace gyrokit;

namespace {

const double pi = std::acos(-1.0);
const double L = 1.2, D = 0.05, E = 2.1e11, nu = 0.3, rho = 7800, g = 9.80665, disk = 25.0;
const int n = 12;   // elements; the disk at node n / 2

FeRotor simply_supported(bool shear) {
    FeRotor r = fe_uniform_shaft(L, n, D, 0.0, E, nu, rho);
    r.shear_deformation = shear;
    r.disks.push_back({n / 2, disk, 0.0, 0.0, 0.0, 0.0});
    r.supports.push_back({0});        // pinned: x and y held
    r.supports.push_back({n});
    return r;
}

// The nodal values of cubic (Euler-Bernoulli) and interdependent (Timoshenko) elements are
// exact for point loads and, with consistent loads, for a uniform load; what remains is the
// rounding of a solve whose condition number grows as n^4 (about 1e5 here): 1e-9 relative.
const double tol = 1e-9;

}  // namespace

TEST_CASE("static: a simply supported shaft with a central disk under gravity, against the beam formulas") {
    const double A = pi * D * D / 4, I = pi * std::pow(D, 4) / 64, w = rho * A * g, P = disk * g;
    for (const bool shear : {false, true}) {
        INFO("shear deformation " << shear);
        const StaticResult s = fe_static(simply_supported(shear), {});
        const FeSection sec = fe_section(FeShaftElement{L / n, D, 0.0, {}, {}, {}, E, 0.0, nu, rho});
        const double kGA = shear ? sec.shear_coefficient * sec.shear_modulus * A : INFINITY;
        const double sag = P * L * L * L / (48 * E * I) + 5 * w * std::pow(L, 4) / (384 * E * I) + P * L / (4 * kGA) +
                           w * L * L / (8 * kGA);
        const StaticNode& mid = s.nodes[n / 2];
        CHECK(mid.z == Approx(L / 2).epsilon(1e-15));
        CHECK(mid.y == Approx(-sag).epsilon(tol));
        CHECK(std::abs(mid.x) <= 1e-15 * sag);
        CHECK(std::abs(mid.slope_y) <= tol * sag / L);
        // End slope of the Euler-Bernoulli beam: P L^2 / (16 E I) + w L^3 / (24 E I), downwards from the left.
        if (!shear)
            CHECK(s.nodes[0].slope_y == Approx(-(P * L * L / (16 * E * I) + w * L * L * L / (24 * E * I))).epsilon(tol));
        // Internal forces: M = P L / 4 + w L^2 / 8 at mid-span (sagging), V = (P + w L) / 2 at the supports.
        const StaticSection& left_of_mid = s.sections[2 * (n / 2 - 1) + 1];
        const StaticSection& right_of_mid = s.sections[2 * (n / 2)];
        CHECK(left_of_mid.z == Approx(L / 2));
        CHECK(left_of_mid.moment_y == Approx(P * L / 4 + w * L * L / 8).epsilon(tol));
        CHECK(right_of_mid.moment_y == Approx(P * L / 4 + w * L * L / 8).epsilon(tol));
        CHECK(left_of_mid.shear_y == Approx(P / 2).epsilon(tol));    // the disk's weight: a jump of P
        CHECK(right_of_mid.shear_y == Approx(-P / 2).epsilon(tol));
        CHECK(s.sections.front().shear_y == Approx((P + w * L) / 2).epsilon(tol));
        CHECK(std::abs(s.sections.front().moment_y) <= tol * P * L);
        CHECK(s.sections.back().shear_y == Approx(-(P + w * L) / 2).epsilon(tol));
        // Reactions: half the weight at each support, upwards; the balance and the solve verified.
        REQUIRE(s.reactions.size() == 2);
        for (const StaticReaction& r : s.reactions) CHECK(r.fy == Approx((P + w * L) / 2).epsilon(tol));
        CHECK(s.weight == Approx(P + w * L).epsilon(1e-13));
        CHECK(s.balance_error <= 1e-12);
        CHECK(s.backward_error <= 1e-14);
    }
}

TEST_CASE("static: a horizontal point load bends the horizontal plane alone, M = -F L / 4 under the load") {
    FeRotor r = simply_supported(false);
    StaticOptions o;
    o.gravity = 0.0;
    const double F = 1000.0, I = pi * std::pow(D, 4) / 64;
    o.loads.push_back({n / 2, F, 0.0, 0.0, 0.0});
    const StaticResult s = fe_static(r, o);
    CHECK(s.nodes[n / 2].x == Approx(F * L * L * L / (48 * E * I)).epsilon(tol));
    CHECK(std::abs(s.nodes[n / 2].y) <= 1e-15);
    CHECK(s.sections[2 * (n / 2 - 1) + 1].moment_x == Approx(-F * L / 4).epsilon(tol));
    CHECK(s.sections.front().shear_x == Approx(-F / 2).epsilon(tol));
    for (const StaticReaction& re : s.reactions) CHECK(re.fx == Approx(-F / 2).epsilon(tol));
    CHECK(s.balance_error <= 1e-12);
}

TEST_CASE("static: bearings as springs and a cantilever, against closed forms") {
    // A shaft on two equal springs k, weight only: each spring carries half, and sinks by it / k.
    FeRotor r = fe_uniform_shaft(L, n, D, 0.0, E, nu, rho);
    r.shear_deformation = false;
    const double k = 1e7, W = rho * pi * D * D / 4 * L * g;
    for (const int node : {0, n}) {
        FeBearing b;
        b.node = node;
        b.kxx = b.kyy = k;
        r.bearings.push_back(b);
    }
    const StaticResult s = fe_static(r, {});
    REQUIRE(s.reactions.size() == 2);
    for (const StaticReaction& re : s.reactions) CHECK(re.fy == Approx(W / 2).epsilon(tol));
    CHECK(s.nodes[0].y == Approx(-W / (2 * k)).epsilon(tol));
    // Clamped at z = 0, free at L: tip deflection w L^4 / (8 E I), root moment -w L^2 / 2 (hogging).
    FeRotor c = fe_uniform_shaft(L, n, D, 0.0, E, nu, rho);
    c.shear_deformation = false;
    FeSupport clamp;
    clamp.theta_x = clamp.theta_y = true;
    c.supports.push_back(clamp);
    const StaticResult t = fe_static(c, {});
    const double I = pi * std::pow(D, 4) / 64, w = W / L;
    CHECK(t.nodes[n].y == Approx(-w * std::pow(L, 4) / (8 * E * I)).epsilon(tol));
    CHECK(t.sections.front().moment_y == Approx(-w * L * L / 2).epsilon(tol));
    CHECK(t.reactions[0].fy == Approx(W).epsilon(tol));
    CHECK(t.reactions[0].mx == Approx(-w * L * L / 2).epsilon(tol));   // about +x: holds the shaft up at its root
}

TEST_CASE("static: a rotor its supports leave free, and bad options, are refused with a reason") {
    FeRotor r = fe_uniform_shaft(L, n, D, 0.0, E, nu, rho);
    r.supports.push_back({0});   // one pinned end: it tips
    CHECK_THROWS_WITH(fe_static(r, {}), Catch::Contains("the rotor is not held"));
    r.supports.push_back({n});
    StaticOptions o;
    o.gravity = -1;
    CHECK_THROWS_WITH(fe_static(r, o), Catch::Contains("gravity = -1"));
    o.gravity = 9.81;
    o.loads.push_back({n + 1, 1.0});
    CHECK_THROWS_WITH(fe_static(r, o), Catch::Contains("load 0 at node 13; allowed: 0 to 12"));
    r.motion = FeMotion::torsional;
    CHECK_THROWS_WITH(fe_static(r, {}), Catch::Contains("motion is torsional"));
}

TEST_CASE("static: an mm scene prints positions and deflections in mm, the same numbers scaled") {
    const auto text = [](const std::string& unit, double scale) {
        return fmt::format("[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\nlength_unit = \"{}\"\n"
                           "[[model.shaft]]\nlength = {}\nelements = 4\nouter_diameter = {}\n"
                           "[[model.disk]]\nz = {}\nouter_diameter = {}\nwidth = {}\n"
                           "[[model.support]]\nz = 0\n[[model.support]]\nz = {}\n",
                           unit, 1.0 * scale, 0.05 * scale, 0.5 * scale, 0.2 * scale, 0.03 * scale, 1.0 * scale);
    };
    const Scene m = parse_scene(text("m", 1.0), "m.toml", "."), mm = parse_scene(text("mm", 1000.0), "mm.toml", ".");
    REQUIRE(mm.length_unit().name == "mm");
    const Table a = static_node_table(static_study(m, {}), m.length_unit());
    const Table b = static_node_table(static_study(mm, {}), mm.length_unit());
    CHECK(a.columns()[1] == "z_m");
    CHECK(b.columns() == std::vector<std::string>{"node", "z_mm", "x_mm", "y_mm", "slope_x_rad", "slope_y_rad"});
    REQUIRE(a.rows() == b.rows());
    // The mm scene's inputs differ from the m scene's by the rounding of 1e-3 (a few ulp): so do the results.
    for (std::size_t i = 0; i < a.rows(); ++i)
        for (std::size_t j = 1; j < 4; ++j) {
            const double x = std::get<double>(a.row(i)[j]), y = std::get<double>(b.row(i)[j]);
            CHECK(std::abs(y - 1000.0 * x) <= 1e-12 * std::max(1.0, std::abs(y)));
        }
}

TEST_CASE("static: every bearing is named by its number in the scene, whatever its kind, as in the model summary") {
    // A fluid film listed first, a constant bearing second, a support last: the reactions read
    // bearing 1 (the film, held rigid), bearing 2 (the spring), support 1; the model summary's
    // bearingN_z and the critical map's curves use the same numbers.
    const std::string text =
        "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n"
        "[[model.shaft]]\nlength = 1.0\nelements = 4\nouter_diameter = 0.05\n"
        "[[model.bearing]]\ntype = \"fluid_film\"\nz = 0.0\ndiameter = 0.05\nlength = 0.025\nclearance = 5e-5\n"
        "viscosity = 0.02\nload = \"auto\"\n"
        "[[model.bearing]]\nz = 0.75\nkxx = 1e8\nkyy = 1e8\n"
        "[[model.support]]\nz = 1.0\n";
    const Scene sc = parse_scene(text, "mixed.toml", ".");
    const StaticResult r = static_study(sc, {});
    REQUIRE(r.reactions.size() == 3);
    CHECK(r.reactions[0].what == "bearing 1");
    CHECK(r.reactions[0].node == 0);
    CHECK(r.reactions[1].what == "bearing 2");
    CHECK(r.reactions[1].node == 3);
    CHECK(r.reactions[2].what == "support 1");
    // The weight is carried: the vertical reactions add up to it.
    CHECK(r.reactions[0].fy + r.reactions[1].fy + r.reactions[2].fy == Approx(r.weight).epsilon(1e-9));
    const Table summary = model_summary(sc);
    std::map<std::string, double> z;
    for (std::size_t i = 0; i < summary.rows(); ++i)
        if (const auto* q = std::get_if<std::string>(&summary.row(i)[0]); q && q->rfind("bearing", 0) == 0 &&
                                                                            q->find("_z") != std::string::npos)
            z[*q] = std::get<double>(summary.row(i)[1]);
    CHECK(z == std::map<std::string, double>{{"bearing1_z", 0.0}, {"bearing2_z", 0.75}});
    const BearingNumbers numbers = bearing_numbers(*sc.rotor_model());
    CHECK(numbers.constant == std::vector<int>{2});
    CHECK(numbers.speed_dependent == std::vector<int>{1});
}
