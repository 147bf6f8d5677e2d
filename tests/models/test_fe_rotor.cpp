// Finite-element rotor: structure of the assembled matrices, closed-form beam
// frequencies (Euler-Bernoulli, Timoshenko, spinning Timoshenko), mesh
// convergence, sparse vs dense solvers, a 100,000-DOF model, and the published
// two-disk rotor of Friswell et al. (Examples 5.9.1 and 5.9.2).
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <string>

using namespace gyrokit;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double E = 2.1e11, nu = 0.3, rho = 7850.0;

// Natural frequencies (rad/s, ascending) of the undamped non-rotating model.
std::vector<double> frequencies_at_rest(const FeRotorMatrices& m) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(m.K), Eigen::MatrixXd(m.M));
    std::vector<double> w;
    for (int i = 0; i < es.eigenvalues().size(); ++i) w.push_back(std::sqrt(std::max(0.0, es.eigenvalues()(i))));
    return w;
}

FeRotor pinned_pinned(double L, int count, double d_o, double d_i) {
    FeRotor r = fe_uniform_shaft(L, count, d_o, d_i, E, nu, rho);
    r.supports.push_back({0, true, true, false, false});
    r.supports.push_back({count, true, true, false, false});
    return r;
}

// Spinning Timoshenko beam, pinned at both ends, mode sin(alpha z): the
// frequency equation for r = x + i y ~ e^{i w t} (w > 0 forward, w < 0 backward):
// (kGA a^2 - rho A w^2)(E I a^2 + kGA - rho I w^2 + 2 rho I W w) - (kGA a)^2 = 0.
double spinning_timoshenko(const FeSection& s, double a, double W, double sign) {
    const double kGA = s.shear_coefficient * s.shear_modulus * s.area, EI = E * s.second_moment;
    const double rA = rho * s.area, rI = rho * s.second_moment;
    auto f = [&](double w) {
        return (kGA * a * a - rA * w * w) * (EI * a * a + kGA - rI * w * w + 2 * rI * W * w) - kGA * kGA * a * a;
    };
    const double step = 1.0;   // rad/s; f > 0 at w = 0, the first sign change is the lowest root
    double lo = 0.0, hi = sign * step;
    while (f(hi) > 0) {
        lo = hi;
        hi += sign * step;
    }
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) > 0 ? lo : hi) = mid;
    }
    return std::abs(0.5 * (lo + hi));
}

// A stepped hollow rotor with disks and anisotropic, cross-coupled bearings.
FeRotor machine(int count, double kxy, double cxy) {
    FeRotor r;
    for (int e = 0; e < count; ++e) {
        FeShaftElement s;
        s.length = 1.5 / count;
        s.outer_diameter = 0.06 + 0.02 * std::sin(3.0 * e / count);
        s.inner_diameter = (e % 3 == 0) ? 0.02 : 0.0;
        s.youngs_modulus = E;
        s.poisson_ratio = nu;
        s.density = rho;
        r.elements.push_back(s);
    }
    r.disks.push_back({count / 3, 12.0, 0.09, 0.16, 1e-4, 0.0});
    r.disks.push_back({(2 * count) / 3, 8.0, 0.05, 0.09, 0.0, 0.0});
    r.bearings.push_back({count / 10, 2e7, kxy, -kxy, 3e7, 400.0, cxy, -cxy, 600.0});
    r.bearings.push_back({count - count / 10, 3e7, 0.0, 0.0, 2.5e7, 500.0, 0.0, 0.0, 500.0});
    return r;
}

// The model at standstill solved by dense QZ (all modes) and by ARPACK (the
// `modes` lowest), both with the model's whirl pairs.
struct AtRest {
    QuadraticSpectrum dense, qz;   // the default dense method, and QZ
    SparseSpectrum sparse;
    AtRest(const FeRotorMatrices& m, int modes) {
        const SparsePencil p = m.at_speed(0.0);
        const QuadraticPencil q{Eigen::MatrixXd(p.M), Eigen::MatrixXd(p.C), Eigen::MatrixXd(p.K)};
        dense = solve_quadratic(q, {}, m.whirl_pairs);
        qz = solve_quadratic(q, {EigenMethod::ScaledQZ, false}, m.whirl_pairs);
        SparseEigenOptions o;
        o.modes = modes;
        sparse = solve_quadratic_sparse(p, o, m.whirl_pairs);
    }
};

