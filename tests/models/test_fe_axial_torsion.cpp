// Shaft elements with 6 DOFs per node (axial and torsional bars added to the
// lateral Timoshenko beam) and tapered elements: against another package's
// matrices, closed forms and fine meshes of uniform elements.
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/io/matrix_market.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include "test_helpers.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <cmath>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

using namespace gyrokit;

namespace {

constexpr double pi = 3.14159265358979323846;

// ROSS's rotor_example (data/ross_rotor_example), read off its exported matrices: steel
// E = 211 GPa, G = 81.2 GPa, rho = 7810, 6 elements of 0.25 m, 50 mm; two equal disks
// (280 mm, bore 50 mm, 70 mm wide) from their geometry at 0.5 and 1.0 m; bearings
// kxx = 1 MN/m, kyy = 0.8 MN/m at both ends (as in Friswell et al. Example 5.9.2),
// nothing axial or torsional.
const char* ross_fe_scene = R"(
[model]
type = "fe_rotor"
dofs_per_node = 6
E = 211e9
poisson = 0.2992610837438423
density = 7810
[[model.shaft]]
length = 1.5
elements = 6
outer_diameter = 0.05
[[model.disk]]
z = 0.5
outer_diameter = 0.28
inner_diameter = 0.05
width = 0.07
[[model.disk]]
z = 1.0
outer_diameter = 0.28
inner_diameter = 0.05
width = 0.07
[[model.bearing]]
z = 0.0
kxx = 1e6
kyy = 0.8e6
[[model.bearing]]
z = 1.5
kxx = 1e6
kyy = 0.8e6
)";

// Sorted positive imaginary parts of the eigenvalues (rad/s), |lambda| above `floor`.
std::vector<double> frequencies(const QuadraticSpectrum& s, double floor) {
    std::vector<double> f;
    for (const Mode& m : s.modes)
        if (m.lambda.imag() > 0 && std::abs(m.lambda) > floor) f.push_back(m.lambda.imag());
    std::sort(f.begin(), f.end());
    return f;
}

// Undamped, non-spinning natural frequencies of a model (rad/s), rigid-body modes left out.
std::vector<double> natural_frequencies(const GyroscopicSystem& sys, double floor = 1e-3) {
    return frequencies(solve_at_speed(sys, 0.0), floor);
}

double root(double (*f)(double, void*), void* data, double lo, double hi) {
    gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_function F{f, data};
    gsl_root_fsolver_set(s, &F, lo, hi);
    double x = lo;
    for (int i = 0; i < 200; ++i) {
        gsl_root_fsolver_iterate(s);
        x = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0, 1e-15) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    return x;
}

}  // namespace

// ROSS (the Petrobras package) exports its 6-DOF model of this rotor; the DOF order per
// node there is [x, y, z, alpha, beta, theta], here [x, y, tx, ty, z, tz]. Both build the
// same element and disk matrices from the same data, so every entry agrees to rounding:
// entries are sums of a few terms of size |A|max, hence 1e-12 of the block's largest entry.
TEST_CASE("fe rotor 6 DOF: the ROSS example rotor from its geometry equals the exported M, K and G entry by entry",
          "[fe_rotor][six_dof][published]") {
    const Scene sc = parse_scene(ross_fe_scene, "ross_fe.toml");
    REQUIRE(sc.dofs() == 42);
    const std::string dir = std::string(GYROKIT_DATA_DIR) + "/ross_rotor_example/";
    const int to_ross[6] = {0, 1, 3, 4, 2, 5};   // ours -> ROSS local index
    const auto compare = [&](const Eigen::MatrixXd& ours, const Eigen::MatrixXd& ross, const char* what) {
        INFO(what);
        REQUIRE(ours.rows() == 42);
        const double scale = ross.cwiseAbs().maxCoeff();
        double worst = 0.0;
        for (int i = 0; i < 42; ++i)
            for (int j = 0; j < 42; ++j) {
                const int ri = 6 * (i / 6) + to_ross[i % 6], rj = 6 * (j / 6) + to_ross[j % 6];
                // Block scale: the largest entry of the same pair of DOF kinds.
                double block = 0.0;
                for (int a = 0; a < 7; ++a)
                    for (int b = 0; b < 7; ++b)
                        block = std::max(block, std::abs(ross(6 * a + to_ross[i % 6], 6 * b + to_ross[j % 6])));
                const double d = std::abs(ours(i, j) - ross(ri, rj));
                worst = std::max(worst, d / std::max(block, 1e-300 * scale));
                CHECK(d <= 1e-12 * std::max(block, 1e-300));
            }
        INFO("worst " << worst);
        CHECK(worst < 1e-12);
    };
    compare(Eigen::MatrixXd(sc.system.M), read_matrix_market(dir + "M.mtx"), "M");
    compare(Eigen::MatrixXd(sc.system.K), read_matrix_market(dir + "K.mtx"), "K");
    compare(Eigen::MatrixXd(sc.system.G), read_matrix_market(dir + "G.mtx"), "G");
    CHECK(sc.system.dofs.names[4] == "z0");
    CHECK(sc.system.dofs.names[5] == "tz0");
    CHECK(sc.system.dofs.units[4] == "m");
    CHECK(sc.system.dofs.units[5] == "rad");
    CHECK(sc.system.whirl_pairs.size() == 14);

    // The spectrum: the exporter's reference values at 500 rad/s (README of the model,
    // 3 decimals) and four zero eigenvalues (free axial translation and free torsion).
    const QuadraticSpectrum s = solve_at_speed(sc.system, 500.0);
    // The rigid-body eigenvalues are put apart, none is left among the modes.
    CHECK(s.rigid_body.size() == 4);
    for (const Mode& m : s.rigid_body) CHECK(std::abs(m.lambda) < 1e-3);
    for (const Mode& m : s.modes) CHECK(std::abs(m.lambda) > 1.0);
    const std::vector<double> f = frequencies(s, 0.1);
    const double published[] = {91.560, 96.457, 265.406, 305.353, 658.347, 774.350, 821.325, 1062.921};
    REQUIRE(f.size() >= 8);
    for (int i = 0; i < 8; ++i) CHECK(std::abs(f[i] - published[i]) <= 5e-4);
}

