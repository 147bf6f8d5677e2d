// The energy bound on the growth rate of every mode: closed-form eigenvalues of
// rotors with cross-coupled stiffness and negative damping (the bound holds and is
// sharp to first order), every mode of FE rotors solved in full against it, the
// cases where it does not apply, and the screening's stability criterion, which
// leans on it for the modes above the excitation band.
#include <gyrokit/analysis/energy_bound.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/screening/screening.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <limits>

using namespace gyrokit;
using cd = std::complex<double>;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0, 1, -1, 0).finished();

// m r'' + c r' + (k - i kxy) r = 0 in r = x + i y: mass m on supports k with damping c
// and a cross-coupled stiffness kxy (a seal, a fluid film): K = k I + kxy J.
GyroscopicSystem isotropic(double m, double k, double c, double kxy) {
    GyroscopicSystem g;
    g.M = m * Eigen::Matrix2d::Identity();
    g.K = (k * Eigen::Matrix2d::Identity() + kxy * J).eval();
    g.damping.push_back({"c", c * Eigen::Matrix2d::Identity()});
    g.dofs.names = {"x", "y"};
    g.whirl_pairs = {{0, 1}};
    return g;
}

// The largest Re of the roots of m l^2 + c l + kc = 0 (kc complex), without cancellation.
double largest_real_part(double m, double c, cd kc) {
    cd d = std::sqrt(cd(c * c) - 4.0 * m * kc);
    if (d.real() < 0.0) d = -d;
    const cd q = -0.5 * (c + d);
    return std::max((q / m).real(), (kc / q).real());
}

}  // namespace

TEST_CASE("energy bound: cross-coupled stiffness, kxy / (2 sqrt(k m)) bounds Re lambda and is sharp to first order",
          "[energy_bound]") {
    const double m = 3.0, k = 2e6;
    for (double kxy : {1e2, 1e4, 2e5}) {
        CAPTURE(kxy);
        const GrowthRateBound b = growth_rate_bound(isotropic(m, k, 0.0, kxy), {0.0});
        REQUIRE(b.holds);
        // The bound's own terms: ||L^-1 K_k L^-T||_F = sqrt(2) kxy / m (Frobenius, not the 2-norm kxy / m).
        const double expected = std::sqrt(2.0) * kxy / m / (2.0 * std::sqrt(k / m));
        CHECK(std::abs(b.rate - expected) <= 16 * eps * expected);
        const double exact = largest_real_part(m, 0.0, cd(k, -kxy));
        CHECK(exact <= b.rate);
        // Undamped: Re lambda = kxy / (2 sqrt(k m)) (1 + O((kxy/k)^2)); the Frobenius norm costs sqrt(2).
        const double first_order = kxy / (2.0 * std::sqrt(k * m));
        CHECK(std::abs(exact - first_order) <= first_order * (kxy / k) * (kxy / k));
        CHECK(b.rate <= std::sqrt(2.0) * first_order * (1.0 + 8 * eps));
    }
}

TEST_CASE("energy bound: negative damping -c bounds Re lambda = c / (2 m) by c / m", "[energy_bound]") {
    const double m = 3.0, k = 2e6, c = 50.0;
    const GrowthRateBound b = growth_rate_bound(isotropic(m, k, -c, 0.0), {0.0, 10.0});
    REQUIRE(b.holds);
    CHECK(std::abs(b.rate - c / m) <= 16 * eps * c / m);
    const double exact = largest_real_part(m, -c, cd(k, 0.0));
    CHECK(std::abs(exact - c / (2.0 * m)) <= 8 * eps * c / m);
    CHECK(exact <= b.rate);
}

TEST_CASE("energy bound: symmetric stiffness and dissipating damping, no mode of an FE rotor grows at any speed",
          "[energy_bound]") {
    for (const char* name : {"three_disk_rotor.toml", "fe_rotor.toml"}) {
        CAPTURE(name);
        const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/" + name);
        const std::vector<double> speeds = SpeedRange{0.0, 1600.0, 5}.points();
        const GrowthRateBound b = growth_rate_bound(sc.system, speeds);
        if (!sc.system.bearings.empty()) {   // fe_rotor: bearing tables with cross-coupled stiffness
            REQUIRE(b.holds);
            CHECK(b.rate > 1.0);   // says little: the full solve judges these
            continue;
        }
        REQUIRE(b.holds);
        // Only the rounding allowance: far below any decay the modes have (log dec 1e-6 above 1 kHz).
        CHECK(b.rate < 1e-3);
        // Every eigenvalue of every speed, solved in full, lies left of rate + its error bound.
        for (double w : speeds) {
            const QuadraticSpectrum s = solve_at_speed(sc.system, w);
            for (const Mode& md : s.modes) CHECK(md.lambda.real() <= b.rate + md.error_bound);
        }
    }
}

