// Two-roller auto-balancer: the paper's Tabellen 1-3, the synchronous angles,
// simulations of Bilder 7-10 and the damped slow-phase offsets.
#include <gyrokit/balancing/autobalancer.hpp>
#include <gyrokit/scene/balancer_scene.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/core/error.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <string>

using namespace gyrokit;

namespace {

constexpr double kPi = 3.14159265358979323846;
double deg(double r) { return r * 180.0 / kPi; }
std::string scene(const std::string& name) { return std::string(GYROKIT_DATA_DIR) + "/balancer_" + name + ".toml"; }

// Verdicts per speed range (Omega < omega_x, omega_x..omega_0, omega_0..omega_y, > omega_y),
// 1 = asymptotisch stabil, as printed in the paper.
using Verdicts = std::map<std::string, std::vector<int>>;

void check_table(const std::string& name, const Verdicts& expected) {
    const BalancerScene sc = load_balancer_scene(scene(name));
    const auto tab = state_stability_ranges(sc.params);
    REQUIRE(tab.size() == 4 * expected.size());
    for (std::size_t k = 0; k < tab.size(); ++k) {
        const auto& e = tab[k];
        INFO(name << " state " << e.state.label << " range " << e.range.name);
        REQUIRE(expected.count(e.state.label) == 1);
        const bool want = expected.at(e.state.label)[k % 4] == 1;
        CHECK(e.stable_criterion == want);
        CHECK(e.stable_eigen == want);
    }
}

}  // namespace

TEST_CASE("Tabelle 1: angles 139/263 and 221/97 and all verdicts", "[autobalancer]") {
    const BalancerScene sc = load_balancer_scene(scene("table1"));
    const auto states = synchronous_states(sc.params);
    REQUIRE(states.size() == 6);
    // The paper prints 2.42 (139 deg), 4.59 (263 deg), 3.86 (221 deg), 1.70 (97 deg).
    CHECK(states[0].label == "43");
    CHECK(states[0].alpha[0] == Approx(2.42).margin(0.005));
    CHECK(states[0].alpha[1] == Approx(4.59).margin(0.005));
    CHECK(deg(states[0].alpha[0]) == Approx(139).margin(0.5));
    CHECK(deg(states[0].alpha[1]) == Approx(263).margin(0.5));
    CHECK(states[1].label == "44");
    CHECK(states[1].alpha[0] == Approx(3.86).margin(0.005));
    CHECK(states[1].alpha[1] == Approx(1.70).margin(0.005));
    CHECK(deg(states[1].alpha[0]) == Approx(221).margin(0.5));
    CHECK(deg(states[1].alpha[1]) == Approx(97).margin(0.5));
    check_table("table1", {{"43", {0, 1, 0, 1}}, {"44", {0, 1, 0, 1}}, {"45", {1, 0, 1, 0}},
                           {"46", {0, 0, 0, 0}}, {"48", {0, 0, 0, 0}}, {"47", {0, 0, 0, 0}}});
}

TEST_CASE("Synchronous states satisfy the existence conditions (34)-(35) and compensate (36)-(37)", "[autobalancer]") {
    for (const char* name : {"table1", "table2", "table3"}) {
        const BalancerScene sc = load_balancer_scene(scene(name));
        const auto& p = sc.params;
        const double f0 = p.f_unbalance(0, 1), f1 = p.f_unbalance(1, 1), f2 = p.f_unbalance(2, 1);
        for (const auto& s : synchronous_states(p)) {
            CAPTURE(s);
            const double a1 = s.alpha[0], a2 = s.alpha[1];
            CHECK(std::fabs(f0 * std::sin(a1) + f2 * std::sin(a1 - a2)) < 1e-15 * 4 * f0);
            CHECK(std::fabs(f0 * std::sin(a2) - f1 * std::sin(a1 - a2)) < 1e-15 * 4 * f0);
            if (s.compensating) {
                CHECK(std::fabs(f1 * std::sin(a1) + f2 * std::sin(a2)) < 1e-15 * 4 * f0);
                CHECK(std::fabs(f0 + f1 * std::cos(a1) + f2 * std::cos(a2)) < 1e-15 * 4 * f0);
            }
        }
    }
}

