// Sommerfeld effect of the motor-driven auto-balancer: Tabelle 1 of the paper
// (critical speeds and limit speed estimates that follow from the listed
// parameters), exact folds of the stationary curves against an independent scan
// of eqs. (16)/(25)/(36)/(42), and run-ups below and above the limit speed.
#include <gyrokit/scene/balancer_scene.hpp>
#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/sommerfeld.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/core/error.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

using namespace gyrokit;

namespace {

constexpr double kPi = 3.14159265358979323846;
std::string scene(const std::string& name) { return std::string(GYROKIT_DATA_DIR) + "/sommerfeld_" + name + ".toml"; }

// Tabelle 1 prints one decimal: half a unit of the last digit.
constexpr double kTable = 0.05;

// Eq. (15)/(23) written out from the paper, independent of the library.
double V(double U, double w, double M, double k, double c) {
    const double wk2 = k / M;
    return U * U * c * std::pow(w, 5) / (M * M * std::pow(wk2 - w * w, 2) + c * c * w * w);
}

// Omega(p) from (16) (no rollers), (25)/(36) (rollers), (42) (rollers and unbalance).
double nominal(const AutobalancerParameters& p, double q) {
    const double M = p.M(), k = p.k_x, c = p.c_x, U0 = p.m0 * p.eps0;
    if (p.rollers.empty()) return q + V(U0, q, M, k, c) / p.beta0;
    const double n = static_cast<double>(p.rollers.size()), Ue = p.rollers[0].m * p.rollers[0].eps;
    const double be = p.rollers[0].beta;
    const double w0 = q + n * V(Ue, q, M, k, c) / be;   // (24)/(36)
    return w0 + (V(U0, w0, M, k, c) - n * be * q) / p.beta0;   // (22)/(42)
}

// Local maximum of Omega near the resonance by a scan with step h (independent of the library's search).
double scanned_jump_up(const AutobalancerParameters& p, double wk, double h) {
    double best = 0.0;
    for (double q = 0.8 * wk; q < 1.2 * wk; q += h) best = std::max(best, nominal(p, q));
    return best;
}

std::string write_scene(const std::string& name, const std::string& text) {
    const std::string path = std::string("sommerfeld_test_") + name + ".toml";
    std::ofstream(path) << text;
    return path;
}

const char* kBase = R"([model]
type = "autobalancer"
m = 1.0
J = 0.0054
m0 = 0.05
eps0 = 0.065
L0 = 2.5
beta0 = 0.005
)";

}  // namespace

TEST_CASE("Tabelle 1: critical speeds that follow from the listed masses", "[sommerfeld]") {
    CHECK(sommerfeld_system(load_balancer_scene(scene("rotor")).params).omega_krit == Approx(122.8).margin(kTable));
    CHECK(sommerfeld_system(load_balancer_scene(scene("two_rollers")).params).omega_krit ==
          Approx(125.5).margin(kTable));
    CHECK(sommerfeld_system(load_balancer_scene(scene("two_rollers_unbalance")).params).omega_krit ==
          Approx(125.2).margin(kTable));
    // One roller: M = 1.0025 kg gives 125.66; the table's column value 125.5 belongs to two rollers.
    CHECK(sommerfeld_system(load_balancer_scene(scene("one_roller")).params).omega_krit ==
          Approx(std::sqrt(15830.0 / 1.0025)).epsilon(1e-12));
}

TEST_CASE("Tabelle 1: limit speed estimates (17) and (43)", "[sommerfeld]") {
    CHECK(limit_speed_estimate(sommerfeld_system(load_balancer_scene(scene("rotor")).params)) ==
          Approx(383.5).margin(kTable));
    AutobalancerParameters two = load_balancer_scene(scene("two_rollers")).params;
    CHECK(limit_speed_estimate(sommerfeld_system(two)) == Approx(403.9).margin(kTable));
    two.c_x = two.c_y = 10.0;
    CHECK(limit_speed_estimate(sommerfeld_system(two)) == Approx(543.1).margin(kTable));
}

TEST_CASE("Tabelle 1: values that do not follow from the listed parameters", "[sommerfeld]") {
    // One roller, (26) with m1 = 0.0025 kg, M = 1.0025 kg: 265.4 rad/s, not the table's 403.9.
    const AutobalancerParameters one = load_balancer_scene(scene("one_roller")).params;
    const double wk1 = std::sqrt(15830.0 / 1.0025), U1 = 0.0025 * 0.065;
    const double est1 = limit_speed_estimate(sommerfeld_system(one));
    CHECK(est1 == Approx(wk1 * (1.0 + U1 * U1 * wk1 * wk1 / (2.5e-5 * 15.0))).epsilon(1e-12));
    CHECK(est1 == Approx(265.4).margin(kTable));
    CHECK(std::fabs(est1 - 403.9) > 100.0);
    // Section 3.4, M = 1.01 kg: 401.5 (c = 15), 263.4 (one roller following, factor 2 dropped), 539.7 (c = 10);
    // the table lists 383.3, 251.9 and 510.8.
    AutobalancerParameters ub = load_balancer_scene(scene("two_rollers_unbalance")).params;
    const SommerfeldSystem s = sommerfeld_system(ub);
    CHECK(limit_speed_estimate(s) == Approx(401.5).margin(kTable));
    SommerfeldSystem single = s;
    single.n = 1;
    CHECK(limit_speed_estimate(single) == Approx(263.4).margin(kTable));
    ub.c_x = ub.c_y = 10.0;
    CHECK(limit_speed_estimate(sommerfeld_system(ub)) == Approx(539.7).margin(kTable));
}