// Linear bar elements with consistent mass on a uniform mesh: the discrete modes of a
// fixed-free bar are sin(k z_j) with the continuum's k = (2n - 1) pi / (2 L), and their
// frequencies are exactly w_h = (c / h) sqrt(6 (1 - cos kh) / (2 + cos kh)), c the wave
// speed: to rounding (1e-12). The continuum value (2n - 1) pi c / (2 L) is approached as
// w_h / w - 1 = (kh)^2 / 24 + O(h^4).
TEST_CASE("fe rotor 6 DOF: axial and torsional modes of a fixed-free shaft equal the discrete closed form",
          "[fe_rotor][six_dof][validation]") {
    const double L = 2.0, E = 2.1e11, nu = 0.3, rho = 7800.0, G = E / (2 * (1 + nu));
    const int count = 40;
    FeRotor r = fe_uniform_shaft(L, count, 0.05, 0.02, E, nu, rho);
    r.motion = FeMotion::all;
    FeSupport clamp;
    clamp.node = 0;
    clamp.theta_x = clamp.theta_y = clamp.z = clamp.theta_z = true;
    r.supports.push_back(clamp);
    const FeRotorMatrices m = r.assemble();
    // The axial and the torsional DOFs alone (they are uncoupled from the lateral ones).
    for (const char* kind : {"z", "tz"}) {
        std::vector<int> idx;
        for (int i = 0; i < m.size(); ++i)
            if (m.dofs.names[i].rfind(kind, 0) == 0 && std::isdigit(static_cast<unsigned char>(m.dofs.names[i][std::string(kind).size()])))
                idx.push_back(i);
        REQUIRE(idx.size() == count);
        const Eigen::MatrixXd M = Eigen::MatrixXd(m.M)(idx, idx), K = Eigen::MatrixXd(m.K)(idx, idx);
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
        const double c = std::sqrt((std::string(kind) == "z" ? E : G) / rho), h = L / count;
        for (int n = 1; n <= 5; ++n) {
            const double k = (2 * n - 1) * pi / (2 * L), kh = k * h;
            const double discrete = c / h * std::sqrt(6 * (1 - std::cos(kh)) / (2 + std::cos(kh)));
            const double w = std::sqrt(es.eigenvalues()(n - 1));
            INFO(kind << " mode " << n);
            CHECK(w == Approx(discrete).epsilon(1e-12));
            const double continuum = k * c;
            CHECK(w / continuum - 1 == Approx(kh * kh / 24).epsilon(0.01));
        }
    }
    // Nothing couples them to the lateral DOFs.
    const Eigen::MatrixXd K = Eigen::MatrixXd(m.K), M = Eigen::MatrixXd(m.M), Gy = Eigen::MatrixXd(m.G);
    for (int i = 0; i < m.size(); ++i)
        for (int j = 0; j < m.size(); ++j) {
            const bool ai = m.dofs.names[i][0] == 'z' || m.dofs.names[i].rfind("tz", 0) == 0;
            const bool aj = m.dofs.names[j][0] == 'z' || m.dofs.names[j].rfind("tz", 0) == 0;
            if (ai != aj) CHECK((K(i, j) == 0 && M(i, j) == 0 && Gy(i, j) == 0));
        }
}

// Two disks J1, J2 on a shaft of torsional stiffness k = G J_p / l: free-free torsion
// w^2 = k (1/J1 + 1/J2) when the shaft's own inertia is negligible. With the shaft's
// inertia the exact frequency solves the continuous problem, theta = A cos(b z) + B sin(b z),
// b = w sqrt(rho / G), G J_p theta'(0) = -w^2 J1 theta(0), G J_p theta'(l) = w^2 J2 theta(l):
//   (G J_p b)^2 tan(b l) ... written without poles as
//   f(w) = (G J_p b)(J1 + J2) w^2 cos(b l) + ((G J_p b)^2 - J1 J2 w^4) sin(b l) = 0.
namespace {
struct TwoDisks {
    double GJ, rhoJ, l, J1, J2;
};
double two_disk_equation(double w, void* p) {
    const TwoDisks& d = *static_cast<TwoDisks*>(p);
    const double b = w * std::sqrt(d.rhoJ / d.GJ), g = d.GJ * b;
    return g * (d.J1 + d.J2) * w * w * std::cos(b * d.l) + (g * g - d.J1 * d.J2 * w * w * w * w) * std::sin(b * d.l);
}
}  // namespace

