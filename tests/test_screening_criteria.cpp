// Displacement probes: readings against their definition (exact at multiples of
// 90 degrees, the same at every angle on a circular orbit), the probe at a node.
// The stability margin (min_log_dec): log decrements of Jeffcott rotors against
// the roots of their characteristic equation, within the eigenvalue error bounds.
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <array>
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

// A sweep of the Jeffcott rotor over one of its values (model.kx, model.ky, model.c_e,
// model.c_i; model.k sets both supports).
Sweep jeffcott_sweep(const std::string& varied, const std::vector<double>& values, double ce = 4.0, double ci = 0.0) {
    Sweep s;
    s.path = "jeffcott sweep";
    s.loader = [=](const std::map<std::string, double>& o) {
        const auto get = [&](const std::string& k, double d) {
            const auto it = o.find(k);
            return it == o.end() ? d : it->second;
        };
        const double k = get("model.k", 5e3);
        return jeffcott(get("model.kx", k), get("model.ky", k), get("model.c_e", ce), get("model.c_i", ci));
    };
    SweepParameter p;
    p.name = varied;
    p.values = values;
    s.parameters = {p};
    return s;
}

// The roots of m l^2 + c l + kc = 0 (kc complex), without cancellation: q = -(c + sqrt(d))/2
// with Re sqrt(d) >= 0, l1 = q/m, l2 = kc/q.
std::array<cd, 2> roots(double m, double c, cd kc) {
    const cd q = -0.5 * (c + std::sqrt(c * c - 4.0 * m * kc));
    return {q / m, kc / q};
}

double log_dec(cd l) { return -2.0 * M_PI * l.real() / std::abs(l.imag()); }

// What the eigenvalue's error bound e allows for -2 pi Re l / |Im l|, to first order:
// 2 pi e (1/|Im l| + |Re l|/Im l^2); the closed form's own rounding (a few eps |l|) added to e.
double log_dec_bound(cd l, double e) {
    const double im = std::abs(l.imag());
    return 2.0 * M_PI * (e + 8.0 * eps * std::abs(l)) * (1.0 / im + std::abs(l.real()) / (im * im));
}

