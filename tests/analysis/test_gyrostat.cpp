// The gyrostat with elastic shaft: structure of the matrices, the closed forms
// of the paper (corrected, see docs/gyrostat.md) and its limit cases.
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/speed_range.hpp>
#include "test_helpers.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>

using namespace gyrokit;

namespace {

double closed_form_w1(const GyrostatParameters& p) {   // eq. (29), corrected
    const double wT2 = p.c_T / p.m, wR2 = p.c_R / p.A_R;
    return p.A_R / p.C_R * std::fabs(wR2 - wT2) / std::sqrt(wT2);
}

// Eq. (37), corrected: w = (A_R/C_R) nu, m A_G nu^4 - [m c_G + (A_G + m s^2) c_T] nu^2 + c_G c_T = 0.
std::pair<double, double> closed_form_w23(const GyrostatParameters& p) {
    const double a = p.m * p.A_G, b = p.m * p.c_G + (p.A_G + p.m * p.s * p.s) * p.c_T, c = p.c_G * p.c_T;
    const double d = std::sqrt(b * b - 4 * a * c);
    const double small = 2 * c / (b + d), large = (b + d) / (2 * a);   // cancellation-free roots
    return {p.A_R / p.C_R * std::sqrt(small), p.A_R / p.C_R * std::sqrt(large)};
}

std::vector<double> losses_of(const PervasiveReport& r, const std::string& name) {
    std::vector<double> w;
    for (const auto& l : r.losses)
        if (l.damping == name) w.push_back(l.speed);
    return w;
}

}  // namespace

TEST_CASE("gyrostat matrices: M, D, K symmetric, G skew, det M closed form", "[gyrostat]") {
    std::mt19937 gen(1);
    for (int trial = 0; trial < 20; ++trial) {
        CAPTURE(trial);
        const GyrostatParameters p = test::random_gyrostat(gen, trial % 2 == 0);
        const GyroscopicSystem s = make_system(p);
        REQUIRE(s.size() == 6);
        const Eigen::MatrixXd M = s.M.dense(), K = s.K.dense(), G = s.G.dense();
        CHECK((M - M.transpose()).norm() == 0.0);
        CHECK((K - K.transpose()).norm() == 0.0);
        CHECK((G + G.transpose()).norm() == 0.0);
        for (const auto& c : s.damping) {
            CAPTURE(c);
            CHECK((c.D.dense() - c.D.dense().transpose()).norm() == 0.0);
        }
        // det M = A_G B_G A_R^2 m^2 (all other terms cancel); M positive definite.
        const double det = p.A_G * p.B_G * p.A_R * p.A_R * p.m * p.m;
        CHECK(M.determinant() == Approx(det).epsilon(1e-10));
        CHECK(Eigen::LLT<Eigen::MatrixXd>(M).info() == Eigen::Success);
    }
}

TEST_CASE("cage damping stops pervading exactly at eq. (29)", "[gyrostat][pervasive]") {
    std::mt19937 gen(2);
    for (int trial = 0; trial < 12; ++trial) {
        const GyrostatParameters p = test::random_gyrostat(gen, trial % 3 != 0);   // (29) holds for any cage
        const double w1 = closed_form_w1(p);
        const GyroscopicSystem s = make_system(p);
        for (const int modes : {0, kModesInRange}) {
            PervasiveOptions po;
            po.modes = modes;
            po.f_cut = 100.0 * w1;
            const auto rep = pervasive_damping(s.with_damping_only({"d_G"}), SpeedRange{0.0, 2.0 * w1, 201}.points(), po);
            const auto w = losses_of(rep, "d_G");
            INFO("trial " << trial << " modes " << modes << " w1 = " << w1);
            REQUIRE(w.size() == 1);
            CHECK(std::fabs(w[0] - w1) <= 1e-8 * w1);
        }
    }
}

TEST_CASE("rotation damping stops pervading at eq. (37) for a symmetric cage only", "[gyrostat][pervasive]") {
    std::mt19937 gen(3);
    for (int trial = 0; trial < 12; ++trial) {
        const GyrostatParameters p = test::random_gyrostat(gen, true);
        const auto [w2, w3] = closed_form_w23(p);
        // Every mode solved in full at each speed, and the modes up to f_cut continued
        // (refined by following the branch; f_cut above the lost modes), alike.
        for (const int modes : {0, kModesInRange}) {
            PervasiveOptions po;
            po.modes = modes;
            po.f_cut = 100.0 * w3;
            const auto rep = pervasive_damping(make_system(p).with_damping_only({"d_R"}),
                                               SpeedRange{0.0, 1.5 * w3, 301}.points(), po);
            const auto w = losses_of(rep, "d_R");
            INFO("trial " << trial << " modes " << modes << " w2 = " << w2 << " w3 = " << w3);
            REQUIRE(w.size() == 2);
            CHECK(std::fabs(w[0] - w2) <= 1e-8 * w2);
            CHECK(std::fabs(w[1] - w3) <= 1e-8 * w3);
        }
    }
    for (int trial = 0; trial < 6; ++trial) {   // A_G != B_G: always pervading
        const GyrostatParameters p = test::random_gyrostat(gen, false);
        const auto [w2, w3] = closed_form_w23(p);
        const auto rep =
            pervasive_damping(make_system(p).with_damping_only({"d_R"}), SpeedRange{0.0, 2.0 * w3, 301}.points());
        CHECK(losses_of(rep, "d_R").empty());
    }
}