TEST_CASE("fe rotor 6 DOF: torsion of two disks on a shaft against the closed forms",
          "[fe_rotor][six_dof][validation]") {
    const double l = 0.8, d = 0.04, E = 2.1e11, nu = 0.3, G = E / (2 * (1 + nu));
    const double Jp = pi * std::pow(d, 4) / 32, J1 = 0.35, J2 = 0.8;
    const auto model = [&](double rho, int count) {
        FeRotor r = fe_uniform_shaft(l, count, d, 0.0, E, nu, rho);
        r.motion = FeMotion::all;
        r.disks.push_back({0, 20.0, 0.2, J1, 0.0, 0.0});
        r.disks.push_back({count, 35.0, 0.45, J2, 0.0, 0.0});
        // Lateral bearings, nothing axial or torsional: the shaft turns and slides freely.
        r.bearings.push_back({0, 1e7, 0, 0, 1e7, 0, 0, 0, 0});
        r.bearings.push_back({count, 1e7, 0, 0, 1e7, 0, 0, 0, 0});
        return r.assemble();
    };
    const auto torsion_frequency = [](const FeRotorMatrices& m) {
        std::vector<int> idx;
        for (int i = 0; i < m.size(); ++i)
            if (m.dofs.names[i].rfind("tz", 0) == 0) idx.push_back(i);
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(m.K)(idx, idx),
                                                                    Eigen::MatrixXd(m.M)(idx, idx));
        // The rigid-body rotation first (0 up to rounding of k), then the first torsional mode.
        CHECK(std::abs(es.eigenvalues()(0)) < 1e-9 * es.eigenvalues()(1));
        return std::sqrt(es.eigenvalues()(1));
    };
    const double k = G * Jp / l, massless = std::sqrt(k * (1 / J1 + 1 / J2));

    SECTION("shaft inertia negligible: w^2 = k (1/J1 + 1/J2)") {
        // rho = 1e-3 kg/m^3: the shaft's inertia rho J_p l = 2e-10 kg m^2 moves w by about
        // its ratio to J1, J2 (< 1e-9).
        CHECK(torsion_frequency(model(1e-3, 4)) == Approx(massless).epsilon(1e-8));
    }
    SECTION("steel shaft: the continuous solution, approached at second order") {
        TwoDisks p{G * Jp, 7800.0 * Jp, l, J1, J2};
        const double exact = root(two_disk_equation, &p, 0.5 * massless, 1.5 * massless);
        REQUIRE(two_disk_equation(0.5 * massless, &p) * two_disk_equation(1.5 * massless, &p) < 0);
        const double e8 = torsion_frequency(model(7800.0, 8)) / exact - 1;
        const double e16 = torsion_frequency(model(7800.0, 16)) / exact - 1;
        INFO("exact " << exact << " massless " << massless << " errors " << e8 << " " << e16);
        CHECK(exact < massless);   // the shaft's inertia lowers it
        CHECK(e8 > 0);             // consistent mass: from above
        CHECK(e8 / e16 == Approx(4.0).epsilon(0.02));
        CHECK(std::abs(e16) < 1e-6);
    }
    SECTION("the whole model: four zero eigenvalues (free axial and torsional rigid-body modes)") {
        const FeRotorMatrices m = model(7800.0, 8);
        const QuadraticSpectrum s = solve_at_speed(m.to_system(), 300.0);
        CHECK(s.rigid_body.size() == 4);
        for (const Mode& mode : s.modes) CHECK(std::abs(mode.lambda) > 1.0);
    }
}

// A tapered element integrates the interdependent-interpolation shape functions over the
// varying section; for a uniform section these integrals are the closed-form matrices.
// 6-point Gauss-Legendre is exact for them, so the two agree to rounding.
TEST_CASE("fe rotor tapered element: a uniform section through the tapered path equals the closed form",
          "[fe_rotor][tapered]") {
    for (const bool shear : {true, false})
        for (const bool rotary : {true, false}) {
            FeShaftElement e;
            e.length = 0.13;
            e.outer_diameter = 0.09;
            e.inner_diameter = 0.03;
            e.youngs_modulus = 2.05e11;
            e.poisson_ratio = 0.29;
            e.density = 7850;
            const FeElementMatrices a = fe_shaft_element_matrices(e, shear, rotary);
            e.outer_diameter_end = e.outer_diameter;
            e.inner_diameter_end = e.inner_diameter;
            const FeElementMatrices b = fe_shaft_element_matrices(e, shear, rotary);
            INFO("shear " << shear << " rotary " << rotary);
            CHECK((a.K - b.K).cwiseAbs().maxCoeff() <= 1e-13 * a.K.cwiseAbs().maxCoeff());
            CHECK((a.M - b.M).cwiseAbs().maxCoeff() <= 1e-13 * a.M.cwiseAbs().maxCoeff());
            if (rotary) CHECK((a.G - b.G).cwiseAbs().maxCoeff() <= 1e-13 * a.G.cwiseAbs().maxCoeff());
            CHECK((a.K_axial - b.K_axial).cwiseAbs().maxCoeff() <= 1e-13 * a.K_axial.cwiseAbs().maxCoeff());
            CHECK((a.M_torsion - b.M_torsion).cwiseAbs().maxCoeff() <= 1e-13 * a.M_torsion.cwiseAbs().maxCoeff());
        }
}