double asym(const Eigen::SparseMatrix<double>& A, double sign) {
    const Eigen::SparseMatrix<double> At = A.transpose();
    return Eigen::MatrixXd(A - sign * At).cwiseAbs().maxCoeff() / std::max(1e-300, Eigen::MatrixXd(A).cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("fe rotor: matrix structure, DOF names and whirl pairs", "[fe_rotor]") {
    const FeRotorMatrices m = machine(30, 0.0, 0.0).assemble();
    REQUIRE(m.size() == 4 * 31);
    CHECK(m.dofs.names[0] == "x0");
    CHECK(m.dofs.names[4 * 7 + 3] == "ty7");
    CHECK(m.whirl_pairs.size() == 2 * 31);
    CHECK(asym(m.M, 1.0) < 1e-14);
    CHECK(asym(m.K, 1.0) < 1e-14);
    CHECK(asym(m.D, 1.0) < 1e-14);
    CHECK(asym(m.G, -1.0) < 1e-14);
    Eigen::LLT<Eigen::MatrixXd> llt{Eigen::MatrixXd(m.M)};
    CHECK(llt.info() == Eigen::Success);
    // Cross-coupled bearing stiffness makes K unsymmetric, exactly by 2 kxy.
    const FeRotorMatrices c = machine(30, 1e6, 0.0).assemble();
    CHECK(Eigen::MatrixXd(c.K - Eigen::SparseMatrix<double>(c.K.transpose())).cwiseAbs().maxCoeff() ==
          Approx(2e6).epsilon(1e-12));
    // The system passes the structural checks of GyroscopicSystem, also with
    // cross-coupled bearing damping (cxy != cyx: an unsymmetric D).
    CHECK_NOTHROW(m.to_system().validate("fe"));
    const GyroscopicSystem cross = machine(30, 0.0, 50.0).assemble().to_system();
    CHECK_NOTHROW(cross.validate("fe"));
    const Eigen::MatrixXd Dc = cross.damping_matrix();
    CHECK((Dc - Dc.transpose()).cwiseAbs().maxCoeff() == Approx(100.0).epsilon(1e-12));
    // Total mass: translational mass of the shaft plus disks, seen by a rigid x translation.
    Eigen::VectorXd ux = Eigen::VectorXd::Zero(m.size());
    for (int i = 0; i < m.size(); i += 4) ux(i) = 1.0;
    double mass = 20.0;
    for (const FeShaftElement& s : machine(30, 0, 0).elements) mass += rho * fe_section(s).area * s.length;
    CHECK(ux.dot(m.M * ux) == Approx(mass).epsilon(1e-12));
}

TEST_CASE("fe rotor: input errors name the item, key, value and range", "[fe_rotor]") {
    auto message = [](const FeRotor& r) {
        try {
            r.assemble();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    FeRotor r = fe_uniform_shaft(1.0, 4, 0.05, 0.0, E, nu, rho);
    FeRotor a = r;
    a.elements[2].length = -0.1;
    CHECK_THAT(message(a), Catch::Contains("element 2") && Catch::Contains("length") && Catch::Contains("-0.1"));
    a = r;
    a.elements[1].inner_diameter = 0.05;
    CHECK_THAT(message(a), Catch::Contains("element 1") && Catch::Contains("inner_diameter") &&
                               Catch::Contains("outer_diameter"));
    a = r;
    a.elements[0].density = 0.0;
    CHECK_THAT(message(a), Catch::Contains("density") && Catch::Contains("(0, inf)"));
    a = r;
    a.disks.push_back({5, 1.0, 0.1, 0.1, 0.0, 0.0});
    CHECK_THAT(message(a), Catch::Contains("disk 1") && Catch::Contains("node = 5") && Catch::Contains("[0, 4]"));
    a = r;
    a.bearings.push_back({1, 1e6, 0, 0, std::nan(""), 0, 0, 0, 0});
    CHECK_THAT(message(a), Catch::Contains("bearing 1") && Catch::Contains("kyy"));
    a = r;
    a.elements[3].poisson_ratio = 0.7;
    CHECK_THAT(message(a), Catch::Contains("poisson_ratio"));
    CHECK_THROWS_AS(FeRotor{}.assemble(), InputError);
}

TEST_CASE("fe rotor: Euler-Bernoulli pinned-pinned and free-free frequencies, fourth-order convergence",
          "[fe_rotor][validation]") {
    const double L = 1.0, d = 0.02;   // L/d = 50
    FeShaftElement probe;
    probe.outer_diameter = d;
    const FeSection s = fe_section(probe);
    const double c = std::sqrt(E * s.second_moment / (rho * s.area));

    std::vector<double> err;
    for (int count : {4, 8, 16, 32}) {
        FeRotor r = pinned_pinned(L, count, d, 0.0);
        r.shear_deformation = false;
        r.rotary_inertia = false;
        const std::vector<double> w = frequencies_at_rest(r.assemble());
        double e = 0.0;
        for (int k = 1; k <= 3; ++k) {
            CAPTURE(k);
            const double exact = std::pow(k * pi / L, 2) * c;
            CHECK(w[2 * (k - 1)] == Approx(w[2 * (k - 1) + 1]).epsilon(1e-9));   // x and y planes
            e = std::max(e, std::abs(w[2 * (k - 1)] - exact) / exact);
        }
        err.push_back(e);
    }
    CHECK(err.back() < 1e-5);
    for (std::size_t i = 1; i < err.size(); ++i) {
        CAPTURE(i);
        const double order = std::log2(err[i - 1] / err[i]);
        CHECK(order > 3.7);
        CHECK(order < 4.3);
    }

    // Free-free: four rigid-body modes, then beta_k L = 4.7300407, 7.8532046, 10.9956078.
    FeRotor f = fe_uniform_shaft(L, 40, d, 0.0, E, nu, rho);
    f.shear_deformation = false;
    f.rotary_inertia = false;
    const std::vector<double> w = frequencies_at_rest(f.assemble());
    for (int i = 0; i < 4; ++i) CHECK(w[i] < 1e-4 * w[4]);   // sqrt of rounding noise in w^2
    const double beta[3] = {4.730040744862704, 7.853204624095838, 10.995607838001671};
    for (int k = 0; k < 3; ++k) {
        CAPTURE(k);
        CHECK(w[4 + 2 * k] == Approx(std::pow(beta[k] / L, 2) * c).epsilon(1e-5));
    }
}

TEST_CASE("fe rotor: thick hollow Timoshenko shaft, pinned-pinned, at rest and spinning", "[fe_rotor][validation]") {
    const double L = 0.6, d_o = 0.15, d_i = 0.08;   // L/d = 4: shear and rotary inertia matter
    FeShaftElement probe;
    probe.outer_diameter = d_o;
    probe.inner_diameter = d_i;
    probe.youngs_modulus = E;
    probe.poisson_ratio = nu;
    const FeSection s = fe_section(probe);
    CHECK(s.shear_coefficient == Approx(cowper_shear_coefficient(nu, d_i / d_o)));

    // At rest: W = 0 in the spinning equation is the classical Timoshenko frequency equation.
    std::vector<double> err;
    for (int count : {8, 16, 32, 64}) {
        const std::vector<double> w = frequencies_at_rest(pinned_pinned(L, count, d_o, d_i).assemble());
        double e = 0.0;
        for (int k = 1; k <= 3; ++k) {
            const double exact = spinning_timoshenko(s, k * pi / L, 0.0, 1.0);
            e = std::max(e, std::abs(w[2 * (k - 1)] - exact) / exact);
        }
        err.push_back(e);
    }
    // Once the elements are short against the section (Phi >> 1) the interdependent
    // interpolation tends to linear w and psi: second-order convergence.
    CHECK(err.back() < 1e-3);
    for (std::size_t i = 1; i < err.size(); ++i) {
        CAPTURE(i);
        CHECK(std::log2(err[i - 1] / err[i]) > 1.8);
    }
    // The Euler-Bernoulli value is far off for this thick shaft: shear really is in the model.
    const double eb = std::pow(pi / L, 2) * std::sqrt(E * s.second_moment / (rho * s.area));
    CHECK(spinning_timoshenko(s, pi / L, 0.0, 1.0) < 0.9 * eb);

    // Spinning at W: forward whirl stiffens, backward softens; the split agrees with the closed form.
    const double W = 3000.0;
    const GyroscopicSystem sys = pinned_pinned(L, 64, d_o, d_i).assemble().to_system();
    const QuadraticSpectrum sp = solve_at_speed(sys, W);
    const Mode* fwd = nullptr;
    const Mode* bwd = nullptr;
    for (const Mode& m : sp.modes) {
        if (!fwd && m.whirl == Whirl::Forward) fwd = &m;
        if (!bwd && m.whirl == Whirl::Backward) bwd = &m;
    }
    REQUIRE(fwd);
    REQUIRE(bwd);
    const double wf = spinning_timoshenko(s, pi / L, W, 1.0), wb = spinning_timoshenko(s, pi / L, W, -1.0);
    CHECK(wf > wb * 1.005);
    CHECK(fwd->frequency() == Approx(wf).epsilon(2e-4));
    CHECK(bwd->frequency() == Approx(wb).epsilon(2e-4));
    CHECK(fwd->frequency() - bwd->frequency() == Approx(wf - wb).epsilon(1e-2));
    CHECK(std::abs(fwd->lambda.real()) < 1e-8 * wf);
    CHECK(sp.max_backward_error() < 1e-12);
}

TEST_CASE("fe rotor: single disk on a light shaft against the closed-form Jeffcott/gyroscopic rotor",
          "[fe_rotor][validation]") {
    // Massless-ish shaft pinned at both ends, disk at midspan: the translational
    // stiffness is 48 EI / L^3 and, by symmetry, the disk tilt does not couple, so
    // the lateral frequency is sqrt(48 EI / (m L^3)) for every speed, and the tilt
    // stiffness 12 EI / L gives Id v^2 -+ Ip W v - 12 EI / L = 0.
    const double L = 0.8, d = 0.02;
    FeRotor r = pinned_pinned(L, 8, d, 0.0);
    for (auto& e : r.elements) e.density = 1e-3;   // shaft mass 2e-4 kg vs disk 20 kg
    r.shear_deformation = false;
    const double m = 20.0, Id = 0.3, Ip = 0.5;
    r.disks.push_back({4, m, Id, Ip, 0.0, 0.0});
    FeShaftElement probe;
    probe.outer_diameter = d;
    const double EI = E * fe_section(probe).second_moment;
    const double W = 400.0;
    const QuadraticSpectrum sp = solve_at_speed(r.assemble().to_system(), W);
    const double wt = std::sqrt(48 * EI / (m * L * L * L)), kt = 12 * EI / L;
    const double wf = (Ip * W + std::sqrt(Ip * Ip * W * W + 4 * Id * kt)) / (2 * Id);
    const double wb = (-Ip * W + std::sqrt(Ip * Ip * W * W + 4 * Id * kt)) / (2 * Id);
    auto nearest = [&](double w) {
        double best = 1e300;
        for (const Mode& md : sp.modes) best = std::min(best, std::abs(md.frequency() - w) / w);
        return best;
    };
    CHECK(nearest(wt) < 1e-4);   // shaft mass 1e-5 of the disk mass
    CHECK(nearest(wf) < 1e-4);
    CHECK(nearest(wb) < 1e-4);
}

TEST_CASE("fe rotor: sparse shift-invert agrees with dense QZ on a 300-DOF rotor", "[fe_rotor][sparse]") {
    const FeRotorMatrices m = machine(74, 2e6, 100.0).assemble();
    REQUIRE(m.size() == 300);
    const FeRotorMatrices sym = machine(74, 2e6, 0.0).assemble();   // symmetric bearing damping
    const double W = 800.0;
    for (const FeRotorMatrices* model : {&sym, &m}) {
        const SparsePencil p = model->at_speed(W);
        const QuadraticSpectrum ref =
            solve_quadratic(QuadraticPencil{Eigen::MatrixXd(p.M), Eigen::MatrixXd(p.C), Eigen::MatrixXd(p.K)}, {},
                            model->whirl_pairs);
        // Through the system (cross-coupled damping included): the same pencil.
        const QuadraticSpectrum viasystem = solve_at_speed(model->to_system(), W);
        REQUIRE(viasystem.modes.size() == ref.modes.size());
        // The same pencil assembled two ways, solved by the same QZ: equal within the two
        // error bounds (the cross-coupled bearings' ill-conditioned pairs move with rounding).
        for (std::size_t i = 0; i < ref.modes.size(); ++i)
            CHECK(std::abs(viasystem.modes[i].lambda - ref.modes[i].lambda) <=
                  viasystem.modes[i].error_bound + ref.modes[i].error_bound);
        SparseEigenOptions o;
        o.modes = 8;
        const SparseSpectrum s = solve_quadratic_sparse(p, o, model->whirl_pairs);
        REQUIRE(s.modes.size() == 8);
        for (std::size_t i = 0; i < s.modes.size(); ++i) {
            CAPTURE(i);
            const Mode& sm = s.modes[i];
            const Mode& dm = ref.modes[i];   // both lists: lowest frequencies first
            // Within the two error bounds (cross-coupled, non-normal bearings raise the
            // condition numbers: the difference follows the BLAS's rounding, the bounds
            // cover it); both solvers stay backward stable (below) and vouch for the pair.
            CHECK(std::abs(sm.lambda - dm.lambda) <= sm.error_bound + dm.error_bound);
            CHECK(sm.error_bound <= kVouchTolerance * std::abs(sm.lambda));
            CHECK(dm.error_bound <= kVouchTolerance * std::abs(dm.lambda));
            CHECK(sm.whirl == dm.whirl);
            CHECK(sm.backward_error < 1e-12);
        }
    }
}

TEST_CASE("fe rotor: 100,000-DOF train assembles in O(n) and the sparse solver finds its lowest modes",
          "[fe_rotor][sparse][large]") {
    // 25,000 nodes: a long multi-span shaft on bearings every 50 elements, disks in between.
    // Two spans are longer (1.5 m and 1.3 m): their modes are the lowest, well apart
    // from the cluster of the 1 m spans (equal spans give nearly equal modes).
    const int count = 24999;
    FeRotor r = fe_uniform_shaft(count * 0.02, count, 0.08, 0.03, E, nu, rho);
    for (int e = 100 * 50; e < 101 * 50; ++e) r.elements[e].length = 0.03;
    for (int e = 300 * 50; e < 301 * 50; ++e) r.elements[e].length = 0.026;
    for (int k = 0; k <= count; k += 50) r.bearings.push_back({k, 5e8, 0, 0, 5e8, 2e3, 0, 0, 2e3});
    for (int k = 25; k < count; k += 50) r.disks.push_back({k, 15.0, 0.1, 0.18, 0.0, 0.0});
    const auto t0 = std::chrono::steady_clock::now();
    const FeRotorMatrices m = r.assemble();
    const double t_assembly = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    REQUIRE(m.size() == 100000);
    CHECK(t_assembly < 2.0);
    CHECK(m.M.nonZeros() <= 64LL * count);

    SparseEigenOptions o;
    o.modes = 4;
    o.max_iterations = 300;
    const SparseSpectrum s = solve_quadratic_sparse(m.at_speed(300.0), o, m.whirl_pairs);
    REQUIRE(s.modes.size() == 4);
    // Bound: the clamped-clamped frequency of the longest span (neighbouring spans
    // restrain the rotation at most as much as a clamp; disks and flexible bearings lower it).
    FeShaftElement probe;
    probe.outer_diameter = 0.08;
    probe.inner_diameter = 0.03;
    const FeSection sec = fe_section(probe);
    const double span = 50 * 0.03;
    const double w_cc = std::pow(4.730040744862704 / span, 2) * std::sqrt(E * sec.second_moment / (rho * sec.area));
    for (const Mode& md : s.modes) {
        CHECK(md.backward_error < 1e-10);
        CHECK(md.frequency() > 0.0);
        CHECK(md.frequency() < w_cc);
        CHECK(md.lambda.real() < 0.0);   // bearing damping reaches the lowest modes
    }
}

namespace {

// Friswell, Penny, Garvey & Lees, "Dynamics of Rotating Machines" (Cambridge
// University Press, 2010), Examples 5.9.1 and 5.9.2, as reproduced by ROSS
// (github.com/petrobras/ross): a 1.5 m steel shaft of 50 mm diameter in six
// Timoshenko elements of 0.25 m; E = 211 GPa, G = 81.2 GPa, rho = 7810 kg/m^3.
// Rigid disks 70 mm thick keyed on the shaft (bore = shaft diameter) at 0.5 m
// (280 mm) and 1.0 m (350 mm); short bearings at both ends, stiffness only.
constexpr double friswell_E = 211e9, friswell_G = 81.2e9, friswell_rho = 7810.0;

struct FriswellDisk {
    double mass, Id, Ip;
};

// A disk of width h, outer diameter d_o and bore d_i as in the book (and ROSS's
// DiskElement.from_geometry): m = rho pi h (do^2 - di^2)/4, Ip = m (do^2 + di^2)/8,
// Id = Ip/2 + m h^2/12 = m (3 (ro^2 + ri^2) + h^2)/12.
FriswellDisk friswell_disk(double h, double d_o, double d_i) {
    const double m = friswell_rho * pi * h * (d_o * d_o - d_i * d_i) / 4;
    const double Ip = m * (d_o * d_o + d_i * d_i) / 8;
    return {m, Ip / 2 + m * h * h / 12, Ip};
}

FeRotor friswell_rotor(double kxx, double kyy) {
    FeRotor r;
    for (int e = 0; e < 6; ++e) {
        FeShaftElement s;
        s.length = 0.25;
        s.outer_diameter = 0.05;
        s.youngs_modulus = friswell_E;
        s.shear_modulus = friswell_G;
        s.poisson_ratio = friswell_E / (2 * friswell_G) - 1;   // 0.29926: enters Cowper's kappa only
        s.density = friswell_rho;
        r.elements.push_back(s);
    }
    const FriswellDisk d1 = friswell_disk(0.07, 0.28, 0.05), d2 = friswell_disk(0.07, 0.35, 0.05);
    r.disks.push_back({2, d1.mass, d1.Id, d1.Ip, 0.0, 0.0});
    r.disks.push_back({4, d2.mass, d2.Id, d2.Ip, 0.0, 0.0});
    r.bearings.push_back({0, kxx, 0, 0, kyy, 0, 0, 0, 0});
    r.bearings.push_back({6, kxx, 0, 0, kyy, 0, 0, 0, 0});
    return r;
}

}  // namespace

// Published values: ROSS, the open-source rotordynamics package that implements the
// book's element matrices (Cowper's shear coefficient, disk inertia from geometry).
// ROSS reports agreement with the book's own tables within their rounding (<= 0.002 %,
// ROSS pull request 1337); its printed values carry many more digits than the book's.
// 5.9.1 at 0 and 4000 rev/min: docs/examples/example_05_09_01.rst (commit 15f72537df19);
// 5.9.2 at 0 and 4000 rev/min: docs/examples/example_05_09_02.rst (commit 2e13eb18603c);
// 5.9.2 at 0, 150, 300 rad/s: ross/tests/test_rotor_assembly.py, test_campbell (commit
// 0103185ca42a; its 650.4 rad/s column is a torsional/axial mode of ROSS's 6-DOF nodes,
// outside a lateral model). All printed to 8 decimals in rad/s: rounding <= 5e-9 rad/s,
// i.e. <= 6.1e-11 relative for the lowest value (82.3 rad/s).
// Tolerance 1e-9 relative: 16 times the rounding, room for two different LAPACK
// eigensolvers, and still 1000 times below the smallest modelling change tried
// (G = E / 2(1 + 0.3) = 81.15 GPa instead of 81.2 GPa moves them by 1.0e-6, checked below;
// solid disks 1e-2, no shear 2e-3, the 6-element mesh error against 96 elements 5e-4).
// Measured: max 5.3e-11, every difference within the rounding of the published digits.
TEST_CASE("fe rotor: Friswell et al. Examples 5.9.1 and 5.9.2 (published natural frequencies)",
          "[fe_rotor][validation][published]") {
    // Element and disk data against ROSS's own documented values (ross/shaft_element.py and
    // ross/disk_element.py, commit 02e099517e1e): the shear parameter Phi of a hollow
    // Timoshenko element (L = 0.5, di = 0.05, do = 0.1, steel) and the 280 mm disk.
    FeShaftElement probe;
    probe.length = 0.5;
    probe.inner_diameter = 0.05;
    probe.outer_diameter = 0.1;
    probe.youngs_modulus = friswell_E;
    probe.shear_modulus = friswell_G;
    probe.poisson_ratio = friswell_E / (2 * friswell_G) - 1;
    const FeSection sec = fe_section(probe);
    const double Phi = 12 * friswell_E * sec.second_moment /
                       (sec.shear_coefficient * sec.shear_modulus * sec.area * probe.length * probe.length);
    CHECK(Phi == Approx(0.1571268472906404).epsilon(1e-13));
    const FriswellDisk d1 = friswell_disk(0.07, 0.28, 0.05);
    CHECK(std::abs(d1.mass - 32.58972765) < 5e-9);
    CHECK(std::abs(d1.Id - 0.17808928) < 5e-9);
    CHECK(d1.Ip == Approx(0.32956362089137037).epsilon(1e-14));

    const double rpm = pi / 30;   // rad/s per rev/min
    struct Case {
        const char* name;
        double kyy, speed;     // kxx = 1e6 N/m; speed in rad/s
        double published[6];   // rad/s, lowest first
    };
    const Case cases[] = {
        {"5.9.1, 0 rev/min", 1e6, 0.0,
         {86.65811435, 86.65811435, 274.31285391, 274.31285391, 716.78631221, 716.78631221}},
        {"5.9.1, 4000 rev/min", 1e6, 4000 * rpm,
         {85.389467, 87.7958637, 251.78460413, 294.71333087, 600.17936195, 827.07536193}},
        {"5.9.2, 0 rev/min", 0.8e6, 0.0,
         {82.65303734, 86.65811435, 254.52047828, 274.31285391, 679.48903239, 716.78631221}},
        {"5.9.2, 4000 rev/min", 0.8e6, 4000 * rpm,
         {82.32547398, 86.86369902, 239.64228361, 287.24958074, 583.48782916, 806.8872843}},
        {"5.9.2, 150 rad/s", 0.8e6, 150.0,
         {82.60929602, 86.68625235, 251.70037114, 276.87787937, 652.85679897, 742.60864608}},
        {"5.9.2, 300 rad/s", 0.8e6, 300.0,
         {82.48132723, 86.76734307, 245.49092844, 282.33294699, 614.05536277, 779.07778334}},
    };
    const double tol = 1e-9;
    double worst = 0.0;
    for (const Case& c : cases) {
        INFO(c.name);
        const QuadraticSpectrum sp = solve_at_speed(friswell_rotor(1e6, c.kyy).assemble().to_system(), c.speed);
        REQUIRE(sp.modes.size() >= 6);
        CHECK(sp.max_backward_error() < 1e-12);
        for (int i = 0; i < 6; ++i) {
            const Mode& m = sp.modes[static_cast<size_t>(i)];
            const double rel = std::abs(m.frequency() - c.published[i]) / c.published[i];
            INFO("mode " << i + 1 << ": " << std::setprecision(12) << m.frequency() << " rad/s, published "
                         << c.published[i] << ", relative difference " << rel);
            CHECK(rel <= tol);
            CHECK(std::abs(m.lambda.real()) < 1e-9 * c.published[i]);   // undamped
            // Spinning, every pair splits: the lower backward, the upper forward.
            if (c.speed > 0) CHECK(m.whirl == (i % 2 == 0 ? Whirl::Backward : Whirl::Forward));
            worst = std::max(worst, rel);
        }
    }
    CHECK(worst < tol);

    // The comparison resolves modelling choices: G from nu = 0.3 (81.15 GPa) is visible.
    FeRotor g = friswell_rotor(1e6, 1e6);
    for (FeShaftElement& e : g.elements) {
        e.shear_modulus = 0.0;
        e.poisson_ratio = 0.3;
    }
    const QuadraticSpectrum sg = solve_at_speed(g.assemble().to_system(), 4000 * rpm);
    double moved = 0.0;
    for (int i = 0; i < 6; ++i)
        moved = std::max(moved, std::abs(sg.modes[static_cast<size_t>(i)].frequency() - cases[1].published[i]) /
                                    cases[1].published[i]);
    CHECK(moved > 100 * tol);
}

TEST_CASE("fe rotor: the scene data/friswell_5_9_1.toml reproduces Example 5.9.1", "[fe_rotor][validation][published]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/friswell_5_9_1.toml");
    REQUIRE(sc.model_type() == "fe_rotor");
    CHECK(sc.dofs() == 28);
    REQUIRE(sc.speeds);
    CHECK(sc.speed_points().back() == Approx(4000 * pi / 30).epsilon(1e-15));
    // Same published values and tolerance as above (the scene's disk data have 12 digits).
    const double published[6] = {85.389467, 87.7958637, 251.78460413, 294.71333087, 600.17936195, 827.07536193};
    const QuadraticSpectrum sp = solve_at_speed(sc.system, 4000 * pi / 30);
    REQUIRE(sp.modes.size() >= 6);
    for (int i = 0; i < 6; ++i)
        CHECK(std::abs(sp.modes[static_cast<size_t>(i)].frequency() - published[i]) <= 1e-9 * published[i]);
}

TEST_CASE("fe rotor: double eigenvalues at standstill split into one forward and one backward circular mode",
          "[fe_rotor][whirl]") {
    // Isotropic supports at rest: every frequency is double and any basis of its
    // plane is a pair of eigenvectors, so the solver's own basis whirls at random.
    // Both solvers must return the circular forward and backward combinations.
    FeRotor r = pinned_pinned(1.2, 24, 0.05, 0.0);
    r.disks.push_back({8, 15.0, 0.1, 0.18, 0.0, 0.0});
    const FeRotorMatrices m = r.assemble();
    const AtRest rest(m, 8);
    for (const std::vector<Mode>* modes : {&rest.dense.modes, &rest.sparse.modes}) {
        const std::size_t count = std::min<std::size_t>(8, modes->size());
        for (std::size_t i = 0; i + 1 < count; i += 2) {
            const Mode &a = (*modes)[i], &b = (*modes)[i + 1];
            INFO((modes == &rest.dense.modes ? "dense" : "sparse") << " modes " << i << ", " << i + 1 << ": "
                                                               << a.lambda << " " << b.lambda << ", backward errors "
                                                               << a.backward_error << " " << b.backward_error);
            REQUIRE(std::abs(a.lambda - b.lambda) <= 1e-8 * std::abs(a.lambda));   // double
            CHECK(a.whirl == Whirl::Backward);   // listed by frequency: backward below forward
            CHECK(b.whirl == Whirl::Forward);
            for (const Mode* md : {&a, &b}) {
                // Still eigenvectors: QZ to rounding, ARPACK to its tolerance.
                CHECK(md->backward_error < (modes == &rest.dense.modes ? 1e-15 : 1e-11));
                // Circular orbit at every node: |x| = |y|, a quarter period apart.
                const double top = md->right.cwiseAbs().maxCoeff();
                for (const auto& [u, v] : m.whirl_pairs) {
                    CHECK(std::abs(std::abs(md->right(u)) - std::abs(md->right(v))) <= 1e-6 * top);
                    CHECK(std::abs(std::abs(std::arg(md->right(u) * std::conj(md->right(v)))) - pi / 2) *
                              std::abs(md->right(u)) <= 1e-5 * top);
                }
            }
        }
    }
}

TEST_CASE("fe rotor: a pair split by a small anisotropy keeps its planar modes", "[fe_rotor][whirl]") {
    // Bearings with kyy = kxx (1 + a): the frequencies split by 1e-9 .. 1e-6
    // relative, less than the 1e-6 that makes a pair a candidate, more than the
    // 1e-10 of a double eigenvalue. The modes are planar (x alone, y alone), and
    // every solver must return them so: QZ and the default dense method (its planes are
    // uncoupled groups, each solved apart) to 1e-6, classified planar; ARPACK, whose
    // window mixes the planes, within its vectors' accuracy on a pair split by 1.5e-9
    // relative at a = 1e-7, to 1e-3.
    for (const double a : {1e-7, 1e-5}) {
        FeRotor r = fe_uniform_shaft(1.2, 24, 0.05, 0.0, E, nu, rho);
        const double k = 5e7;
        r.bearings.push_back({0, k, 0.0, 0.0, k * (1 + a), 0.0, 0.0, 0.0, 0.0});
        r.bearings.push_back({24, k, 0.0, 0.0, k * (1 + a), 0.0, 0.0, 0.0, 0.0});
        const FeRotorMatrices m = r.assemble();
        const AtRest rest(m, 6);
        for (const std::vector<Mode>* modes : {&rest.qz.modes, &rest.dense.modes, &rest.sparse.modes}) {
            const bool is_qz = modes == &rest.qz.modes;
            INFO((is_qz ? "QZ" : modes == &rest.dense.modes ? "dense " + rest.dense.method : std::string("sparse"))
                 << ", anisotropy " << a);
            REQUIRE(std::abs((*modes)[1].lambda - (*modes)[0].lambda) < 1e-6 * std::abs((*modes)[0].lambda));
            for (std::size_t i = 0; i < 6; ++i) {
                CAPTURE(i);
                const Mode& md = (*modes)[i];
                double turn = 0.0;   // zero for a planar mode, +-1/2 for a circular one
                for (const auto& [u, v] : m.whirl_pairs) turn += (md.right(u) * std::conj(md.right(v))).imag();
                const bool is_sparse = modes == &rest.sparse.modes;
                CHECK(std::abs(turn) <= (is_sparse ? 1e-3 : 1e-6));   // planar to the vectors' accuracy
                if (!is_sparse) CHECK(md.whirl == Whirl::Planar);
            }
        }
    }
}

TEST_CASE("fe rotor: a free-free spinning shaft: rigid-body eigenvalues put apart by both solvers, the free "
          "precession at w Ip/Id",
          "[fe_rotor][rigid]") {
    const double L = 1.0, d = 0.05;
    const FeRotorMatrices m = fe_uniform_shaft(L, 20, d, 0.0, E, nu, rho).assemble();
    const GyroscopicSystem sys = m.to_system();
    // At rest: x, y, and the two tilts are free, each q = a + b t: eight zero eigenvalues.
    CHECK(solve_at_speed(sys, 0.0).rigid_body.size() == 8);
    const double w = 500.0;
    const QuadraticSpectrum s = solve_at_speed(sys, w);
    // Spinning: the gyroscopic moment couples the two tilts, which keep one zero
    // eigenvalue each and precess at Id nu = Ip w (rigid rotor, torque-free).
    CHECK(s.rigid_body.size() == 6);
    const double A = pi * d * d / 4, I = pi * std::pow(d, 4) / 64;
    const double Ip = 2 * rho * I * L, Id = rho * A * L * L * L / 12 + rho * I * L;
    REQUIRE(!s.modes.empty());
    // The elastic modes (the first at about 1450 rad/s) bend the precessing shaft a
    // little; the precession frequency of the model is 5e-7 below the rigid value.
    CHECK(s.modes[0].frequency() == Approx(w * Ip / Id).epsilon(1e-5));
    CHECK(s.modes[0].whirl == Whirl::Forward);
    for (const Mode& q : s.modes) CHECK(q.stability() == Stability::Neutral);
    // The sparse solver at target 0: P(0) = K is singular; the shift moves and the
    // modes equal the dense ones.
    SparseEigenOptions o;
    o.modes = 4;
    const SparseSpectrum sp = solve_quadratic_sparse(m.at_speed(w), o, m.whirl_pairs);
    CHECK(!sp.notes.empty());
    CHECK(!sp.rigid_body.empty());
    REQUIRE(sp.modes.size() == 4);
    // To 1e-10, or within the two error bounds: the precession at 1.87 rad/s is 1e-5 of
    // the model's frequency scale, so perturbations of K of rounding size move it by
    // up to 6e-4 (its bound); the two solvers differ by 1.6e-7 there.
    for (size_t k = 0; k < 4; ++k) {
        INFO("mode " << k << " sparse " << sp.modes[k].lambda << " dense " << s.modes[k].lambda << " bounds "
                     << sp.modes[k].error_bound << " " << s.modes[k].error_bound);
        CHECK(std::abs(sp.modes[k].lambda - s.modes[k].lambda) <=
              std::max(1e-10 * std::abs(s.modes[k].lambda), sp.modes[k].error_bound + s.modes[k].error_bound));
        CHECK(sp.modes[k].error_bound <= 1e-3 * std::abs(sp.modes[k].lambda));
    }
}

TEST_CASE("fe rotor: cross-coupled bearings: the stability threshold equals a bisection on the largest real part",
          "[fe_rotor][stability]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/fe_rotor.toml");
    const GyroscopicSystem& sys = sc.system;
    std::vector<double> speeds;
    for (int k = 0; k <= 40; ++k) speeds.push_back(10.0 * k);
    CampbellOptions co;
    co.modes = 6;
    const CampbellDiagram cd = campbell(sys, speeds, co);
    const std::vector<StabilityChange> changes = stability_changes(sys, cd);
    REQUIRE(changes.size() == 1);
    CHECK(changes[0].becomes_unstable);
    // Independent: no tracking, no error bounds: the largest Re lambda of all modes.
    const auto growth = [&](double w) {
        double g = -1e300;
        for (const Mode& q : solve_at_speed(sys, w).modes) g = std::max(g, q.lambda.real());
        return g;
    };
    double a = 200.0, b = 300.0;
    REQUIRE(growth(a) < 0.0);
    REQUIRE(growth(b) > 0.0);
    while (b - a > 1e-12 * b) (growth(0.5 * (a + b)) > 0.0 ? b : a) = 0.5 * (a + b);
    // The bisection on the raw real part is uncertain by its mode's error bound (about
    // 7e-7 1/s, normwise) over the slope (about 1.1e-4 1/s per rad/s); the change's own
    // bound is sharp (1e-7 rad/s or so, docs/numerics.md): the two agree within the sum.
    const double mid = 0.5 * (a + b);
    double ref_error = 0.0, largest = -1e300;
    for (const Mode& q : solve_at_speed(sys, mid).modes)
        if (q.lambda.real() > largest) largest = q.lambda.real(), ref_error = q.error_bound;
    const double slope = (growth(mid + 1.0) - growth(mid - 1.0)) / 2.0;
    REQUIRE(slope > 0.0);
    const double bound = changes[0].bound;
    CHECK(bound > 0.0);
    CHECK(bound < 1e-6 * changes[0].speed);   // a bound that says something
    CHECK(std::abs(changes[0].speed - mid) <= bound + ref_error / slope);
    CHECK(std::abs(changes[0].speed - 251.609) <= 1e-3 + bound);
    CHECK(unstable_ranges(cd).size() == 1);
}

TEST_CASE("fe rotor: a dense diagram of the K lowest modes keeps the others for a verdict over every mode",
          "[fe_rotor][stability]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/fe_rotor.toml");
    std::vector<double> speeds;
    for (int k = 0; k <= 40; ++k) speeds.push_back(100.0 * k);
    CampbellOptions one, all;
    one.modes = 1;
    const CampbellDiagram low = campbell(sc.system, speeds, one), every = campbell(sc.system, speeds, all);
    REQUIRE(low.branches.size() == 1);
    CHECK(low.untracked.size() + 1 == every.branches.size());
    // The tracked mode is stable; modes 2 and 4 are not (the bearings' cross-coupling), and the
    // verdict over every mode finds them at the same speeds as the diagram of every mode.
    CHECK(unstable_ranges(low).empty());
    const auto a = unstable_ranges(low, true), b = unstable_ranges(every);
    REQUIRE(a.size() == b.size());
    REQUIRE(!a.empty());
    for (size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].branch == b[i].branch);
        CHECK(a[i].from == b[i].from);
        CHECK(a[i].to == b[i].to);
    }
    CHECK(low.untracked.front().points.front().mode.right.size() == 0);   // eigenvalues only
}