TEST_CASE("Exact folds: local maximum of Omega(omega), slightly above the estimates", "[sommerfeld]") {
    for (const char* name : {"rotor", "one_roller", "two_rollers", "two_rollers_unbalance"}) {
        INFO(name);
        const AutobalancerParameters p = load_balancer_scene(scene(name)).params;
        const SommerfeldAnalysis a = analyse_sommerfeld(p);
        REQUIRE(a.has_jump);
        // The scan's error is second order in its step (1e-3 rad/s at a curvature of order 1 / (rad/s)).
        const double scan = scanned_jump_up(p, a.system.omega_krit, 1e-3);
        CHECK(a.jump_up.point.nominal == Approx(scan).epsilon(1e-6));
        CHECK(nominal(p, a.jump_up.p) == Approx(a.jump_up.point.nominal).epsilon(1e-12));
        // The estimates put omega = omega_krit into (16): slightly low, by well under 1 %.
        CHECK(a.estimate < a.jump_up.point.nominal);
        CHECK(a.jump_up.point.nominal < 1.01 * a.estimate);
        // The hanging speed at the fold lies just above omega_krit.
        CHECK(a.jump_up.p > a.system.omega_krit);
        CHECK(a.jump_up.p < 1.02 * a.system.omega_krit);
        // Three non-synchronous states between the folds, one outside.
        auto curve_states = [&](double W) {
            int n = 0;
            for (const auto& q : stationary_states(a, W)) n += q.branch != "synchronous";
            return n;
        };
        const double up = a.jump_up.point.nominal, down = a.jump_down.point.nominal;
        REQUIRE(down < up);
        CHECK(curve_states(0.999 * down) == 1);
        CHECK(curve_states(1.001 * down) == 3);
        CHECK(curve_states(0.999 * up) == 3);
        CHECK(curve_states(1.001 * up) == 1);
    }
}

TEST_CASE("Stationary states solve (16) and (36)/(37), middle branch unstable", "[sommerfeld]") {
    const AutobalancerParameters p = load_balancer_scene(scene("rotor")).params;
    const SommerfeldAnalysis a = analyse_sommerfeld(p);
    const auto st = stationary_states(a, 300.0);
    REQUIRE(st.size() == 3);
    for (const auto& q : st) {
        CAPTURE(q);
        CHECK(nominal(p, q.rotor_speed) == Approx(300.0).epsilon(1e-10));
    }
    CHECK(st[0].branch == "resonance");
    CHECK(st[0].stable);
    CHECK(st[1].branch == "unstable");
    CHECK_FALSE(st[1].stable);
    CHECK(st[2].branch == "upper");
    CHECK(st[2].stable);

    const AutobalancerParameters two = load_balancer_scene(scene("two_rollers")).params;
    const SommerfeldAnalysis b = analyse_sommerfeld(two);
    const auto s2 = stationary_states(b, 500.0);
    REQUIRE(s2.size() == 2);
    // The non-synchronous upper state (phase difference 0) is phase-unstable above omega_krit.
    CHECK(s2[0].branch == "upper");
    CHECK_FALSE(s2[0].stable);
    CHECK(s2[1].branch == "synchronous");
    CHECK(s2[1].stable);
    CHECK(s2[1].rotor_speed == Approx(0.005 * 500.0 / (0.005 - 2 * 2.5e-5)).epsilon(1e-14));   // (37)
    // Large Omega: (27) omega_e ~ omega0 / (1 + m_e^2 G_e / M^2) with the factor 2 of (36).
    const double G = 0.065 * 0.065 * 15.0 / 2.5e-5, m = 0.0025, M = two.M();
    const auto far = stationary_states(b, 5000.0);
    CHECK(far[0].roller_speed / far[0].rotor_speed == Approx(1.0 / (1.0 + 2.0 * m * m * G / (M * M))).epsilon(2e-3));
}

