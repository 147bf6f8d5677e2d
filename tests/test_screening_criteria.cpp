// Displacement probes: readings against their definition (exact at multiples of
// 90 degrees, the same at every angle on a circular orbit), the probe at a node.
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/screening/screening.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <fstream>
#include <limits>
#include <sstream>

using namespace gyrokit;
using cd = std::complex<double>;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0, 1, -1, 0).finished();

// Jeffcott rotor, mass m on supports kx, ky with external damping c_e and internal
// damping c_i: m x'' + (c_e + c_i) x' + kx x + c_i w y = m eps w^2 cos(wt), and y alike
// (in r = x + i y, isotropic: m r'' + (c_e + c_i) r' + (k - i c_i w) r = m eps w^2 e^{iwt}).
constexpr double jm = 2.0, jeps = 1e-4;

Scene jeffcott(double kx, double ky, double ce, double ci) {
    Scene sc;
    GyroscopicSystem& g = sc.system;
    g.M = jm * Eigen::Matrix2d::Identity();
    g.K = Eigen::Vector2d(kx, ky).asDiagonal();
    g.damping.push_back({"c_e", ce * Eigen::Matrix2d::Identity()});
    if (ci > 0) {
        g.damping.push_back({"c_i", ci * Eigen::Matrix2d::Identity()});
        g.N = ci * J;
    }
    g.unbalance = Eigen::Vector2cd(jm * jeps, cd(0, -jm * jeps));
    g.dof_names = {"x", "y"};
    g.dof_units = {"m", "m"};
    g.whirl_pairs = {{0, 1}};
    return sc;
}

}  // namespace

TEST_CASE("probe reading: 0 degrees reads x, 90 degrees y, a circular orbit the same at every angle", "[probe]") {
    Eigen::VectorXcd Z(3);
    Z << cd(0.3, -1.7), cd(-2.2, 0.4), cd(5.0, 5.0);
    const auto reading = [&](double angle, int x = 0, int y = 1) { return probe_amplitude(Probe{"p", x, y, angle}, Z); };
    // Multiples of 90 degrees read one DOF exactly (cos and sin are not rounded there).
    CHECK(reading(0.0) == std::abs(Z(0)));
    CHECK(reading(90.0) == std::abs(Z(1)));
    CHECK(reading(180.0) == std::abs(Z(0)));
    CHECK(reading(-90.0) == std::abs(Z(1)));
    CHECK(reading(360.0) == std::abs(Z(0)));
    CHECK(reading(90.0, 2, 0) == std::abs(Z(0)));
    CHECK(probe_response(Probe{"p", 0, 1, 270.0}, Z) == -Z(1));
    // A line orbit along x: |Z_x cos(angle)|.
    Eigen::VectorXcd line(2);
    line << cd(1e-3, 2e-3), 0.0;
    // A circular forward orbit: Z_y = -i Z_x (x = A cos wt, y = A sin wt), every direction reads |Z_x|.
    Eigen::VectorXcd circle(2);
    circle << cd(1e-3, 2e-3), cd(2e-3, -1e-3);
    for (double angle = -360.0; angle <= 360.0; angle += 7.5) {
        CAPTURE(angle);
        // cos and sin of the rounded argument (|error| <= 2 eps |angle in rad| + eps) and the
        // sum of two complex products (a few eps): 8 eps (1 + |angle in rad|) relative.
        const double tol = 8.0 * eps * (1.0 + std::abs(angle) * M_PI / 180.0);
        const double a = probe_amplitude(Probe{"c", 0, 1, angle}, circle);
        CHECK(std::abs(a - std::abs(circle(0))) <= tol * std::abs(circle(0)));
        const double l = probe_amplitude(Probe{"l", 0, 1, angle}, line);
        CHECK(std::abs(l - std::abs(line(0) * std::cos(angle * M_PI / 180.0))) <= tol * std::abs(line(0)));
    }
    CHECK_THROWS_AS(probe_amplitude(Probe{"p", 0, 3, 0.0}, Z), InputError);
}

TEST_CASE("probe at a node: the node's x and y, errors naming the node and the allowed range", "[probe]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const GyroscopicSystem& sys = sc.system;
    const Probe p = probe_at_node(sys, "NDE", 23, 45.0);
    CHECK(sys.dof_names.at(p.dof_x) == "x23");
    CHECK(sys.dof_names.at(p.dof_y) == "y23");
    CHECK(p.angle_degrees == 45.0);
    try {
        probe_at_node(sys, "far", 99, 0.0);
        FAIL("node 99 accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("node 99 does not exist; allowed: 0 to 24") != std::string::npos);
    }
    // A pinned end holds x and y of node 0: no probe there.
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    std::stringstream text;
    text << in.rdbuf();
    std::string t = text.str();
    t.insert(t.find("[speeds]"), "[[model.support]]\nz = 0.0\ntype = \"pinned\"\n\n");
    const Scene pinned = parse_scene(t, "pinned.toml", GYROKIT_DATA_DIR);
    try {
        probe_at_node(pinned.system, "held", 0, 0.0);
        FAIL("a held node accepted");
    } catch (const InputError& e) {
        CHECK(std::string(e.what()).find("node 0 has no free x and y") != std::string::npos);
    }
    CHECK_THROWS_AS(probe_at_node(jeffcott(5e3, 5e3, 4.0, 0.0).system, "none", 0, 0.0), InputError);
}