// A conical cantilever (120 -> 40 mm over 1 m, bore 20 -> 10 mm): tapered elements against
// meshes of uniform elements (each with the section at its middle). Both converge to the
// same continuum: the stepped meshes at second order in h (midpoint sections), the tapered
// ones at second order as well (linear bars; a beam this thick has Phi >> 1 per element,
// where the interdependent interpolation is second order, docs/fe_rotor.md): both orders
// checked from three meshes each, each sequence extrapolated (Richardson with the
// observed ratio), and the tapered sequence must converge to the stepped one's limit.
TEST_CASE("fe rotor tapered element: a conical shaft converges to fine meshes of uniform elements",
          "[fe_rotor][tapered][validation]") {
    const double L = 1.0, o0 = 0.12, o1 = 0.04, i0 = 0.02, i1 = 0.01;
    const auto cantilever = [&](int count, bool tapered) {
        FeRotor r;
        r.motion = FeMotion::all;
        for (int k = 0; k < count; ++k) {
            FeShaftElement e;
            e.length = L / count;
            e.youngs_modulus = 2.1e11;
            e.poisson_ratio = 0.3;
            e.density = 7800;
            const double a = static_cast<double>(k) / count, b = static_cast<double>(k + 1) / count;
            if (tapered) {
                e.outer_diameter = o0 + a * (o1 - o0);
                e.inner_diameter = i0 + a * (i1 - i0);
                e.outer_diameter_end = o0 + b * (o1 - o0);
                e.inner_diameter_end = i0 + b * (i1 - i0);
            } else {
                const double c = 0.5 * (a + b);
                e.outer_diameter = o0 + c * (o1 - o0);
                e.inner_diameter = i0 + c * (i1 - i0);
            }
            r.elements.push_back(e);
        }
        FeSupport clamp;
        clamp.theta_x = clamp.theta_y = clamp.z = clamp.theta_z = true;
        r.supports.push_back(clamp);
        const FeRotorMatrices m = r.assemble();
        // The three lowest bending frequencies (x-z plane), the first two axial and torsional ones.
        std::vector<double> f;
        for (const char* kind : {"x", "z", "tz"}) {
            std::vector<int> idx;
            for (int i = 0; i < m.size(); ++i) {
                const std::string& n = m.dofs.names[i];
                const bool bending = std::string(kind) == "x" && (n[0] == 'x' || n.rfind("ty", 0) == 0);
                const std::size_t len = std::string(kind).size();
                if (bending || (std::string(kind) != "x" && n.compare(0, len, kind) == 0 &&
                                std::isdigit(static_cast<unsigned char>(n[len]))))
                    idx.push_back(i);
            }
            Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(m.K)(idx, idx),
                                                                        Eigen::MatrixXd(m.M)(idx, idx));
            for (int k = 0; k < (std::string(kind) == "x" ? 3 : 2); ++k) f.push_back(std::sqrt(es.eigenvalues()(k)));
        }
        return f;
    };
    const std::vector<double> t1 = cantilever(40, true), t2 = cantilever(80, true), t4 = cantilever(160, true);
    const std::vector<double> s1 = cantilever(100, false), s2 = cantilever(200, false), s4 = cantilever(400, false);
    REQUIRE(t1.size() == 7);
    for (std::size_t i = 0; i < t1.size(); ++i) {
        const double rs = (s1[i] - s2[i]) / (s2[i] - s4[i]), rt = (t1[i] - t2[i]) / (t2[i] - t4[i]);
        const double stepped = s4[i] - (s2[i] - s4[i]) / (rs - 1), tapered = t4[i] - (t2[i] - t4[i]) / (rt - 1);
        INFO("frequency " << i << " tapered " << t1[i] << " " << t2[i] << " " << t4[i] << " (ratio " << rt
                          << ") stepped " << s1[i] << " " << s2[i] << " " << s4[i] << " (ratio " << rs
                          << ") extrapolated " << tapered << " " << stepped);
        CHECK(rs == Approx(4.0).epsilon(0.05));   // stepped: second order
        CHECK(rt == Approx(4.0).epsilon(0.15));   // tapered: second order too (Phi >> 1, bars)
        // The tapered meshes tend to the stepped meshes' limit: the finest one's distance to
        // it is its own Richardson error estimate (t2 - t4) / 3 within 50 %, and the
        // extrapolated tapered value removes most of that distance.
        const double estimate = (t2[i] - t4[i]) / 3;
        CHECK((t4[i] - stepped) / estimate == Approx(1.0).margin(0.5));
        CHECK(std::abs(tapered - stepped) <= std::max(0.2 * std::abs(t4[i] - stepped), 1e-6 * stepped));
    }
}

