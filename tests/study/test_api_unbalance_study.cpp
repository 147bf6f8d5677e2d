// The API unbalance cases of data/three_disk_rotor.toml (constant bearings) and of
// data/three_disk_rotor_journal.toml (plain journal bearings), against independent
// computations: W against the rotor's mass from its geometry; the response at the
// largest probe orbit by an LU of the dynamic stiffness from the exported pencil, the
// orbit's peak-to-peak by sampling the ellipse; the refined peak against a finer grid;
// the half-power AF against a search of our own; the margins, Scc and the clearance
// ratios from API 617's formulas by hand; bad [api] data refused with its key.
#include <gyrokit/core/constants.hpp>
#include <gyrokit/gyrokit.hpp>

#include "api_checks.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>

using namespace gyrokit;
using namespace gyrokit::test;

namespace {

std::string data_text(const std::string& name) {
    std::ifstream in(std::string(GYROKIT_DATA_DIR) + "/" + name);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("API unbalance cases of the three-disk rotor: W, U, the response and the rules by hand",
          "[api_unbalance]") {
    const Scene sc = parse_scene(data_text("three_disk_rotor.toml"), "three_disk_rotor.toml", GYROKIT_DATA_DIR);
    const ApiUnbalanceStudy s = api_unbalance_study(sc);
    const GyroscopicSystem& sys = sc.system;
    CHECK(s.mcs == Approx(rpm(10000)).epsilon(1e-12));
    CHECK(s.min_speed == Approx(rpm(7000)).epsilon(1e-12));
    CHECK(s.trip_speed == Approx(rpm(10500)).epsilon(1e-12));
    CHECK(s.search_to == Approx(rpm(1.25 * 10500)).epsilon(1e-12));   // above 1.26 mcs
    // Two probes (the bearings) and the five seals of [[api.clearance]].
    REQUIRE(s.locations.size() == 7);
    CHECK(s.locations[0].probe);
    CHECK(s.locations[1].probe);
    CHECK(s.locations[4].name == "eye seal, middle impeller");
    CHECK(s.locations[4].clearance == Approx(0.4e-3).epsilon(1e-12));
    REQUIRE(!s.cases.empty());

    // The first case: the first mode, at mid-span, W the journals' loads: the rotor's weight.
    const ApiUnbalanceCase& c = s.cases.front();
    CHECK(c.placement.layout == UnbalanceLayout::first_mode);
    REQUIRE(c.loads.size() == 1);
    CHECK(c.loads[0].z == Approx(0.6).margin(1e-12));
    const double rho = 7810, q = kPi / 4;
    const double shaft = rho * q * (2 * 0.06 * 0.06 * 0.1 + 2 * 0.09 * 0.09 * 0.25 + 0.1 * 0.1 * 0.5);
    const double disks = rho * q * (2 * (0.32 * 0.32 - 0.01) * 0.05 + (0.4 * 0.4 - 0.01) * 0.07);
    CHECK(c.loads[0].weight == Approx(shaft + disks).epsilon(1e-9));
    CHECK(c.loads[0].unbalance == Approx(2 * 6350 * (shaft + disks) / 10000 * 1e-6).epsilon(1e-9));
    // Every critical speed of the case below the trip speed's reach, each case's rules by hand.
    for (const ApiUnbalanceCase& k : s.cases) check_rules(s, k);

    // The largest probe orbit against an LU of our own and a sampled ellipse; no larger
    // orbit on a finer grid around it (the peak is refined, not read off the grid).
    const Eigen::VectorXcd u = unbalance_of(sys, c);
    // The first probe (the rotor is symmetric: both read alike up to rounding).
    const ApiLocation& probe = s.locations[0];
    const ApiAmplitude& a = c.amplitudes[0];
    // A1: the probes' largest orbit within 10 % of the critical speed of concern (every margin
    // met: the crossing of the largest AF), against a fine grid of our own there.
    double af = 0.0, concern = 0.0;
    for (const ApiCritical& k : c.criticals)
        if (k.critical.amplification > af) af = k.critical.amplification, concern = k.critical.speed;
    CHECK(c.concern == concern);
    double grid = 0.0;
    for (int k = -100; k <= 100; ++k)
        for (std::size_t p = 0; p < 2; ++p)
            grid = std::max(grid, pp_at(sys, u, s.locations[p], concern * (1.0 + 1e-3 * k)));
    CHECK(c.a1 >= grid * (1 - 1e-7));   // a refined peak is no lower than a grid's
    CHECK(c.a1 <= grid * (1 + 1e-3));   // and above it by the grid's step squared over the width squared
    CHECK(pp_at(sys, u, probe, a.speed) == Approx(a.peak_to_peak).epsilon(1e-7));
    for (int k = -20; k <= 20; ++k) {
        const double w = a.speed * (1.0 + 1e-3 * k);
        CHECK(pp_at(sys, u, probe, w) <= a.peak_to_peak * (1 + 1e-7));
    }
    // The middle eye seal's ratio by hand: margins met, unscaled, against 75 % of 0.4 mm.
    const ApiAmplitude& seal = c.amplitudes[4];
    CHECK(pp_at(sys, u, s.locations[4], seal.speed) == Approx(seal.peak_to_peak).epsilon(1e-7));
    CHECK(seal.ratio == Approx(seal.peak_to_peak / 0.3e-3).epsilon(1e-12));

    // The half-power AF of the forward crossing that has one, against our own search on
    // the case's response at the same DOF: the peak by golden section, the 0.707 points by
    // bisection.
    const ApiCritical* hp = nullptr;
    for (const ApiCritical& k : c.criticals)
        if (k.critical.amplification_method == AmplificationMethod::HalfPower) hp = &k;
    REQUIRE(hp != nullptr);
    const int dof = sys.dofs.find(hp->critical.amplification_dof);
    REQUIRE(dof >= 0);
    const auto amp = [&](double w) { return std::abs(response(sys, u, w)(dof)); };
    double lo = 0.8 * hp->critical.speed, hi = 1.2 * hp->critical.speed;
    const double g = (std::sqrt(5.0) - 1) / 2;
    for (int it = 0; it < 100; ++it) {
        const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        (amp(m1) < amp(m2) ? lo : hi) = amp(m1) < amp(m2) ? m1 : m2;
    }
    const double peak_w = 0.5 * (lo + hi), level = amp(peak_w) / std::sqrt(2.0);
    const auto half = [&](double a0, double b0) {
        for (int it = 0; it < 100; ++it) {
            const double m = 0.5 * (a0 + b0);
            ((amp(m) > level) == (amp(a0) > level) ? a0 : b0) = m;
        }
        return 0.5 * (a0 + b0);
    };
    const double w1 = half(0.5 * peak_w, peak_w), w2 = half(peak_w, 1.5 * peak_w);
    CHECK(hp->critical.amplification == Approx(peak_w / (w2 - w1)).epsilon(1e-4));
}

TEST_CASE("API unbalance cases of a rotor on plain journal bearings: the films' clearances, Scc where a margin "
          "is not met, and an unstable rotor refused a pass",
          "[api_unbalance]") {
    const std::string text = data_text("three_disk_rotor_journal.toml");
    const Scene sc = parse_scene(text, "three_disk_rotor_journal.toml", GYROKIT_DATA_DIR);
    ApiUnbalanceRequest r;
    r.speeds = 121;
    const ApiUnbalanceStudy s = api_unbalance_study(sc, r);
    // The films' diametral clearances, 2 c = 120 um, and the eye seal.
    REQUIRE(s.locations.size() == 5);
    CHECK(!s.locations[2].probe);
    CHECK(s.locations[2].clearance == Approx(120e-6).epsilon(1e-12));
    CHECK(s.locations[4].clearance == Approx(0.4e-3).epsilon(1e-12));
    CHECK(s.reasons.empty());   // the films whip only above the trip speed
    bool scaled = false;
    for (const ApiUnbalanceCase& c : s.cases) {
        check_rules(s, c);
        scaled = scaled || !c.margins_met;
        if (!c.margins_met) CHECK((c.verdict == ApiVerdict::pass_scaled || c.verdict == ApiVerdict::fail));
    }
    CHECK(scaled);   // a crossing inside 4500-6000 rpm with AF >= 2.5
    // One case's largest probe orbit by our own LU on the films' coefficients at that speed.
    const ApiUnbalanceCase& c = s.cases.back();
    const Eigen::VectorXcd u = unbalance_of(sc.system, c);
    CHECK(pp_at(sc.system, u, s.locations[0], c.amplitudes[0].speed) ==
          Approx(c.amplitudes[0].peak_to_peak).epsilon(1e-7));

    // Run to 10000 rpm, the films whip inside the range: no pass, and the reason says why.
    ApiUnbalanceRequest fast;
    fast.mcs = 10000;
    fast.min_speed = 7000;
    fast.trip_speed = 10500;
    fast.speeds = 61;
    const ApiUnbalanceStudy w = api_unbalance_study(sc, fast);
    CHECK(w.verdict == ApiVerdict::fail);
    REQUIRE(!w.reasons.empty());
    CHECK(w.reasons[0].find("unstable") != std::string::npos);
}

TEST_CASE("API unbalance: [api] data written and read back, bad data refused naming its key", "[api_unbalance]") {
    const Scene sc = parse_scene(data_text("three_disk_rotor.toml"), "three_disk_rotor.toml", GYROKIT_DATA_DIR);
    const Scene back = parse_scene(scene_text(sc), "written.toml", GYROKIT_DATA_DIR);
    REQUIRE(back.api.has_value());
    CHECK(*back.api->min_speed == Approx(*sc.api->min_speed).epsilon(1e-12));
    CHECK(*back.api->trip_speed == Approx(*sc.api->trip_speed).epsilon(1e-12));
    REQUIRE(back.api->clearances.size() == 5);
    CHECK(back.api->clearances[2].name == "eye seal, middle impeller");
    CHECK(back.api->clearances[2].z == Approx(0.6).epsilon(1e-12));
    CHECK(back.api->clearances[2].clearance == Approx(0.4e-3).epsilon(1e-12));

    const std::string rotor = data_text("three_disk_rotor.toml");
    const std::string base = rotor.substr(0, rotor.find("\n[api]"));
    const auto refused = [&](const std::string& api, const std::string& key) {
        try {
            const Scene bad = parse_scene(base + api, "bad.toml", GYROKIT_DATA_DIR);
            (void)api_unbalance_study(bad);
            FAIL("accepted: " << api);
        } catch (const InputError& e) {
            const std::string m = e.what();
            CHECK(m.find(key) != std::string::npos);
            CHECK(m.find('\n') == std::string::npos);
        }
    };
    refused("\n[api]\nmin_speed = 7000\n", "mcs");
    refused("\n[api]\nmcs = 10000\nmin_speed = 12000\n", "min_speed");
    refused("\n[api]\nmcs = 10000\ntrip_speed = 9000\n", "trip_speed");
    refused("\n[api]\nmcs = 10000\n[[api.clearance]]\nz = 0.6\nclearance = 0\n", "clearance");
    refused("\n[api]\nmcs = 10000\n[[api.clearance]]\nz = 0.6\nclearance = 1e-3\ngap = 2\n", "gap");
    refused("\n[api]\nmcs = 10000\n[[api.stage]]\nz = 0.6\npower = -1e6\ndiameter = 0.4\nwidth = 0.02\n"
            "density_ratio = 1.3\n",
            "power");
    refused("\n[api]\nmcs = 10000\n[[api.stage]]\nz = 0.6\npower = 1e6\ndiameter = 0.4\nwidth = 0.02\n"
            "density_ratio = 0.8\n",
            "density_ratio");
    refused("\n[api]\nmcs = 10000\n[[api.stage]]\nz = 0.6\npower = 1e6\ndiameter = 0.4\nwidth = 0.5\n"
            "density_ratio = 1.3\n",
            "width");
}
