// Textbook rotors with closed forms: the Jeffcott rotor (unbalance response,
// stability threshold of rotating internal damping) and a rigid rotor on
// isotropic tilt springs (Campbell diagram and critical speed).
#include <gyrokit/numerics/assignment.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>

#include <catch2/catch.hpp>
#include <cmath>

using namespace gyrokit;

namespace {

const Eigen::Matrix2d J = (Eigen::Matrix2d() << 0, 1, -1, 0).finished();

// Jeffcott rotor: m z'' + (c_e + c_i) z' + k z - i c_i w z = m eps w^2 e^{iwt}, z = x + iy.
GyroscopicSystem jeffcott(double m, double k, double ce, double ci, double eps) {
    GyroscopicSystem s;
    s.M = m * Eigen::Matrix2d::Identity();
    s.K = k * Eigen::Matrix2d::Identity();
    s.damping.push_back({"c_e", ce * Eigen::Matrix2d::Identity()});
    if (ci > 0) {
        s.damping.push_back({"c_i", ci * Eigen::Matrix2d::Identity()});
        s.N = ci * J;   // rotating damping is circulatory in the fixed frame
    }
    s.unbalance = Eigen::Vector2cd(m * eps, std::complex<double>(0, -m * eps));   // (cos wt, sin wt)
    s.dofs.names = {"x", "y"};
    s.whirl_pairs = {{0, 1}};
    return s;
}

// Rigid rotor tilting on isotropic springs: I_t a'' + I_p w J a' + k_t a = 0.
GyroscopicSystem rigid_rotor(double It, double Ip, double kt) {
    GyroscopicSystem s;
    s.M = It * Eigen::Matrix2d::Identity();
    s.K = kt * Eigen::Matrix2d::Identity();
    s.G = Ip * J;
    s.dofs.names = {"tilt_x", "tilt_y"};
    s.whirl_pairs = {{0, 1}};
    return s;
}

}  // namespace

TEST_CASE("Jeffcott rotor: unbalance response closed form", "[textbook][response]") {
    const double m = 3.0, k = 1.2e4, c = 15.0, eps = 2e-4;
    const GyroscopicSystem s = jeffcott(m, k, c, 0.0, eps);
    for (double w : {5.0, 40.0, std::sqrt(k / m), 90.0, 400.0}) {
        CAPTURE(w);
        const Eigen::VectorXcd Z = unbalance_response(s, w);
        const double amp = m * eps * w * w / std::abs(std::complex<double>(k - m * w * w, c * w));
        CHECK(std::abs(Z(0)) == Approx(amp).epsilon(1e-13));
        CHECK(std::abs(Z(1)) == Approx(amp).epsilon(1e-13));
        // Circular forward orbit: y lags x by 90 degrees.
        CHECK(std::abs(Z(1) - std::complex<double>(0, -1) * Z(0)) <= 1e-13 * amp);
    }
    // The peak is at w_n / sqrt(1 - 2 zeta^2) for displacement under rotating unbalance.
    const ResponseCurve rc = unbalance_response(s, SpeedRange{10.0, 120.0, 111}.points());
    const auto ex = response_extrema(s, rc);
    const double zeta = c / (2 * std::sqrt(k * m)), wn = std::sqrt(k / m);
    REQUIRE(!ex.empty());
    CHECK(ex.front().peak);
    CHECK(ex.front().speed == Approx(wn / std::sqrt(1 - 2 * zeta * zeta)).epsilon(1e-7));
}