TEST_CASE("fe rotor scene: dofs_per_node, axial and torsional supports, thrust bearings, tapered sections, mm",
          "[fe_rotor][six_dof][scene]") {
    const std::string base = R"(
[model]
type = "fe_rotor"
material = "steel"
)";
    SECTION("a clamped end holds all six DOFs, a pinned one what it names") {
        const Scene sc = parse_scene(base + R"(dofs_per_node = 6
[[model.shaft]]
length = 1.0
elements = 2
outer_diameter = 0.05
[[model.support]]
z = 0.0
type = "clamped"
[[model.support]]
z = 1.0
torsion = true
[[model.bearing]]
z = 0.5
k = 1e6
kzz = 2e6
czz = 30
)",
                                     "six.toml");
        CHECK(sc.dofs() == 18 - 6 - 3);
        const auto& n = sc.system.dofs.names;
        CHECK(std::find(n.begin(), n.end(), "z2") != n.end());
        CHECK(std::find(n.begin(), n.end(), "tz2") == n.end());
        CHECK(std::find(n.begin(), n.end(), "x2") == n.end());
        const int z1 = static_cast<int>(std::find(n.begin(), n.end(), "z1") - n.begin());
        const FeRotorMatrices m = sc.fe_rotor()->assemble();
        CHECK(m.D.coeff(z1, z1) == 30.0);
    }
    SECTION("lengths in mm give the same model as in m") {
        const std::string m_text = base + R"(
[[model.shaft]]
length = 0.4
elements = 4
outer_diameter = 0.06
outer_diameter_end = 0.04
inner_diameter = 0.01
[[model.disk]]
z = 0.2
outer_diameter = 0.2
inner_diameter = 0.05
width = 0.03
[[model.bearing]]
z = 0.0
k = 1e7
[[model.bearing]]
z = 0.4
k = 1e7
)";
        const std::string mm_text = base + R"(length_unit = "mm"
[[model.shaft]]
length = 400
elements = 4
outer_diameter = 60
outer_diameter_end = 40
inner_diameter = 10
[[model.disk]]
z = 200
outer_diameter = 200
inner_diameter = 50
width = 30
[[model.bearing]]
z = 0
k = 1e7
[[model.bearing]]
z = 400
k = 1e7
)";
        const Scene a = parse_scene(m_text, "m.toml"), b = parse_scene(mm_text, "mm.toml");
        REQUIRE(a.dofs() == b.dofs());
        const Eigen::MatrixXd Ma(a.system.M), Mb(b.system.M), Ka(a.system.K), Kb(b.system.K);
        CHECK((Ma - Mb).cwiseAbs().maxCoeff() <= 1e-13 * Ma.cwiseAbs().maxCoeff());
        CHECK((Ka - Kb).cwiseAbs().maxCoeff() <= 1e-13 * Ka.cwiseAbs().maxCoeff());
        // The section's elements are tapered, end to end.
        REQUIRE(a.fe_rotor()->elements.size() == 4);
        CHECK(a.fe_rotor()->elements[1].outer_diameter == Approx(0.055).epsilon(1e-14));
        CHECK(*a.fe_rotor()->elements[1].outer_diameter_end == Approx(0.05).epsilon(1e-14));
        CHECK(*a.fe_rotor()->elements[3].outer_diameter_end == Approx(0.04).epsilon(1e-14));
        CHECK(*a.fe_rotor()->elements[3].inner_diameter_end == Approx(0.01).epsilon(1e-14));
    }
    SECTION("bad input: one line naming key, value and range") {
        const std::string shaft = "[[model.shaft]]\nlength = 1.0\nouter_diameter = 0.05\n";
        CHECK_THAT(test::scene_error(base + "dofs_per_node = 5\n" + shaft),
                   Catch::Contains("dofs_per_node = 5") && Catch::Contains("4 (lateral) or 6"));
        CHECK_THAT(test::scene_error(base + "dofs_per_node = 8\n" + shaft),
                   Catch::Contains("dofs_per_node = 8; allowed: 4 (lateral) or 6"));
        CHECK_THAT(test::scene_error(base + "length_unit = \"cm\"\n" + shaft), Catch::Contains("length_unit"));
        CHECK_THAT(test::scene_error(base + shaft + "[[model.bearing]]\nz = 0.0\nk = 1e6\nkzz = 1e6\n"),
                   Catch::Contains("kzz") && Catch::Contains("dofs_per_node = 6"));
        CHECK_THAT(test::scene_error(base + shaft + "[[model.support]]\nz = 0.0\naxial = true\n"),
                   Catch::Contains("axial") && Catch::Contains("dofs_per_node = 6"));
        CHECK_THAT(test::scene_error(base + shaft + "outer_diameter_end = 0.02\ninner_diameter = 0.03\n"),
                   Catch::Contains("inner_diameter"));
        CHECK_THAT(test::scene_error(base + shaft + "inner_diameter_end = 0.06\n"),
                   Catch::Contains("inner_diameter_end = 0.06") && Catch::Contains("outer"));
        CHECK_THAT(test::scene_error(base + shaft + "outer_diameter_end = -0.06\n"),
                   Catch::Contains("outer_diameter_end = -0.06"));
        CHECK_THAT(test::scene_error(base + "length_unit = \"mm\"\n" + shaft + "[[model.disk]]\nz = 0.5\nmass = 1\n"),
                   Catch::Contains("z = 0.5 mm is not a node"));
    }
}