TEST_CASE("energy bound: a free rotor, a massless DOF and a huge model are no cases for it", "[energy_bound]") {
    const GrowthRateBound free = growth_rate_bound(isotropic(3.0, 0.0, 1.0, 0.0), {0.0});
    CHECK_FALSE(free.holds);
    CHECK(free.reason.find("stiffness is not positive definite at 0 rad/s") != std::string::npos);
    GyroscopicSystem massless = isotropic(3.0, 2e6, 1.0, 0.0);
    massless.M = Eigen::Vector2d(3.0, 0.0).asDiagonal();
    const GrowthRateBound b = growth_rate_bound(massless, {0.0});
    CHECK_FALSE(b.holds);
    CHECK(b.reason.find("mass matrix is not positive definite") != std::string::npos);
    CHECK_FALSE(growth_rate_bound(isotropic(3.0, 2e6, 1.0, 0.0), {}).holds);
}

namespace {

// Two rotors on one frame, uncoupled: a slow one (w_n = 50 rad/s, damped) and a stiff
// one (w_n = 5000 rad/s, far above the band of speeds up to 100 rad/s) with damping
// c_high and a cross-coupled stiffness kxy that makes it unstable where
// kxy / (2 sqrt(k m)) > c / (2 m) (at every speed: nothing here depends on speed).
Scene two_rotors(double c_high, double kxy, double kxy_per_speed = 0.0) {
    Scene sc;
    GyroscopicSystem& g = sc.system;
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(4, 4), K = Eigen::MatrixXd::Zero(4, 4);
    K.topLeftCorner(2, 2) = 2500.0 * Eigen::Matrix2d::Identity();
    K.bottomRightCorner(2, 2) = 2.5e7 * Eigen::Matrix2d::Identity() + kxy * J;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(4, 4);
    D.topLeftCorner(2, 2) = 10.0 * Eigen::Matrix2d::Identity();
    D.bottomRightCorner(2, 2) = c_high * Eigen::Matrix2d::Identity();
    g.M = M;
    g.K = K;
    g.damping.push_back({"d", D});
    if (kxy_per_speed != 0.0) {   // a cross-coupling growing with speed (K + w N): an onset inside the range
        Eigen::MatrixXd N = Eigen::MatrixXd::Zero(4, 4);
        N.bottomRightCorner(2, 2) = kxy_per_speed * J;
        g.N = N;
    }
    g.dofs.names = {"x1", "y1", "x2", "y2"};
    g.whirl_pairs = {{0, 1}, {2, 3}};
    return sc;
}

Sweep two_rotor_sweep(const std::string& varied, const std::vector<double>& values) {
    Sweep s;
    s.path = "two rotors";
    s.loader = [](const std::map<std::string, double>& o) {
        const auto get = [&](const std::string& k, double d) { return o.count(k) ? o.at(k) : d; };
        return two_rotors(get("model.c_high", 100.0), get("model.kxy", 0.0), get("model.kxy_per_speed", 0.0));
    };
    SweepParameter p;
    p.name = varied;
    p.values = values;
    s.parameters = {p};
    s.criteria.stability = StabilityCriterion{100.0, 21, std::nullopt};
    finalize_sweep(s);
    return s;
}

}  // namespace

TEST_CASE("screening stability: a mode far above the band that grows is caught, by the bound or by full solves",
          "[energy_bound][screening][stability]") {
    // kxy = 1e6 on the stiff rotor: Re lambda = kxy / (2 sqrt(k m)) - c / 2 = 100 - 50 > 0 (unstable);
    // kxy = 0: every mode decays, and the bound says so without solving the stiff rotor's modes.
    const Sweep s = two_rotor_sweep("model.kxy", {0.0, 1e6});
    const DesignResult stable = evaluate_design(s, 0), unstable = evaluate_design(s, 1);
    CHECK(stable.verdict == Verdict::Pass);
    CHECK(unstable.verdict == Verdict::Fail);
    CHECK(unstable.failed == std::vector<std::string>{"stability"});
    CHECK(unstable.reason.find("is unstable from 0 rad/s") != std::string::npos);
    // Negative damping on the stiff rotor (a destabilising seal, an active bearing gone wrong).
    const Sweep neg = two_rotor_sweep("model.c_high", {100.0, -1.0});
    CHECK(evaluate_design(neg, 0).verdict == Verdict::Pass);
    const DesignResult r = evaluate_design(neg, 1);
    CHECK(r.verdict == Verdict::Fail);
    CHECK(r.reason.find("is unstable from 0 rad/s") != std::string::npos);
    // A cross-coupling kxy = a w on the stiff rotor: lambda = i nu is a root of
    // lambda^2 + c lambda + k - i kxy where nu^2 = k and c nu = kxy, so the onset is
    // w = c sqrt(k) / a = 100 * 5000 / 1e4 = 50 rad/s, between two grid speeds (5 rad/s apart):
    // found on the full spectra and bisected to 1e-9; the stability rule (Re lambda beyond
    // its bound, ~1e-8 1/s, rising by 1 1/s per rad/s) moves it by less than 1e-7 of it.
    const Sweep grow = two_rotor_sweep("model.kxy_per_speed", {1e4});
    const DesignResult g = evaluate_design(grow, 0);
    CHECK(g.verdict == Verdict::Fail);
    CHECK(g.reason.find("a mode above the range") != std::string::npos);
    REQUIRE(g.quantities.at(0));
    CHECK(*g.quantities[0] == Approx(50.0).epsilon(1e-7));
}
