// API 617's unbalance rules against hand computations: U = 2 x 6350 W/N g mm, Avl,
// Scc's clamp, an orbit's peak-to-peak against a sampled ellipse, the separation
// margin's sides, and where the unbalance goes for synthetic first, second and
// overhung mode shapes (whatever their phase).
#include <gyrokit/analysis/api_unbalance.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

using namespace gyrokit;

namespace {

double rad_s(double rpm) { return rpm * 2.0 * kPi / 60.0; }

// Shapes on 21 nodes over z in [0, 1], bearings at 0.1 and 0.9, forward circular
// whirl (y = -i x), turned by a phase that placement must take out.
struct Shape {
    std::vector<double> z;
    Eigen::VectorXcd x, y;
};
Shape shape(const std::function<double(double)>& f, double phase) {
    Shape s;
    s.x.resize(21);
    s.y.resize(21);
    for (int k = 0; k < 21; ++k) {
        s.z.push_back(0.05 * k);
        s.x(k) = f(s.z.back()) * std::polar(1.0, phase);
        s.y(k) = std::complex<double>(0, -1) * s.x(k);
    }
    return s;
}

}  // namespace

TEST_CASE("API unbalance: U = 2 x 6350 W / N g mm", "[api_unbalance]") {
    // 1000 kg at 10000 rpm: 2 x 6350 x 1000 / 10000 = 1270 g mm = 1.27e-3 kg m.
    CHECK(api_unbalance(1000.0, rad_s(10000.0)) == Approx(1.27e-3).epsilon(1e-14));
    CHECK(api_unbalance(250.0, rad_s(3600.0)) == Approx(2 * 6350 * 250.0 / 3600.0 * 1e-6).epsilon(1e-14));
    CHECK_THROWS_AS(api_unbalance(0.0, 100.0), InputError);
    CHECK_THROWS_AS(api_unbalance(10.0, -1.0), InputError);
}

TEST_CASE("API unbalance: Avl = 25.4 sqrt(12000 / N) um, at most 25.4 um", "[api_unbalance]") {
    CHECK(api_allowable_vibration(rad_s(12000.0)) == Approx(25.4e-6).epsilon(1e-14));
    CHECK(api_allowable_vibration(rad_s(48000.0)) == Approx(12.7e-6).epsilon(1e-14));
    CHECK(api_allowable_vibration(rad_s(3000.0)) == 25.4e-6);   // 50.8 um capped
    CHECK_THROWS_AS(api_allowable_vibration(0.0), InputError);
}

TEST_CASE("API unbalance: Scc = Avl / A1 within [0.5, 6]", "[api_unbalance]") {
    CHECK(api_scale_factor(25e-6, 10e-6) == Approx(2.5).epsilon(1e-15));
    CHECK(api_scale_factor(25e-6, 1e-6) == 6.0);
    CHECK(api_scale_factor(25e-6, 100e-6) == 0.5);
    CHECK(api_scale_factor(25e-6, std::numeric_limits<double>::infinity()) == 0.5);
}

TEST_CASE("API unbalance: an orbit's peak-to-peak is its ellipse's major axis", "[api_unbalance]") {
    const std::complex<double> i(0, 1);
    CHECK(orbit_peak_to_peak(1.0, -i) == Approx(2.0).epsilon(1e-15));          // forward circle, radius 1
    CHECK(orbit_peak_to_peak(1.0, 0.0) == Approx(2.0).epsilon(1e-15));         // a line of half-length 1
    CHECK(orbit_peak_to_peak(3.0, -2.0 * i) == Approx(6.0).epsilon(1e-15));    // ellipse 3 x 2
    // A tilted ellipse: the largest distance of a sampled orbit from the centre, twice.
    const std::complex<double> zx(0.7, -1.3), zy(-0.4, 0.9);
    double far = 0.0;
    const int n = 200000;
    for (int k = 0; k < n; ++k) {
        const std::complex<double> e = std::polar(1.0, 2.0 * kPi * k / n);
        far = std::max(far, std::hypot((zx * e).real(), (zy * e).real()));
    }
    CHECK(orbit_peak_to_peak(zx, zy) == Approx(2.0 * far).epsilon(1e-8));
}