// A rigid rotor of mass m_s on two bearings k_b, each on a pedestal m_p on springs k_p:
// the rotor's translation in x and the pedestals' (equal by symmetry) form the 2-DOF
// system [m_s 0; 0 2m_p] q'' + [2k_b -2k_b; -2k_b 2k_b + 2k_p] q = 0. The shaft is one
// element with E = 1e15 Pa: its bending stiffness 48EI/L^3 ~ 2e12 N/m against k_b = 1e7
// moves the frequencies by about k_b / k_shaft ~ 5e-6, hence 1e-5.
TEST_CASE("fe rotor pedestals: a rigid rotor on bearings on pedestal masses against the 2-DOF closed form",
          "[fe_rotor][pedestal][validation]") {
    FeRotor r = fe_uniform_shaft(0.5, 1, 0.1, 0.0, 1e15, 0.3, 7800);
    r.shear_deformation = false;
    const double kb = 1e7, kp = 3e7, mp = 25.0, cp = 0.0;
    r.bearings.push_back({0, kb, 0, 0, kb, 0, 0, 0, 0});
    r.bearings.push_back({1, kb, 0, 0, kb, 0, 0, 0, 0});
    r.pedestals.push_back({0, mp, kp, kp, cp, cp});
    r.pedestals.push_back({1, mp, kp, kp, cp, cp});
    const FeRotorMatrices m = r.assemble();
    REQUIRE(m.size() == 12);
    CHECK(m.dofs.names[8] == "px0");
    CHECK(m.dofs.names[11] == "py1");
    CHECK(m.dofs.nodes[8] == -1);
    const double ms = 7800 * pi * 0.01 / 4 * 0.5;
    // det([2kb - ms w2, -2kb; -2kb, 2kb + 2kp - 2mp w2]) = 0, a quadratic in w2.
    const double a = ms * 2 * mp, b = -(ms * (2 * kb + 2 * kp) + 2 * mp * 2 * kb), c = 2 * kb * 2 * kp;
    const double w1 = std::sqrt((-b - std::sqrt(b * b - 4 * a * c)) / (2 * a));
    const double w2 = std::sqrt((-b + std::sqrt(b * b - 4 * a * c)) / (2 * a));
    const std::vector<double> f = natural_frequencies(m.to_system());
    const auto near = [&](double w) {
        return std::count_if(f.begin(), f.end(), [&](double x) { return std::abs(x - w) <= 1e-5 * w; });
    };
    INFO("closed form " << w1 << " " << w2);
    CHECK(near(w1) == 2);   // x and y
    CHECK(near(w2) == 2);
    // Symmetric: K and M; the pedestal blocks carry -kb off the diagonal.
    const Eigen::MatrixXd K(m.K);
    CHECK((K - K.transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK(K(0, 8) == -kb);
    CHECK(K(8, 8) == kb + kp);
}

// Bearings of every kind on pedestals: a fluid-film bearing (evaluated per speed) on a
// pedestal gives the eigenvalues of the same rotor with constant bearings equal to the
// film's coefficients at that speed (the same matrices by two assembly paths: 1e-10).
TEST_CASE("fe rotor pedestals: a fluid-film bearing on a pedestal equals its coefficients as a constant bearing",
          "[fe_rotor][pedestal]") {
    const std::string head = R"(
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 0.6
elements = 6
outer_diameter = 0.05
[[model.disk]]
z = 0.3
outer_diameter = 0.25
width = 0.04
[[model.pedestal]]
z = 0.0
mass = 20
k = 5e7
c = 2e3
[[model.pedestal]]
z = 0.6
mass = 30
kxx = 4e7
kyy = 6e7
)";
    const std::string film = R"(
[[model.bearing]]
z = 0.0
type = "fluid_film"
diameter = 0.05
length = 0.02
clearance = 5e-5
viscosity = 0.02
load = 70
[[model.bearing]]
z = 0.6
k = 2e7
c = 500
)";
    const Scene a = parse_scene(head + film, "film.toml");
    REQUIRE(a.system.bearings.size() == 1);
    const double w = 600.0;
    const BearingCoefficients co = a.system.bearings[0].at(w);
    const std::string constant = fmt::format(R"(
[[model.bearing]]
z = 0.0
kxx = {}
kxy = {}
kyx = {}
kyy = {}
cxx = {}
cxy = {}
cyx = {}
cyy = {}
[[model.bearing]]
z = 0.6
k = 2e7
c = 500
)",
                                             co.K(0, 0), co.K(0, 1), co.K(1, 0), co.K(1, 1), co.C(0, 0), co.C(0, 1),
                                             co.C(1, 0), co.C(1, 1));
    const Scene b = parse_scene(head + constant, "constant.toml");
    const QuadraticPencil pa = a.system.at_speed(w), pb = b.system.at_speed(w);
    CHECK((pa.K - pb.K).cwiseAbs().maxCoeff() <= 1e-12 * pa.K.cwiseAbs().maxCoeff());
    CHECK((pa.C - pb.C).cwiseAbs().maxCoeff() <= 1e-12 * pa.C.cwiseAbs().maxCoeff());
    const QuadraticSpectrum sa = solve_at_speed(a.system, w), sb = solve_at_speed(b.system, w);
    REQUIRE(sa.modes.size() == sb.modes.size());
    for (std::size_t i = 0; i < sa.modes.size(); ++i)
        CHECK(std::abs(sa.modes[i].lambda - sb.modes[i].lambda) <= 1e-10 * std::abs(sb.modes[i].lambda));
    // A shaft held where a pedestal stands: every kind of bearing acts from the pedestal to
    // the ground (a table the same as a constant bearing).
    const std::string held = head + "[[model.support]]\nz = 0.0\n[[model.bearing]]\nz = 0.6\nk = 2e7\n";
    const Scene c = parse_scene(held + "[[model.bearing]]\nz = 0.0\nk = 3e7\n", "held.toml");
    const Scene d = parse_scene(held + "[[model.bearing]]\nz = 0.0\nspeeds = [0, 1000]\nk = [3e7, 3e7]\n",
                                "held_table.toml");
    const QuadraticPencil pc = c.system.at_speed(w), pd = d.system.at_speed(w);
    CHECK((pc.K - pd.K).cwiseAbs().maxCoeff() <= 1e-12 * pc.K.cwiseAbs().maxCoeff());
    CHECK((pc.C - pd.C).cwiseAbs().maxCoeff() <= 1e-12 * pc.C.cwiseAbs().maxCoeff());
    // Bad input.
    CHECK_THAT(test::scene_error(head + "[[model.bearing]]\nz = 0.1\nk = 1e6\n"),
               Catch::Contains("where no bearing stands"));
    CHECK_THAT(test::scene_error(head + film + "[[model.pedestal]]\nz = 0.0\nmass = 1\n"),
               Catch::Contains("a second pedestal at node 0"));
    CHECK_THAT(test::scene_error(head + film + "[[model.pedestal]]\nz = 0.3\nmass = 0\n"),
               Catch::Contains("mass = 0"));
}