// The largest bound over the oscillating modes the criterion reads: its own study
// (every mode, 0..up_to) on the design's scene.
double largest_log_dec_bound(const Scene& sc, double up_to, int count) {
    StudyOptions so = study_options(sc);
    so.solver.modes = 0;
    so.speeds = SpeedRange{0.0, up_to, count}.points();
    double b = 0.0;
    for (const Branch& br : stability_study(sc.system, so).tracked.diagram.branches)
        for (const BranchPoint& p : br.points)
            if (p.mode.lambda.imag() > 0.0) b = std::max(b, log_dec_bound(p.mode.lambda, p.mode.error_bound));
    REQUIRE(std::isfinite(b));
    return b;
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

TEST_CASE("log decrement margin: Jeffcott rotor, delta = 2 pi zeta / sqrt(1 - zeta^2) at every speed",
          "[screening][stability]") {
    // k = 5e3, m = 2: zeta = c_e / (2 sqrt(k m)) = c_e / 200; delta = 0.0314, 0.0628, 0.126, 0.315.
    const double up_to = 100.0, limit = 0.1;
    const int count = 41;
    Sweep s = jeffcott_sweep("model.c_e", {1.0, 2.0, 4.0, 10.0});
    s.criteria.stability = StabilityCriterion{up_to, count, limit};
    finalize_sweep(s);
    const std::vector<std::string> q = quantity_columns(s);
    REQUIRE(q == std::vector<std::string>{"instability_onset_rad_s", "min_log_dec", "min_log_dec_speed_rad_s"});
    for (std::size_t i = 0; i < s.design_count(); ++i) {
        const DesignResult r = evaluate_design(s, i);   // the numbers unrounded (a row has 12 digits)
        const double ce = r.parameters[0], zeta = ce / 200.0;
        const double expected = 2.0 * M_PI * zeta / std::sqrt(1.0 - zeta * zeta);
        const double tol = largest_log_dec_bound(s.loader({{"model.c_e", ce}}), up_to, count);
        INFO("c_e = " << ce << ", delta = " << expected << " +- " << tol << ": " << r.reason);
        REQUIRE(r.quantities[1]);
        CHECK(std::abs(*r.quantities[1] - expected) <= tol);
        CHECK(*r.quantities[2] >= 0.0);
        CHECK(*r.quantities[2] <= up_to);
        CHECK_FALSE(r.quantities[0]);   // stable
        const bool fails = expected < limit;
        CHECK(r.verdict == (fails ? Verdict::Fail : Verdict::Pass));
        if (fails) {
            CHECK(r.failed == std::vector<std::string>{"stability"});
            CHECK(r.reason.find("stability: log decrement") != std::string::npos);
            CHECK(r.reason.find("required 0.1, short by") != std::string::npos);
        }
    }
    // The run writes them as columns after the onset.
    const RunResult run = run_screening(s, RunOptions{});
    CHECK(result_columns(s)[3] == "min_log_dec");
    for (const auto& row : run.rows) CHECK(std::abs(std::stod(row.cells[3]) - *evaluate_design(s, row.index).quantities[1]) <=
                                           1e-11 * std::stod(row.cells[3]));   // 12 digits
}

TEST_CASE("log decrement margin: internal damping, the forward mode is least damped at the top speed",
          "[screening][stability]") {
    // m r'' + (c_e + c_i) r' + (k - i c_i w) r = 0: the forward root loses damping with speed and
    // turns unstable at w_n (1 + c_e/c_i) = 250, 150, 75 rad/s for c_i = 1, 2, 8.
    const double k = 5e3, ce = 4.0, up_to = 100.0, limit = 0.1;
    const int count = 41;
    Sweep s = jeffcott_sweep("model.c_i", {1.0, 2.0, 8.0}, ce);
    s.criteria.stability = StabilityCriterion{up_to, count, limit};
    finalize_sweep(s);
    for (std::size_t i = 0; i < s.design_count(); ++i) {
        const DesignResult r = evaluate_design(s, i);
        const double ci = r.parameters[0];
        const auto least = [&](double w) {
            const auto l = roots(jm, ce + ci, cd(k, -ci * w));
            return std::min(log_dec(l[0]), log_dec(l[1]));
        };
        // The least decrement falls with speed: the minimum is the top speed's.
        for (int i = 1; i <= 1000; ++i) REQUIRE(least(up_to * i / 1000.0) < least(up_to * (i - 1) / 1000.0));
        const auto l = roots(jm, ce + ci, cd(k, -ci * up_to));
        const cd weakest = log_dec(l[0]) < log_dec(l[1]) ? l[0] : l[1];
        const double expected = log_dec(weakest);
        const double tol = largest_log_dec_bound(s.loader({{"model.c_i", ci}}), up_to, count);
        INFO("c_i = " << ci << ", delta = " << expected << " +- " << tol << ": " << r.reason);
        REQUIRE(r.quantities[1]);
        CHECK(std::abs(*r.quantities[1] - expected) <= tol);
        CHECK(*r.quantities[2] == up_to);
        const double threshold = std::sqrt(k / jm) * (1.0 + ce / ci);
        REQUIRE(std::abs(expected - limit) > tol);
        CHECK(r.verdict == (expected < limit || threshold < up_to ? Verdict::Fail : Verdict::Pass));
        CHECK(bool(r.quantities[0]) == (threshold < up_to));
        if (threshold < up_to) {   // unstable: the onset's reason, and the least decrement with it
            CHECK(expected < 0.0);
            CHECK(r.reason.find("is unstable from") != std::string::npos);
            CHECK(r.reason.find(", least log decrement -") != std::string::npos);
            CHECK(r.failed == std::vector<std::string>{"stability"});
        }
    }
}