TEST_CASE("Tabelle 2: f0 > f1 + f2, (pi, pi) reduces the unbalance as far as possible", "[autobalancer]") {
    check_table("table2", {{"45", {1, 0, 1, 0}}, {"46", {0, 1, 0, 1}}, {"48", {0, 0, 0, 0}}, {"47", {0, 0, 0, 0}}});
}

TEST_CASE("Tabelle 3: the printed rows (pi, 0) and (0, pi) are interchanged", "[autobalancer]") {
    // As printed: (pi, 0) never stable, (0, pi) stable where A_xx + A_yy < 0. Eq. (67)-(70) with the
    // indices exchanged, and the caption of Bild 10, give the opposite: f1 > f0 + f2 makes (48) stable.
    const Verdicts corrected{{"45", {1, 0, 1, 0}}, {"46", {0, 0, 0, 0}}, {"48", {0, 1, 0, 1}}, {"47", {0, 0, 0, 0}}};
    check_table("table3", corrected);
    const Verdicts printed{{"45", {1, 0, 1, 0}}, {"46", {0, 0, 0, 0}}, {"48", {0, 0, 0, 0}}, {"47", {0, 1, 0, 1}}};
    const BalancerScene sc = load_balancer_scene(scene("table3"));
    const auto ranges = speed_intervals(sc.params);
    int disagreements = 0;
    for (const auto& e : state_stability_ranges(sc.params)) {
        CAPTURE(e);
        std::size_t idx = 0;
        while (ranges[idx].name != e.range.name) ++idx;
        if (e.stable_criterion != (printed.at(e.state.label)[idx] == 1)) ++disagreements;
    }
    CHECK(disagreements == 4);   // exactly the two swapped rows in the two ranges where A_xx + A_yy < 0
}

TEST_CASE("Rotor without rollers: the simulated orbit matches the damped closed form", "[autobalancer]") {
    AutobalancerParameters p;
    p.m = 1.0;
    p.m0 = 0.002;
    p.eps0 = 0.05;
    p.k_x = 4000.0;
    p.k_y = 15000.0;
    p.c_x = p.c_y = 5.0;
    p.speed = 80.0;
    SimulationSettings s;
    s.duration = 6.0;   // free vibration decays as exp(-c/(2M) t) = exp(-15)
    const SimulationResult r = simulate(p, s);
    const double M = p.M(), W = p.speed, f0 = p.m0 * p.eps0 * W * W;
    const double ax = f0 / std::hypot(p.k_x - M * W * W, p.c_x * W), ay = f0 / std::hypot(p.k_y - M * W * W, p.c_y * W);
    CHECK(r.residual_rms == Approx(std::sqrt(0.5 * (ax * ax + ay * ay))).epsilon(1e-5));
    // Sampled at 16 points per revolution: |r|^2 has period pi/Omega, so the sampled peak can miss
    // by (1 - cos(pi/8)) / 2 in |r|^2, i.e. about 2 % in |r|.
    CHECK(r.residual_max == Approx(std::max(ax, ay)).epsilon(0.02));
}

TEST_CASE("Damped slow-phase model: compensating states are exact, the others move off", "[autobalancer]") {
    const BalancerScene sc = load_balancer_scene(scene("table1"));
    for (const auto& s : synchronous_states(sc.params)) {
        CAPTURE(s);
        const auto a = damped_equilibrium(sc.params, 80.0, s.alpha);
        const double d = std::max(phase_distance(a[0], s.alpha[0]), phase_distance(a[1], s.alpha[1]));
        if (s.compensating) CHECK(d < 1e-12);
        else CHECK(d > 1e-3);
    }
    // Without bearing damping the states are (43)-(48) themselves.
    AutobalancerParameters p = sc.params;
    p.c_x = p.c_y = 0.0;
    for (const auto& s : synchronous_states(p)) {
        CAPTURE(s);
        const auto a = damped_equilibrium(p, 40.0, s.alpha);
        CHECK(std::max(phase_distance(a[0], s.alpha[0]), phase_distance(a[1], s.alpha[1])) < 1e-12);
    }
}