// A bearing table written in the scene: speeds converted from rpm, coefficients linearly
// interpolated between its rows (checked halfway between the last two), missing ones 0.
TEST_CASE("fe rotor scene: a bearing table written in the scene (speeds in rpm) interpolates its rows",
          "[fe_rotor][scene][bearing_table]") {
    const std::string head = R"(
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 0.6
elements = 3
outer_diameter = 0.05
[[model.bearing]]
z = 0.6
k = 2e7
)";
    const Scene a = parse_scene(head + R"(
[[model.bearing]]
z = 0.0
speeds = [0, 3000, 6000]
speed_unit = "rpm"
kxx = [1e7, 2e7, 4e7]
kyy = [1.5e7, 2.5e7, 4.5e7]
kxy = [0, 1e6, 3e6]
c = [100, 200, 300]
)",
                                "inline.toml");
    REQUIRE(a.system.bearings.size() == 1);
    const BearingTable& t = a.system.bearings[0];
    CHECK(t.name == "table_0");
    CHECK(t.speeds[1] == Approx(3000 * pi / 30).epsilon(1e-15));
    const double w = 4500 * pi / 30;   // halfway between the last two rows
    const BearingCoefficients c = t.at(w);
    CHECK(c.K(0, 0) == Approx(3e7).epsilon(1e-14));
    CHECK(c.K(1, 1) == Approx(3.5e7).epsilon(1e-14));
    CHECK(c.K(0, 1) == Approx(2e6).epsilon(1e-14));
    CHECK(c.K(1, 0) == 0.0);
    CHECK(c.C(0, 0) == Approx(250).epsilon(1e-14));
    CHECK(c.C(1, 1) == Approx(250).epsilon(1e-14));
    CHECK(c.C(0, 1) == 0.0);
    const auto bad = [&](const std::string& rows) { return test::scene_error(head + "[[model.bearing]]\nz = 0.0\n" + rows); };
    CHECK_THAT(bad("speeds = [0, 100]\nkxx = [1e7]\n"), Catch::Contains("kxx has 1 entries") &&
                                                           Catch::Contains("an array of 2 numbers"));
    CHECK_THAT(bad("speeds = [100]\nk = [1e7]\n"), Catch::Contains("at least 2 numbers"));
    CHECK_THAT(bad("speeds = [100, 50]\nk = [1e7, 2e7]\n"), Catch::Contains("strictly increasing"));
    CHECK_THAT(bad("speeds = [3000, 1000]\nspeed_unit = \"rpm\"\nk = [1e7, 2e7]\n"),
               Catch::Contains("entry 2 = 1000 rpm does not exceed entry 1 = 3000"));
    CHECK_THAT(bad("speeds = [-60, 1000]\nspeed_unit = \"rpm\"\nk = [1e7, 2e7]\n"),
               Catch::Contains("entry 1 = -60 rpm; allowed: >= 0"));
    CHECK_THAT(bad("speeds = [0, 100]\nk = [1e7, 'a']\n"), Catch::Contains("entry 2 is not a finite number"));
    CHECK_THAT(bad("speeds = [0, 100]\nk = [1e7, 1e7]\ntable = \"x.csv\"\n"), Catch::Contains("table is given together with speeds"));
    CHECK_THAT(bad("speed_unit = \"rpm\"\nk = 1e7\n"), Catch::Contains("speed_unit needs speeds"));
    CHECK_THAT(bad("speeds = [0, 100]\nspeed_unit = \"furlong\"\nk = [1, 2]\n"), Catch::Contains("allowed: rad/s, Hz, rpm"));
}