TEST_CASE("Run-up profile: sinusoidal rise, hold, fall, and the angle integrates the speed", "[sommerfeld]") {
    RunupSettings s;
    s.max_speed = 400.0;
    s.rise = 4.0;
    s.hold = 2.0;
    s.fall = 3.0;
    CHECK(runup_nominal_speed(s, 0.0) == 0.0);
    CHECK(runup_nominal_speed(s, 2.0) == Approx(200.0));
    CHECK(runup_nominal_speed(s, 5.0) == Approx(400.0));
    CHECK(runup_nominal_speed(s, 7.5) == Approx(200.0));
    CHECK(runup_nominal_speed(s, 10.0) == 0.0);
    for (double t : {1.0, 3.9, 4.5, 6.2, 8.0}) {
        CAPTURE(t);
        const double h = 1e-5;
        CHECK((runup_nominal_angle(s, t + h) - runup_nominal_angle(s, t - h)) / (2 * h) ==
              Approx(runup_nominal_speed(s, t)).epsilon(1e-7));
    }
    CHECK(runup_nominal_angle(s, 20.0) == Approx(400.0 * (2.0 + 2.0 + 1.5)).epsilon(1e-14));
}

TEST_CASE("Run-ups: capture below and passage above the limit speed", "[sommerfeld]") {
    struct Case {
        const char* name;
        double low, high;   // max_speed below the jump-up speed (but above omega_krit) and above it
    };
    for (const Case& c : {Case{"rotor", 300.0, 500.0}, Case{"one_roller", 230.0, 500.0},
                          Case{"two_rollers", 300.0, 500.0}, Case{"two_rollers_unbalance", 300.0, 500.0}}) {
        INFO(c.name);
        const BalancerScene sc = load_balancer_scene(scene(c.name));
        const bool rollers = !sc.params.rollers.empty();
        for (double W : {c.low, c.high}) {
            INFO("max_speed " << W);
            RunupSettings s = sc.runup;
            s.max_speed = W;
            s.fall = 0.0;
            const RunupResult r = simulate_runup(sc.params, s);
            const RunupSummary sm = summarize_runup(sc.params, r);
            CHECK(sm.captured == (W == c.low));
            // After 7.5 s of hold (rotor time constant J00 / beta0 ~ 1.1 s) the transient is below 1e-3.
            CHECK(r.held_rotor_speed == Approx(sm.stationary_rotor_speed).epsilon(1e-3));
            if (rollers) CHECK(r.held_roller_speed == Approx(sm.stationary_roller_speed).epsilon(1e-3));
            const double hanging = rollers ? r.held_roller_speed : r.held_rotor_speed;
            if (W == c.low) {
                CHECK(hanging < 1.02 * sm.omega_krit);
                CHECK(r.held_amplitude > 1e-3);
            } else {
                CHECK(hanging > 0.95 * W);
            }
            if (std::string(c.name) == "two_rollers" && W == c.high) {
                // Passage: the rollers reach the opposed phase and the vibration vanishes.
                CHECK(r.held_phase_difference == Approx(kPi).margin(1e-2));
                CHECK(r.held_amplitude < 1e-6);
            }
            if (std::string(c.name) == "two_rollers_unbalance" && W == c.high) {
                // m0 eps0 = 2 m_e eps_e: both rollers opposite the unbalance.
                CHECK(phase_distance(r.held_alpha[0], kPi) < 2e-2);
                CHECK(phase_distance(r.held_alpha[1], kPi) < 2e-2);
                CHECK(r.held_amplitude < 1e-6);
            }
        }
    }
}

TEST_CASE("Scene keys k, c and the [runup] table", "[sommerfeld]") {
    const BalancerScene sc = load_balancer_scene(scene("two_rollers"));
    CHECK(sc.params.k_x == 15830.0);
    CHECK(sc.params.k_y == 15830.0);
    CHECK(sc.params.c_x == 15.0);
    CHECK(sc.params.c_y == 15.0);
    REQUIRE(sc.has_runup);
    CHECK(sc.runup.max_speed == 500.0);
    CHECK(sc.runup.alpha[0] == Approx(179.0 * kPi / 180.0));

    const std::string good = std::string(kBase) + "k = 15830.0\nc = 15.0\n";
    CHECK(load_balancer_scene(write_scene("good", good)).params.k_y == 15830.0);
    CHECK_THROWS_AS(load_balancer_scene(write_scene("both_k", good + "k_x = 1.0\n")), InputError);
    CHECK_THROWS_AS(load_balancer_scene(write_scene("both_c", good + "c_x = 1.0\n")), InputError);
    CHECK_THROWS_AS(load_balancer_scene(write_scene("runup_key", good + "[runup]\nmax_speed = 1.0\nrise = 1.0\n"
                                                                      "hold = 1.0\nspeed = 3.0\n")),
                    InputError);
    CHECK_THROWS_AS(load_balancer_scene(write_scene("runup_neg", good + "[runup]\nmax_speed = -1.0\nrise = 1.0\n"
                                                                      "hold = 1.0\n")),
                    InputError);
    // Anisotropic bearings are rejected by the stationary analysis.
    AutobalancerParameters p = load_balancer_scene(write_scene("good2", good)).params;
    p.k_y = 2.0 * p.k_x;
    CHECK_THROWS_AS(sommerfeld_system(p), InputError);
    for (const char* n : {"good", "both_k", "both_c", "runup_key", "runup_neg", "good2"})
        std::remove(("sommerfeld_test_" + std::string(n) + ".toml").c_str());
}