TEST_CASE("API unbalance: the separation margin from the operating range", "[api_unbalance]") {
    const SeparationMargin below = separation_margin(800.0, 1000.0, 1200.0);
    CHECK(below.side == SeparationMargin::Side::below);
    CHECK(below.percent == Approx(20.0).epsilon(1e-14));
    const SeparationMargin above = separation_margin(1500.0, 1000.0, 1200.0);
    CHECK(above.side == SeparationMargin::Side::above);
    CHECK(above.percent == Approx(25.0).epsilon(1e-14));
    const SeparationMargin inside = separation_margin(1100.0, 1000.0, 1200.0);
    CHECK(inside.side == SeparationMargin::Side::inside);
    CHECK(inside.percent == 0.0);
}

TEST_CASE("API unbalance: placement by the mode shape", "[api_unbalance]") {
    const double z0 = 0.1, z1 = 0.9;
    for (const double phase : {0.0, 1.0, -2.5}) {
        // First bending mode: one half sine between the bearings: mid-span (z = 0.5, node 10).
        const Shape a = shape([](double z) { return std::sin(kPi * (z - 0.1) / 0.8); }, phase);
        const UnbalancePlacement pa = api_unbalance_placement(a.z, a.x, a.y, z0, z1);
        CHECK(pa.layout == UnbalanceLayout::first_mode);
        REQUIRE(pa.points.size() == 1);
        CHECK(pa.points[0].index == 10);
        // Second: a full sine: its extremes at z = 0.3 (positive) and 0.7 (negative), 180 degrees apart.
        const Shape b = shape([](double z) { return std::sin(2.0 * kPi * (z - 0.1) / 0.8); }, phase);
        const UnbalancePlacement pb = api_unbalance_placement(b.z, b.x, b.y, z0, z1);
        CHECK(pb.layout == UnbalanceLayout::second_mode);
        REQUIRE(pb.points.size() == 2);
        CHECK(pb.points[0].index == 6);
        CHECK(pb.points[1].index == 14);
        CHECK(pb.points[0].phase == 0.0);
        CHECK(pb.points[1].phase == kPi);
        // The mirrored shape (negative first) is the same loading: the same points and phases.
        const Shape m = shape([](double z) { return -std::sin(2.0 * kPi * (z - 0.1) / 0.8); }, phase);
        const UnbalancePlacement pm = api_unbalance_placement(m.z, m.x, m.y, z0, z1);
        CHECK(pm.points[0].index == 6);
        CHECK(pm.points[0].phase == 0.0);
        CHECK(pm.points[1].phase == kPi);
        // Overhung: the largest deflection at the free end z = 1 (node 20), outboard of z1.
        const Shape c = shape([](double z) { return z > 0.9 ? 10.0 * (z - 0.9) + 0.2 : 0.2 * std::sin(kPi * (z - 0.1) / 0.8); },
                              phase);
        const UnbalancePlacement pc = api_unbalance_placement(c.z, c.x, c.y, z0, z1, false, true);
        CHECK(pc.layout == UnbalanceLayout::overhung);
        REQUIRE(pc.points.size() == 1);
        CHECK(pc.points[0].index == 20);
        // The same shape where nothing hangs beyond z1 (a bare shaft end): the span's own first mode.
        CHECK(api_unbalance_placement(c.z, c.x, c.y, z0, z1).layout == UnbalanceLayout::first_mode);
    }
    // A sign change below 5 % of the largest deflection is no second mode.
    for (const double phase : {0.0, 1.0, -2.5}) {
        const Shape d = shape([](double z) { return z < 0.2 ? -0.01 : std::sin(kPi * (z - 0.1) / 0.8); }, phase);
        CHECK(api_unbalance_placement(d.z, d.x, d.y, z0, z1).layout == UnbalanceLayout::first_mode);
    }
    const Shape e = shape([](double) { return 0.0; }, 0.0);
    CHECK_THROWS_AS(api_unbalance_placement(e.z, e.x, e.y, z0, z1), InputError);
    CHECK_THROWS_AS(api_unbalance_placement(e.z, e.x.head(3), e.y, z0, z1), InputError);
}