// Two equal rigid disks (m, J) joined by a flexible coupling only, each on a bearing k_b:
// translation in phase w^2 = k_b / m', out of phase w^2 = (k_b + 2 k_lat) / m' (m' = m plus
// half the coupling's mass); torsion, free: w^2 = 2 k_t / J' (J' = J + Ip_c / 2); axial
// with thrust bearings k_z at both ends: k_z / m' and (k_z + 2 k_ax) / m'. Exact (1e-12).
TEST_CASE("fe rotor coupling: two disks joined by a flexible coupling against the closed forms",
          "[fe_rotor][coupling][validation]") {
    const double m = 12.0, J = 0.08, mc = 2.0, Ipc = 0.004, kb = 3e6, klat = 5e5, kt = 2e4, kax = 7e6, kz = 1e6;
    const Scene sc = parse_scene(fmt::format(R"(
[model]
type = "fe_rotor"
dofs_per_node = 6
length_unit = "mm"
[[model.shaft]]
type = "coupling"
length = 120
k_lateral = {}
k_bending = 1e4
k_axial = {}
k_torsion = {}
mass = {}
Id = 0.002
Ip = {}
[[model.disk]]
z = 0
mass = {}
Id = 0.05
Ip = {}
[[model.disk]]
z = 120
mass = {}
Id = 0.05
Ip = {}
[[model.bearing]]
z = 0
k = {}
kzz = {}
[[model.bearing]]
z = 120
k = {}
kzz = {}
)",
                                             klat, kax, kt, mc, Ipc, m, J, m, J, kb, kz, kb, kz),
                                 "coupling.toml");
    REQUIRE(sc.dofs() == 12);
    const double mm = m + mc / 2, JJ = J + Ipc / 2;
    const auto pair_frequencies = [&](const char* kind) {
        std::vector<int> idx;
        for (int i = 0; i < sc.dofs(); ++i)
            if (sc.system.dofs.names[i] == std::string(kind) + "0" || sc.system.dofs.names[i] == std::string(kind) + "1")
                idx.push_back(i);
        REQUIRE(idx.size() == 2);
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(sc.system.K)(idx, idx),
                                                                    Eigen::MatrixXd(sc.system.M)(idx, idx));
        return es.eigenvalues();
    };
    const Eigen::Vector2d x = pair_frequencies("x"), t = pair_frequencies("tz"), a = pair_frequencies("z");
    CHECK(x(0) == Approx(kb / mm).epsilon(1e-12));
    CHECK(x(1) == Approx((kb + 2 * klat) / mm).epsilon(1e-12));
    CHECK(std::abs(t(0)) < 1e-9 * t(1));
    CHECK(t(1) == Approx(2 * kt / JJ).epsilon(1e-12));
    CHECK(a(0) == Approx(kz / mm).epsilon(1e-12));
    CHECK(a(1) == Approx((kz + 2 * kax) / mm).epsilon(1e-12));
    // The coupling's polar inertia is gyroscopic, half at each node.
    const Eigen::MatrixXd G(sc.system.G);
    CHECK(G.sum() == 0.0);
    CHECK(G.cwiseAbs().maxCoeff() == Approx(J + Ipc / 2).epsilon(1e-15));
    // Bad input.
    const std::string head = "[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n[[model.shaft]]\nlength = 0.2\n"
                             "outer_diameter = 0.05\n[[model.shaft]]\ntype = \"coupling\"\nlength = 0.05\n";
    CHECK_THAT(test::scene_error(head + "k_lateral = 1e6\n"), Catch::Contains("k_bending' is missing"));
    CHECK_THAT(test::scene_error(head + "k_lateral = -1\nk_bending = 1\n"), Catch::Contains("k_lateral = -1"));
    CHECK_THAT(test::scene_error(head + "k_lateral = 1\nk_bending = 1\nk_torsion = 1\n"),
               Catch::Contains("dofs_per_node = 6"));
    CHECK_THAT(test::scene_error(head + "k_lateral = 1\nk_bending = 1\nouter_diameter = 0.1\n"),
               Catch::Contains("unknown key 'outer_diameter'"));
}