TEST_CASE("fe rotor: a DOF whose response is zero by symmetry shows no peak, bounded or not",
          "[fe_rotor][response]") {
    // A centred disk on a symmetric shaft: the midspan slopes tx2, ty2 are zero up to rounding,
    // and their rounding wiggles were once called undamped resonances.
    const Scene sc = parse_scene("[model]\ntype = \"fe_rotor\"\nmaterial = \"steel\"\n"
                                 "[[model.shaft]]\nlength = 1.0\nelements = 4\nouter_diameter = 0.05\n"
                                 "[[model.disk]]\nz = 0.5\nmass = 20\nId = 0.1\nIp = 0.2\nunbalance = 1e-4\n"
                                 "[[model.bearing]]\nz = 0.0\nk = 1e7\nc = 500\n"
                                 "[[model.bearing]]\nz = 1.0\nk = 1e7\nc = 500\n",
                                 "sym.toml");
    const ResponseCurve rc = unbalance_response(sc.system, SpeedRange{10.0, 600.0, 119}.points());
    const auto maxima = response_maxima(rc, response_extrema(sc.system, rc));
    for (const auto& m : maxima) {
        CAPTURE(sc.system.dofs.names[static_cast<size_t>(m.dof)]);
        CHECK(m.bounded);
        CHECK(std::isfinite(m.amplitude));
    }
    // The midspan translation peaks at the first critical speed.
    const auto x2 = std::find(sc.system.dofs.names.begin(), sc.system.dofs.names.end(), "x2") - sc.system.dofs.names.begin();
    CHECK(maxima[static_cast<size_t>(x2)].refined);
}