TEST_CASE("Simulations of Bilder 7-10 settle in the predicted stable states", "[autobalancer][simulation]") {
    struct Case {
        const char* name;
        const char* state;
    };
    for (const Case c : {Case{"bild7", "45"}, Case{"bild8", "43"}, Case{"bild9", "44"}, Case{"bild10", "48"}}) {
        INFO(c.name);
        const BalancerScene sc = load_balancer_scene(scene(c.name));
        const SimulationResult r = simulate(sc.params, sc.simulation);
        const double W = sc.params.speed;
        std::vector<double> target;
        bool compensating = false;
        for (const auto& s : synchronous_states(sc.params))
            if (s.label == c.state) {
                target = damped_equilibrium(sc.params, W, s.alpha);
                compensating = s.compensating;
                REQUIRE(stable_by_eigenvalues(slow_eigenvalues(sc.params, W, target, true)));
            }
        REQUIRE(target.size() == 2);
        // The averaging neglects terms of the order of the fast phase oscillation (below 1e-3 deg here);
        // 0.01 deg separates the damped offsets (0.2 to 5 deg) clearly.
        CHECK(deg(phase_distance(r.final_alpha[0], target[0])) < 0.01);
        CHECK(deg(phase_distance(r.final_alpha[1], target[1])) < 0.01);
        const double uncompensated = sc.params.f_unbalance(0, W) * std::abs(influence_sum(sc.params, W, true));
        if (compensating) CHECK(r.residual_rms < 1e-3 * uncompensated);
        else CHECK(r.residual_rms > 0.1 * uncompensated);
    }
}

TEST_CASE("Bild 7: the damped offset of state (45) is predicted by the slow model", "[autobalancer][simulation]") {
    const BalancerScene sc = load_balancer_scene(scene("bild7"));
    const auto a = damped_equilibrium(sc.params, 40.0, {0.0, 0.0});
    const double offset = deg(phase_distance(a[0], 0.0));
    CHECK(offset > 1.0);   // several degrees at 40 rad/s with c = 2 N s/m
    SimulationSettings s = sc.simulation;
    const SimulationResult r = simulate(sc.params, s);
    CHECK(deg(phase_distance(r.final_alpha[0], 0.0)) == Approx(offset).margin(0.01));
    // The averaged equations land on the same state.
    const SimulationResult ra = simulate_averaged(sc.params, s);
    CHECK(deg(phase_distance(ra.final_alpha[0], a[0])) < 0.01);
}

TEST_CASE("Long run: thousands of revolutions keep the compensating state", "[autobalancer][simulation]") {
    BalancerScene sc = load_balancer_scene(scene("bild9"));
    SimulationSettings s = sc.simulation;
    s.duration = 63.0;   // about 3000 revolutions at 300 rad/s
    const SimulationResult r = simulate(sc.params, s);
    CHECK(r.revolutions > 3000);
    const auto st = synchronous_states(sc.params);
    CHECK(deg(phase_distance(r.final_alpha[0], st[1].alpha[0])) < 1e-4);
    CHECK(deg(phase_distance(r.final_alpha[1], st[1].alpha[1])) < 1e-4);
    CHECK(r.stats.seconds < 5.0);
}

TEST_CASE("Motor drive turns at about L0/beta0 and the rollers compensate", "[autobalancer][simulation]") {
    BalancerScene sc = load_balancer_scene(scene("bild9"));
    AutobalancerParameters p = sc.params;
    p.drive = Drive::Motor;
    p.beta0 = 0.01;
    p.L0 = 300.0 * p.beta0;
    SimulationSettings s = sc.simulation;
    s.alpha = {220.0 * kPi / 180, 100.0 * kPi / 180};
    s.duration = 15.0;
    const SimulationResult r = simulate(p, s);
    // Synchronous rollers: beta0 w - sum beta_i w = L0, eq. (18) averaged with x = y = 0.
    CHECK(r.final_speed == Approx(p.L0 / (p.beta0 - 2 * 3e-5)).epsilon(1e-6));
    CHECK(deg(phase_distance(r.final_alpha[0], synchronous_states(p)[1].alpha[0])) < 0.01);
}

