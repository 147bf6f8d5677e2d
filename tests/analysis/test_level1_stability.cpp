// The Level I curve (log decrement of the first forward mode against cross-coupling Q)
// against closed forms: a Jeffcott rotor with cross-coupling Q at its disk obeys
// m z'' + c z' + (k - i Q) z = 0 (z = x + i y), whose forward root reaches the
// imaginary axis at Q0 = c sqrt(k / m).
#include <gyrokit/core/constants.hpp>
#include <gyrokit/gyrokit.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

using namespace gyrokit;

namespace {

GyroscopicSystem jeffcott(double m, double k, double c) {
    GyroscopicSystem s;
    s.dofs.add("x0", 0, DofMotion::x);
    s.dofs.add("y0", 0, DofMotion::y);
    s.node_z = {0.0};
    s.whirl_pairs = {{0, 1}};
    s.M = Eigen::MatrixXd(m * Eigen::MatrixXd::Identity(2, 2));
    s.K = Eigen::MatrixXd(k * Eigen::MatrixXd::Identity(2, 2));
    s.damping.push_back({"bearings", Eigen::MatrixXd(c * Eigen::MatrixXd::Identity(2, 2))});
    s.validate("jeffcott");
    return s;
}

// The forward root of m l^2 + c l + k - i Q = 0 (Im l > 0: z = e^{l t} turns forward).
std::complex<double> forward_root(double m, double k, double c, double q) {
    const std::complex<double> d = std::sqrt(std::complex<double>(c * c - 4 * m * k, 4 * m * q));
    const std::complex<double> a = (-c + d) / (2 * m), b = (-c - d) / (2 * m);
    return a.imag() > 0 ? a : b;
}

}  // namespace

TEST_CASE("Level I on a Jeffcott rotor: the log decrement against Q and Q0 = c sqrt(k/m)", "[level1]") {
    const double m = 10.0, k = 1e6, c = 200.0;
    const double q0 = c * std::sqrt(k / m);   // 63245.55...
    Level1Options o;
    o.stations = {{0, 1.0}};
    o.speed = 500.0;   // a point mass has no gyroscopic term: any speed
    o.q_max = 2e5;
    o.intervals = 20;
    o.marks = {5.5e4};   // between grid points: a point of its own
    const Level1Curve curve = level1_curve(jeffcott(m, k, c), o);
    REQUIRE(curve.points.size() == 22);
    for (const Level1Point& p : curve.points) {
        const std::complex<double> l = forward_root(m, k, c, p.q);
        CHECK(std::abs(p.lambda - l) <= 1e-9 * std::abs(l));
        CHECK(std::abs(p.lambda - l) <= p.error_bound);   // the bound covers the truth
        CHECK(p.whirl == Whirl::Forward);
        CHECK(p.log_decrement == Approx(-2 * kPi * l.real() / l.imag()).margin(1e-9));
    }
    // Forward and backward whirl are equally near at every step (no gyroscopic split): the
    // eigenvector decides, and no step is left undecided or halved.
    CHECK(curve.notes.empty());
    CHECK(curve.solves <= 21 + 1 + 60);   // the points, QA, and the bisection (at most 1e-10 relative)
    REQUIRE(curve.q0.has_value());
    CHECK(std::fabs(*curve.q0 - q0) <= curve.q0_bound);   // covers the truth
    CHECK(curve.q0_bound <= 1e-6 * q0);                   // and is tight
    CHECK(std::fabs(*curve.q0 - q0) <= 1e-6 * q0);
}

TEST_CASE("Level I: a rotor unstable at Q = 0 has Q0 = 0, one that stays stable has none", "[level1]") {
    Level1Options o;
    o.stations = {{0, 1.0}};
    o.speed = 100.0;
    o.q_max = 1e4;   // below Q0 = 63245
    const Level1Curve stable = level1_curve(jeffcott(10.0, 1e6, 200.0), o);
    CHECK_FALSE(stable.q0.has_value());
    CHECK(stable.points.back().log_decrement > 0);
    // Negative damping: unstable before any cross-coupling.
    GyroscopicSystem s = jeffcott(10.0, 1e6, 200.0);
    s.damping[0].D = Eigen::MatrixXd(-20.0 * Eigen::MatrixXd::Identity(2, 2));
    const Level1Curve unstable = level1_curve(s, o);
    REQUIRE(unstable.q0.has_value());
    CHECK(*unstable.q0 == 0.0);
    // Undamped: neutral at Q = 0, and any Q > 0 destabilises it (Q0 = c sqrt(k/m) = 0).
    const Level1Curve undamped = level1_curve(jeffcott(10.0, 1e6, 0.0), o);
    REQUIRE(undamped.q0.has_value());
    CHECK(*undamped.q0 == 0.0);
    CHECK(undamped.points.front().log_decrement == 0.0);
    CHECK(undamped.points.back().log_decrement < 0.0);
}

TEST_CASE("Level I refuses options out of range, naming them", "[level1]") {
    const GyroscopicSystem s = jeffcott(10.0, 1e6, 200.0);
    Level1Options o;
    o.stations = {{0, 1.0}};
    o.speed = 100.0;
    o.q_max = 1e4;
    const auto message = [&](Level1Options bad) {
        try {
            level1_curve(s, bad);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    Level1Options a = o;
    a.speed = -1.0;
    CHECK_THAT(message(a), Catch::Contains("speed = -1"));
    a = o;
    a.q_max = 0.0;
    CHECK_THAT(message(a), Catch::Contains("q_max = 0"));
    a = o;
    a.stations = {{3, 1.0}};
    CHECK_THAT(message(a), Catch::Contains("station node 3"));
    a = o;
    a.stations = {{0, 0.5}};
    CHECK_THAT(message(a), Catch::Contains("sum to 0.5"));
    a = o;
    a.marks = {2e4};
    CHECK_THAT(message(a), Catch::Contains("to mark"));
}

TEST_CASE("the region A/B boundary of API 617's chart", "[level1]") {
    CHECK(region_b_boundary(5.0) == 2.5);
    CHECK(region_b_boundary(16.53) == 2.5);
    CHECK(region_b_boundary(60.0) == Approx(2.0).epsilon(1e-12));
    CHECK(region_b_boundary(38.0) == Approx(2.69 - 0.0115 * 38.0));
    CHECK(region_b_boundary(61.0) == 0.0);
}
