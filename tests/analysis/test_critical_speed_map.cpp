// The undamped critical speed map against closed forms: a uniform Rayleigh shaft
// (rotary inertia and gyroscopic moments, no shear) whose rigid-support limit is the
// pinned-pinned spinning beam, forward and backward, and whose soft-bearing end is the
// rigid rotor on springs (cylindrical and conical modes) and, above it, the free-free beam.
#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/critical_map_study.hpp>
#include <gyrokit/study/defaults.hpp>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <string>

using namespace gyrokit;

namespace {

const double pi = std::acos(-1.0);
const double L = 1.0, D = 0.04, E = 2.1e11, rho = 7800;
const int n = 40;

RotorModel shaft_on_end_bearings() {
    RotorModel m;
    RotorSection s;
    s.shape.length = L;
    s.shape.outer_diameter = D;
    s.shape.youngs_modulus = E;
    s.shape.density = rho;
    s.elements = n;
    m.sections = {s};
    m.shear_deformation = false;   // a Rayleigh beam: rotary inertia and gyroscopic moments
    for (double z : {0.0, L}) {
        RotorBearing b;
        b.z = z;
        b.constant.kxx = b.constant.kyy = 1e7;
        b.constant.cxx = b.constant.cyy = 1e3;   // removed by the map
        m.bearings.push_back(b);
    }
    return m;
}

const MapPoint* find(const std::vector<MapPoint>& ps, double k, const char* whirl, int number) {
    for (const MapPoint& p : ps)
        if (p.stiffness == k && p.whirl == whirl && p.number == number) return &p;
    return nullptr;
}

}  // namespace

TEST_CASE("critical speed map: the rigid-support limit is the spinning pinned-pinned Rayleigh shaft") {
    const double A = pi * D * D / 4, I = pi * std::pow(D, 4) / 64;
    CriticalSpeedMapOptions o;
    o.stiffness = {1e6, 1e9};
    o.modes = 3;
    const CriticalSpeedMap map = critical_speed_map(shaft_on_end_bearings(), o);
    for (int j = 1; j <= 3; ++j) {
        INFO("mode " << j);
        // sin(j pi z / L): E I k^4 = w^2 (rho A -+ rho I k^2), the polar inertia 2 rho I
        // turning the rotary inertia's rho I k^2 into -rho I k^2 (forward) or +3 rho I k^2
        // (backward) at synchronous whirl.
        const double k = j * pi / L;
        const double forward = k * k * std::sqrt(E * I / (rho * A - rho * I * k * k));
        const double backward = k * k * std::sqrt(E * I / (rho * A + 3 * rho * I * k * k));
        const MapPoint* f = find(map.rigid, map.rigid.front().stiffness, "forward", j);
        const MapPoint* b = find(map.rigid, map.rigid.front().stiffness, "backward", j);
        REQUIRE(f);
        REQUIRE(b);
        // Cubic elements: the frequency error is about (k h)^4 / 1440, below 2e-6 for the
        // third mode with 40 elements; 1e-5 leaves room for the constant.
        CHECK(f->speed == Approx(forward).epsilon(1e-5));
        CHECK(b->speed == Approx(backward).epsilon(1e-5));
        CHECK(f->backward_error <= 1e-12);
    }
    CHECK(std::isinf(map.rigid.front().stiffness));
    // Stiffer bearings raise every critical speed towards the rigid limit.
    for (int j = 1; j <= 3; ++j) {
        const MapPoint *soft = find(map.points, 1e6, "forward", j), *stiff = find(map.points, 1e9, "forward", j);
        REQUIRE(soft);
        REQUIRE(stiff);
        CHECK(soft->speed < stiff->speed);
        CHECK(stiff->speed < find(map.rigid, map.rigid.front().stiffness, "forward", j)->speed);
    }
    CHECK(map.max_backward_error <= 1e-12);
    REQUIRE(map.bearings.size() == 2);   // the constant bearings' kxx, drawn at 1e7 N/m
    CHECK(map.bearings[0].stiffness.front() == 1e7);
}