TEST_CASE("Jeffcott rotor: the largest response is the refined peak, not the largest grid value",
          "[textbook][response]") {
    // A lightly damped rotor on a grid whose points miss the resonance by far.
    const double m = 3.0, k = 1.2e4, c = 0.6, eps = 2e-4;
    const GyroscopicSystem s = jeffcott(m, k, c, 0.0, eps);
    const double zeta = c / (2 * std::sqrt(k * m));
    const double peak = eps / (2 * zeta * std::sqrt(1 - zeta * zeta)), at = std::sqrt(k / m) / std::sqrt(1 - 2 * zeta * zeta);
    const ResponseCurve rc = unbalance_response(s, SpeedRange{0.0, 130.0, 14}.points());   // step 10: 60.03 is missed
    const double grid_max = rc.Z.col(0).cwiseAbs().maxCoeff();
    REQUIRE(grid_max < 0.05 * peak);
    const auto maxima = response_maxima(rc, response_extrema(s, rc));
    REQUIRE(maxima.size() == 2);
    for (const auto& mx : maxima) {
        CHECK(mx.refined);
        // The peak is flat: amplitude to rounding, speed to sqrt(eps) of the flat top.
        CHECK(mx.amplitude == Approx(peak).epsilon(1e-12));
        CHECK(mx.speed == Approx(at).epsilon(1e-7));
    }
    // No interior peak on an increasing curve: the range end.
    const ResponseCurve low = unbalance_response(s, SpeedRange{0.0, 30.0, 7}.points());
    const auto end = response_maxima(low, response_extrema(s, low));
    CHECK(!end[0].refined);
    CHECK(end[0].speed == 30.0);
    CHECK(end[0].amplitude == Approx(std::abs(low.Z(6, 0))).epsilon(1e-15));
}

TEST_CASE("Jeffcott rotor: a peak narrower than the search resolves is unbounded, not a number",
          "[textbook][response]") {
    // Half-power half-width zeta w_n against the search's 10 resolutions, 40 sqrt(eps) w_n = 6.0e-7 w_n.
    const double m = 3.0, k = 1.2e4, eps = 2e-4, wn = std::sqrt(k / m);
    const auto grid = SpeedRange{0.0, 130.0, 14}.points();   // misses w_n = 63.2456 by 3.2
    for (const double zeta : {0.0, 1e-12, 1e-7}) {
        CAPTURE(zeta);
        const GyroscopicSystem s = jeffcott(m, k, 2 * zeta * std::sqrt(k * m), 0.0, eps);
        const ResponseCurve rc = unbalance_response(s, grid);
        const auto ex = response_extrema(s, rc);
        REQUIRE(ex.size() == 2);
        for (const auto& e : ex) {
            CHECK(e.peak);
            CHECK(!e.bounded);
            CHECK(std::isinf(e.amplitude));
            CHECK(e.speed == Approx(wn).epsilon(1e-6));
        }
        const auto maxima = response_maxima(rc, ex);
        CHECK((!maxima[0].bounded && std::isinf(maxima[0].amplitude)));
    }
    for (const double zeta : {2e-6, 1e-5, 1e-3}) {
        CAPTURE(zeta);
        const GyroscopicSystem s = jeffcott(m, k, 2 * zeta * std::sqrt(k * m), 0.0, eps);
        const ResponseCurve rc = unbalance_response(s, grid);
        const auto maxima = response_maxima(rc, response_extrema(s, rc));
        // Brent's speed is within 6e-8 w_n of the peak: the height within (1 + (6e-8/zeta)^2 / 2).
        const double peak = eps / (2 * zeta * std::sqrt(1 - zeta * zeta));
        for (const auto& mx : maxima) {
            CHECK(mx.bounded);
            CHECK(mx.amplitude == Approx(peak).epsilon(std::max(1e-12, 0.5 * std::pow(6e-8 / zeta, 2))));
        }
    }
}

TEST_CASE("Jeffcott rotor with internal damping: instability threshold w_n (1 + c_e/c_i)", "[textbook][stability]") {
    const double m = 2.0, k = 5e3, ce = 4.0, ci = 10.0;
    const GyroscopicSystem s = jeffcott(m, k, ce, ci, 0.0);
    const double wn = std::sqrt(k / m), threshold = wn * (1 + ce / ci);
    const CampbellDiagram cd = campbell(s, SpeedRange{0.0, 2 * threshold, 41}.points());
    const auto ch = stability_changes(s, cd);
    REQUIRE(ch.size() == 1);
    CHECK(ch[0].becomes_unstable);
    CHECK(ch[0].speed == Approx(threshold).epsilon(1e-10));
    CHECK(ch[0].mode.whirl == Whirl::Forward);
}

