// Finite-element rotor: structure of the assembled matrices, closed-form beam
// frequencies (Euler-Bernoulli, Timoshenko, spinning Timoshenko), mesh
// convergence, sparse vs dense solvers, and a 100,000-DOF model.
#include "core/error.hpp"
#include "eig/quadratic_eigensolver.hpp"
#include "eig/sparse_eigensolver.hpp"
#include "models/fe_rotor.hpp"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>

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

double asym(const Eigen::SparseMatrix<double>& A, double sign) {
    const Eigen::SparseMatrix<double> At = A.transpose();
    return Eigen::MatrixXd(A - sign * At).cwiseAbs().maxCoeff() / std::max(1e-300, Eigen::MatrixXd(A).cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("fe rotor: matrix structure, DOF names and whirl pairs", "[fe_rotor]") {
    const FeRotorMatrices m = machine(30, 0.0, 0.0).assemble();
    REQUIRE(m.size() == 4 * 31);
    CHECK(m.dof_names[0] == "x0");
    CHECK(m.dof_names[4 * 7 + 3] == "ty7");
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
    // The dense system passes the structural checks of GyroscopicSystem.
    CHECK_NOTHROW(m.to_dense().validate("fe"));
    CHECK_THROWS_AS(machine(30, 0.0, 50.0).assemble().to_dense(), InputError);
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
    CHECK_THAT(message(a), Catch::Contains("disk 0") && Catch::Contains("node = 5") && Catch::Contains("[0, 4]"));
    a = r;
    a.bearings.push_back({1, 1e6, 0, 0, std::nan(""), 0, 0, 0, 0});
    CHECK_THAT(message(a), Catch::Contains("bearing 0") && Catch::Contains("kyy"));
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
            const double exact = std::pow(k * pi / L, 2) * c;
            CHECK(w[2 * (k - 1)] == Approx(w[2 * (k - 1) + 1]).epsilon(1e-9));   // x and y planes
            e = std::max(e, std::abs(w[2 * (k - 1)] - exact) / exact);
        }
        err.push_back(e);
    }
    CHECK(err.back() < 1e-5);
    for (std::size_t i = 1; i < err.size(); ++i) {
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
    for (int k = 0; k < 3; ++k) CHECK(w[4 + 2 * k] == Approx(std::pow(beta[k] / L, 2) * c).epsilon(1e-5));
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
    for (std::size_t i = 1; i < err.size(); ++i) CHECK(std::log2(err[i - 1] / err[i]) > 1.8);
    // The Euler-Bernoulli value is far off for this thick shaft: shear really is in the model.
    const double eb = std::pow(pi / L, 2) * std::sqrt(E * s.second_moment / (rho * s.area));
    CHECK(spinning_timoshenko(s, pi / L, 0.0, 1.0) < 0.9 * eb);

    // Spinning at W: forward whirl stiffens, backward softens; the split agrees with the closed form.
    const double W = 3000.0;
    const GyroscopicSystem sys = pinned_pinned(L, 64, d_o, d_i).assemble().to_dense();
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
    const QuadraticSpectrum sp = solve_at_speed(r.assemble().to_dense(), W);
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
    const FeRotorMatrices sym = machine(74, 2e6, 0.0).assemble();   // to_dense needs cxy = cyx
    const double W = 800.0;
    for (const FeRotorMatrices* model : {&sym, &m}) {
        const SparsePencil p = model->at_speed(W);
        const QuadraticSpectrum ref =
            solve_quadratic(QuadraticPencil{Eigen::MatrixXd(p.M), Eigen::MatrixXd(p.C), Eigen::MatrixXd(p.K)}, {},
                            model->whirl_pairs);
        if (model == &sym) {
            const QuadraticSpectrum viadense = solve_at_speed(model->to_dense(), W);
            REQUIRE(viadense.modes.size() == ref.modes.size());
            for (std::size_t i = 0; i < ref.modes.size(); ++i)
                CHECK(std::abs(viadense.modes[i].lambda - ref.modes[i].lambda) <= 1e-12 * std::abs(ref.modes[i].lambda));
        }
        SparseEigenOptions o;
        o.modes = 8;
        const SparseSpectrum s = solve_quadratic_sparse(p, o, model->whirl_pairs);
        REQUIRE(s.modes.size() == 8);
        for (std::size_t i = 0; i < s.modes.size(); ++i) {
            const Mode& sm = s.modes[i];
            const Mode& dm = ref.modes[i];   // both lists: lowest frequencies first
            // Symmetric bearing damping: 1e-10 relative. Cross-coupled (non-normal) bearings
            // raise the eigenvalue condition numbers; both solvers stay backward stable (below).
            const double tol = model == &sym ? 1e-10 : 1e-9;
            CHECK(std::abs(sm.lambda - dm.lambda) <= tol * std::abs(dm.lambda));
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