TEST_CASE("critical speed map: on soft bearings the shaft is a rigid rotor on springs") {
    const double A = pi * D * D / 4, m = rho * A * L, r = D / 2;
    const double Id = m * (L * L / 12 + r * r / 4), Ip = m * r * r / 2;   // a solid cylinder about its centre
    const double k = 1.0;   // N/m: 1e-6 of the shaft's own stiffness, its bending does not count
    CriticalSpeedMapOptions o;
    o.stiffness = {k};
    o.modes = 2;
    const CriticalSpeedMap map = critical_speed_map(shaft_on_end_bearings(), o);
    // Cylindrical: w^2 = 2 k / m in both whirls; conical with the bearings at +-L/2:
    // w^2 = 2 k (L/2)^2 / (Id -+ Ip) forward / backward. The shaft's flexibility shifts
    // them by about k / k_shaft = 1e-6.
    const double cylindrical = std::sqrt(2 * k / m);
    const double conical_f = std::sqrt(2 * k * L * L / 4 / (Id - Ip)), conical_b = std::sqrt(2 * k * L * L / 4 / (Id + Ip));
    CHECK(find(map.points, k, "forward", 1)->speed == Approx(cylindrical).epsilon(1e-5));
    CHECK(find(map.points, k, "backward", 1)->speed == Approx(cylindrical).epsilon(1e-5));
    CHECK(find(map.points, k, "forward", 2)->speed == Approx(conical_f).epsilon(1e-5));
    CHECK(find(map.points, k, "backward", 2)->speed == Approx(conical_b).epsilon(1e-5));
}

TEST_CASE("critical speed map: the free-free limit, above the two rigid-body lines, is the free beam's bending") {
    // Without rotary inertia (and so without gyroscopic moments) the shaft is an
    // Euler-Bernoulli beam: free-free bending at w = (beta L)^2 sqrt(E I / (rho A L^4)),
    // beta L = 4.730041, 7.853205, in both planes. On 1e-3 N/m springs (1e-9 of the shaft's own
    // stiffness) the lines above the rigid-body ones are these modes.
    const double A = pi * D * D / 4, I = pi * std::pow(D, 4) / 64;
    RotorModel m = shaft_on_end_bearings();
    m.rotary_inertia = false;
    CriticalSpeedMapOptions o;
    o.stiffness = {1e-3};
    o.modes = 8;
    const CriticalSpeedMap map = critical_speed_map(m, o);
    // Without gyroscopic moments the whirl is planar and every mode comes twice (the x
    // and y planes): lines 1-4 are the rigid-body ones, 5-6 and 7-8 the bending modes.
    const double beta_l[] = {4.730041, 7.853205};   // cos(bL) cosh(bL) = 1, to 7 digits
    for (int line = 5; line <= 8; ++line) {
        INFO("line " << line);
        const double bl = beta_l[(line - 5) / 2];
        const double exact = bl * bl * std::sqrt(E * I / (rho * A)) / (L * L);
        const MapPoint* p = find(map.points, 1e-3, "planar", line);
        REQUIRE(p);
        // Cubic elements: (k h)^4 / 1440 ~ 1e-6 for the second mode on 40 elements;
        // beta L to 7 digits gives 3e-7 in w.
        CHECK(p->speed == Approx(exact).epsilon(1e-5));
    }
    CHECK(find(map.points, 1e-3, "planar", 4)->speed < 1e-3 * find(map.points, 1e-3, "planar", 5)->speed);
}

TEST_CASE("critical speed map: bad options and a model without bearings are refused") {
    CriticalSpeedMapOptions o;
    o.stiffness = {1e7, 1e6};
    CHECK_THROWS_WITH(critical_speed_map(shaft_on_end_bearings(), o), Catch::Contains("entry 1 = 1000000") &&
                                                                          Catch::Contains("increasing"));
    o.stiffness = {};
    o.modes = 0;
    CHECK_THROWS_WITH(critical_speed_map(shaft_on_end_bearings(), o), Catch::Contains("modes = 0"));
    RotorModel free = shaft_on_end_bearings();
    free.bearings.clear();
    CHECK_THROWS_WITH(critical_speed_map(free, {}), Catch::Contains("has no bearings"));
    // The default: 31 stiffnesses over five decades around the shaft's own stiffness.
    const std::vector<double> k = default_map_stiffness(shaft_on_end_bearings());
    const double k_shaft = 48 * E * pi * std::pow(D, 4) / 64 / (L * L * L);
    REQUIRE(k.size() == 31);
    CHECK(k.front() == Approx(1e-2 * k_shaft).epsilon(1e-12));
    CHECK(k.back() == Approx(1e3 * k_shaft).epsilon(1e-12));
}

TEST_CASE("the critical map study refuses a scene without an FE rotor, in the library", "[critical_map][errors]") {
    const Scene gyrostat = load_scene(std::string(GYROKIT_DATA_DIR) + "/centrifuge.toml");
    CHECK_THROWS_WITH(critical_map_study(gyrostat),
                      Catch::Contains("a critical speed map of a [model] of type") &&
                          Catch::Contains("allowed: an fe_rotor model"));
    const Scene fe = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    CriticalSpeedMapOptions two;
    two.stiffness = {1e7, 1e8};
    const CriticalSpeedMap map = critical_map_study(fe, two);
    CHECK(map.stiffness == two.stiffness);
    int most = 0;
    for (const MapPoint& p : map.points) most = std::max(most, p.number);
    CHECK(most == defaults::critical_map_modes);   // the default count, each whirl's lowest
}