TEST_CASE("rigid rotor: closed-form Campbell diagram and critical speed", "[textbook][campbell]") {
    const double It = 0.5, Ip = 0.2, kt = 800.0;
    const GyroscopicSystem s = rigid_rotor(It, Ip, kt);
    const CampbellDiagram cd = campbell(s, SpeedRange{0.0, 200.0, 81}.points());
    REQUIRE(cd.branches.size() == 2);
    for (const Branch& b : cd.branches)
        for (const auto& p : b.points) {
            CAPTURE(p);
            const double L = Ip * p.speed, r = std::sqrt(L * L + 4 * It * kt);
            // Backward branch (r - L)/(2 It), forward (r + L)/(2 It).
            const double expect = b.id == 1 ? (r - L) / (2 * It) : (r + L) / (2 * It);
            CHECK(p.mode.frequency() == Approx(expect).epsilon(1e-12));
            if (p.speed > 0) CHECK(p.mode.whirl == (b.id == 1 ? Whirl::Backward : Whirl::Forward));
        }
    // Forward crossing with 1x: (It - Ip) w^2 = kt; backward: (It + Ip) w^2 = kt.
    const auto cs = critical_speeds(s, cd, {1});
    const auto direct = critical_speeds_direct(s, 1, 0.0, 200.0);
    REQUIRE(cs.size() == 2);
    REQUIRE(direct.size() == 2);
    CHECK(cs[0].speed == Approx(std::sqrt(kt / (It + Ip))).epsilon(1e-12));
    CHECK(cs[0].mode.whirl == Whirl::Backward);
    CHECK(cs[1].speed == Approx(std::sqrt(kt / (It - Ip))).epsilon(1e-12));
    CHECK(cs[1].mode.whirl == Whirl::Forward);
    for (size_t i = 0; i < 2; ++i) {
        CAPTURE(i);
        CHECK(direct[i].speed == Approx(cs[i].speed).epsilon(1e-12));
    }
    // Second harmonic: (4 It -+ 2 Ip) w^2 = kt.
    const auto h2 = critical_speeds(s, cd, {2});
    REQUIRE(h2.size() == 2);
    CHECK(h2[0].speed == Approx(std::sqrt(kt / (4 * It + 2 * Ip))).epsilon(1e-12));
    CHECK(h2[1].speed == Approx(std::sqrt(kt / (4 * It - 2 * Ip))).epsilon(1e-12));
}

TEST_CASE("Campbell tracking follows crossing branches without swapping", "[campbell]") {
    // Translation (constant frequency) and tilt (gyroscopic) in one system, uncoupled:
    // the backward tilt branch crosses the translation branches.
    GyroscopicSystem s;
    s.M = Eigen::Vector4d(1.0, 1.0, 0.5, 0.5).asDiagonal();
    s.K = Eigen::Vector4d(900.0, 900.0, 800.0, 800.0).asDiagonal();
    Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
    G.bottomRightCorner<2, 2>() = 0.4 * J;
    s.G = G;
    s.dofs.names = {"x", "y", "ax", "ay"};
    s.whirl_pairs = {{0, 1}, {2, 3}};
    const CampbellDiagram cd = campbell(s, SpeedRange{0.0, 300.0, 31}.points());
    int constant = 0;
    for (const Branch& b : cd.branches) {
        bool flat = true;
        for (const auto& p : b.points) flat = flat && std::fabs(p.mode.frequency() - 30.0) < 1e-9;
        constant += flat;
    }
    CHECK(constant == 2);   // both translation branches stay at sqrt(900) = 30 rad/s
}

TEST_CASE("degenerate speed lists are refused, never a hang, and matching refuses NaN costs", "[campbell][reliability]") {
    GyroscopicSystem s;
    s.M = Eigen::Matrix2d::Identity();
    s.K = Eigen::Vector2d(900.0, 900.0).asDiagonal();
    s.G = 0.4 * J;
    s.whirl_pairs = {{0, 1}};
    s.dofs.names = {"x", "y"};
    CHECK_THROWS_AS(campbell(s, {1.0, 1.0, 2.0}), InputError);            // repeated
    CHECK_THROWS_AS(campbell(s, {2.0, 1.0}), InputError);                 // decreasing
    CHECK_THROWS_AS(campbell(s, {0.0, std::nan("")}), InputError);        // NaN
    CHECK_THROWS_AS(SpeedRange::parse("1:1.0000000000000002:3", "--speeds"), InputError);
    // Adjacent doubles: the tracking cannot bisect between them and must stop.
    const double a = 30.0, b = std::nextafter(30.0, 31.0);
    CHECK_NOTHROW(campbell(s, {a, b}));
    Eigen::MatrixXd cost = Eigen::MatrixXd::Ones(2, 2);
    cost(0, 1) = std::nan("");
    CHECK_THROWS_AS(solve_assignment(cost), SolverError);
}