TEST_CASE("translation damping pervades iff s != 0", "[gyrostat][pervasive]") {
    std::mt19937 gen(4);
    for (int trial = 0; trial < 8; ++trial) {
        CAPTURE(trial);
        GyrostatParameters p = test::random_gyrostat(gen, trial % 2 == 0);
        const auto speeds = SpeedRange{0.0, 3.0 * closed_form_w1(p), 101}.points();
        CHECK(losses_of(pervasive_damping(make_system(p).with_damping_only({"d_T"}), speeds), "d_T").empty());
        p.s = 0.0;   // translation decouples: its damping reaches nothing else, at every speed
        const auto rep = pervasive_damping(make_system(p).with_damping_only({"d_T"}), speeds);
        const auto lost = losses_of(rep, "d_T");
        const std::set<double> at(lost.begin(), lost.end());
        std::set<int> modes;
        for (const auto& l : rep.losses) modes.insert(l.mode);
        for (double w : speeds) {
            CAPTURE(w);
            CHECK(at.count(w) == 1);
        }
        CHECK(modes.size() == 4);   // the cage and rotor-tilt modes; only translation is damped
    }
}

TEST_CASE("centrifuge: undamped resonances only at forward crossings of the 1x line", "[gyrostat][response]") {
    GyrostatParameters p = test::centrifuge();
    p.d_G = p.d_T = p.d_R = 0.0;
    const GyroscopicSystem s = make_system(p);
    const auto cs = critical_speeds_direct(s, 1, 0.0, 60.0);
    int forward = 0;
    for (const auto& c : cs) {
        // Near a resonance |Z| grows like 1/|w - w_c|: 100 times closer, 100 times larger.
        const auto amp = [&](double rel) {
            return unbalance_response(s, c.speed * (1.0 + rel)).cwiseAbs().maxCoeff();
        };
        const double ratio = amp(1e-6) / amp(1e-4);
        INFO("critical speed " << c.speed << " whirl " << to_string(c.mode.whirl) << " ratio " << ratio);
        if (c.mode.whirl == Whirl::Forward) {
            ++forward;
            CHECK(ratio > 50.0);
        } else {
            CHECK(ratio < 2.0);
        }
    }
    CHECK(forward == 2);   // the paper's 10.4 and 19.4 1/s; C_R > A_R: no nutation resonance
    // The scene was fitted to these values (docs/gyrostat.md).
    std::vector<double> fw;
    for (const auto& c : cs)
        if (c.mode.whirl == Whirl::Forward) fw.push_back(c.speed);
    REQUIRE(fw.size() == 2);
    CHECK(fw[0] == Approx(10.4).epsilon(1e-4));
    CHECK(fw[1] == Approx(19.4).epsilon(1e-4));
}

TEST_CASE("whirl directions alternate as in Tabelle 1 (-,+,-,+,-,+)", "[gyrostat][whirl]") {
    GyrostatParameters p = test::centrifuge();
    p.d_G = p.d_T = p.d_R = 0.0;
    for (double w : {1.0, 10.0, 30.0, 100.0, 1000.0}) {
        CAPTURE(w);
        const auto sp = solve_at_speed(make_system(p), w);
        REQUIRE(sp.modes.size() == 6);
        for (size_t i = 0; i < 6; ++i)
            CHECK(sp.modes[i].whirl == (i % 2 == 0 ? Whirl::Backward : Whirl::Forward));
    }
}