TEST_CASE("A failing integration names the time and the reason", "[autobalancer][simulation]") {
    BalancerScene sc = load_balancer_scene(scene("bild9"));
    SimulationSettings s = sc.simulation;
    s.ode.max_steps = 1000;
    s.duration = 5.0;
    try {
        simulate(sc.params, s);
        FAIL("expected a SolverError");
    } catch (const SolverError& e) {
        const std::string m = e.what();
        CHECK(m.find("t = ") != std::string::npos);
        CHECK(m.find("step limit") != std::string::npos);
    }
    CHECK_THROWS_AS(parse_ode_method("euler"), InputError);
}

TEST_CASE("Scene errors are one-line InputErrors", "[autobalancer]") {
    const std::string f = "/tmp/gyrokit_balancer_bad.toml";
    auto write = [&](const std::string& body) { std::ofstream(f) << body; };
    const std::string base = "[model]\ntype = \"autobalancer\"\nm = 1.0\nm0 = 0.002\neps0 = 0.05\nomega_x = 62.5\n"
                             "omega_y = 125.1\nm1 = 0.002\neps1 = 0.05\nR1 = 0.055\nmu1 = 0.4\nbeta1 = 3e-5\n";
    write(base + "speed = 100.0\n");
    CHECK_NOTHROW(load_balancer_scene(f));
    for (const std::string bad : {"speed = -1.0\n", "speed = 100.0\nm2 = -0.1\n", "speed = 100.0\nfoo = 1\n",
                                  "L0 = 1.0\nbeta0 = 0.0\n"}) {
        write(base + bad);
        try {
            load_balancer_scene(f);
            FAIL("expected InputError for " << bad);
        } catch (const InputError& e) {
            CHECK(std::string(e.what()).find('\n') == std::string::npos);
        }
    }
    write("[model]\ntype = \"autobalancer\"\nm = 1.0\nm0 = 0.002\neps0 = 0.05\nomega_x = 62.5\nomega_y = 125.1\n"
          "m1 = 0.002\neps1 = 0.05\nR1 = 0.05\nmu1 = 0.4\nbeta1 = 3e-5\nspeed = 100.0\n");
    CHECK_THROWS_WITH(load_balancer_scene(f), Catch::Contains("R1"));
}

TEST_CASE("Range verdicts: Tabelle 1 balances above omega_x and above omega_y, Tabelle 2 nowhere",
          "[autobalancer]") {
    const auto v1 = range_verdicts(state_stability_ranges(load_balancer_scene(scene("table1")).params));
    REQUIRE(v1.size() == 4);
    const std::vector<std::vector<std::string>> comp{{}, {"43", "44"}, {}, {"43", "44"}}, other{{"45"}, {}, {"45"}, {}};
    for (std::size_t k = 0; k < 4; ++k) {
        CAPTURE(k);
        CHECK(v1[k].compensating == comp[k]);
        CHECK(v1[k].other == other[k]);
        CHECK(v1[k].disputed.empty());
    }
    for (const auto& v : range_verdicts(state_stability_ranges(load_balancer_scene(scene("table2")).params)))
        CHECK(v.compensating.empty());
    // A state whose criterion and eigenvalues disagree is neither stable nor unstable.
    StateStability a, b;
    a.state.label = "x", a.state.compensating = true, a.range.name = "r", a.stable_criterion = true;
    b.state.label = "y", b.range.name = "r", b.stable_criterion = b.stable_eigen = true;
    const auto v = range_verdicts({a, b});
    REQUIRE(v.size() == 1);
    CHECK(v[0].compensating.empty());
    CHECK(v[0].other == std::vector<std::string>{"y"});
    CHECK(v[0].disputed == std::vector<std::string>{"x"});
}