TEST_CASE("high-speed asymptotes: nutation (15) from above, precession (19) from below", "[gyrostat]") {
    std::mt19937 gen(5);
    for (int trial = 0; trial < 10; ++trial) {
        GyrostatParameters p = test::random_gyrostat(gen, trial % 2 == 0);
        p.d_G = p.d_T = p.d_R = 0.0;
        const GyroscopicSystem s = make_system(p);
        double prev_nut = INFINITY, prev_pre = INFINITY;
        for (double w : {1e3, 1e4, 1e5}) {
            CAPTURE(w);
            const auto sp = solve_at_speed(s, w);
            const double L = p.C_R * w;
            const double nu6 = sp.modes.back().frequency(), nu1 = sp.modes.front().frequency();
            const double nut = L / p.A_R, pre = p.c_G * p.c_R / (L * (p.c_G + p.c_R));
            CHECK(nu6 > nut);
            CHECK(nu1 < pre);
            const double e_nut = nu6 / nut - 1.0, e_pre = 1.0 - nu1 / pre;
            CHECK(e_nut < prev_nut);   // the gaps close as the speed grows
            CHECK(e_pre < prev_pre);
            prev_nut = e_nut;
            prev_pre = e_pre;
        }
        CHECK(prev_nut < 1e-3);
        CHECK(prev_pre < 1e-3);
    }
}

TEST_CASE("rigid shaft and rigid housing limits", "[gyrostat][limits]") {
    GyrostatParameters p = test::centrifuge();
    p.d_G = p.d_T = p.d_R = 0.0;
    const double w = 25.0;
    const double A = p.A_G + p.A_R + p.m * p.s * p.s;
    SECTION("rigid shaft: gyro pendulum (12), A nu^2 -+ C_R w nu - c_G = 0") {
        GyrostatParameters q = p;
        q.rigid_shaft = true;
        const auto sp = solve_at_speed(make_system(q), w);
        REQUIRE(sp.modes.size() == 2);
        const double L = p.C_R * w, r = std::sqrt(L * L + 4 * A * p.c_G);
        CHECK(sp.modes[0].frequency() == Approx((r - L) / (2 * A)).epsilon(1e-12));
        CHECK(sp.modes[1].frequency() == Approx((r + L) / (2 * A)).epsilon(1e-12));
        CHECK(sp.modes[0].whirl == Whirl::Backward);
        CHECK(sp.modes[1].whirl == Whirl::Forward);
        // The elastic model approaches it as the shaft stiffens (error of order 1/c).
        GyrostatParameters e = p;
        e.c_T = e.c_R = 1e12;
        const auto se = solve_at_speed(make_system(e), w);
        CHECK(se.modes[0].frequency() == Approx(sp.modes[0].frequency()).epsilon(1e-6));
        CHECK(se.modes[1].frequency() == Approx(sp.modes[1].frequency()).epsilon(1e-6));
    }
    SECTION("rigid housing: decoupled translation and gyroscopic tilt") {
        GyrostatParameters q = p;
        q.rigid_housing = true;
        const auto sp = solve_at_speed(make_system(q), w);
        REQUIRE(sp.modes.size() == 4);
        const double L = p.C_R * w, r = std::sqrt(L * L + 4 * p.A_R * p.c_R), wT = std::sqrt(p.c_T / p.m);
        std::vector<double> expect{(r - L) / (2 * p.A_R), wT, wT, (r + L) / (2 * p.A_R)};
        std::sort(expect.begin(), expect.end());
        for (size_t i = 0; i < 4; ++i) {
            CAPTURE(i);
            CHECK(sp.modes[i].frequency() == Approx(expect[i]).epsilon(1e-12));
        }
    }
}

TEST_CASE("symmetric cage: response magnitudes pairwise equal, (alpha,beta), (x,y), (psi,theta)",
          "[gyrostat][response]") {
    const GyroscopicSystem s = make_system(test::centrifuge());
    for (double w : {5.0, 12.0, 31.0, 50.0}) {
        CAPTURE(w);
        const Eigen::VectorXcd Z = unbalance_response(s, w);
        for (int k = 0; k < 6; k += 2) {
            CAPTURE(k);
            CHECK(std::abs(Z(k)) == Approx(std::abs(Z(k + 1))).epsilon(1e-12));
        }
    }
}

TEST_CASE("branch-refined and direct critical speeds agree", "[gyrostat][critical]") {
    std::mt19937 gen(6);
    for (int trial = 0; trial < 6; ++trial) {
        GyrostatParameters p = trial == 0 ? test::centrifuge() : test::random_gyrostat(gen, trial % 2 == 0);
        p.d_G = p.d_T = p.d_R = 0.0;
        const GyroscopicSystem s = make_system(p);
        const double top = 2.0 * std::sqrt(p.c_T / p.m);
        const auto direct = critical_speeds_direct(s, 1, 0.0, top);
        const auto cd = campbell(s, SpeedRange{0.0, top, 161}.points());
        const auto branch = critical_speeds(s, cd, {1});
        INFO("trial " << trial);
        REQUIRE(branch.size() == direct.size());
        for (size_t i = 0; i < direct.size(); ++i) {
            CAPTURE(i);
            CHECK(branch[i].speed == Approx(direct[i].speed).epsilon(1e-10));
            CHECK(branch[i].mode.whirl == direct[i].mode.whirl);
        }
    }
}
