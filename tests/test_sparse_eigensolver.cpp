// Sparse shift-invert (ARPACK) against the dense scaled QZ on a damped
// gyroscopic chain of a few hundred DOFs.
#include "core/error.hpp"
#include "eig/quadratic_eigensolver.hpp"
#include "eig/sparse_eigensolver.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace gyrokit;

namespace {

// A chain of disks with lateral DOFs (x, y) per disk, springs between neighbours,
// gyroscopic coupling per disk and light damping: a banded sparse system.
SparsePencil chain(int disks, double w) {
    const int n = 2 * disks;
    std::vector<Eigen::Triplet<double>> m, c, k;
    for (int i = 0; i < disks; ++i) {
        const double mass = 1.0 + 0.3 * std::sin(i), gyro = 0.05 * (1 + i % 3), stiff = 1e4 * (1.0 + 0.2 * std::cos(i));
        for (int d = 0; d < 2; ++d) {
            const int a = 2 * i + d;
            m.emplace_back(a, a, mass);
            c.emplace_back(a, a, 0.02 * (1 + i % 2));
            k.emplace_back(a, a, 2 * stiff + (i == 0 || i == disks - 1 ? stiff : 0.0));
            if (i + 1 < disks) {
                k.emplace_back(a, a + 2, -stiff);
                k.emplace_back(a + 2, a, -stiff);
            }
        }
        c.emplace_back(2 * i, 2 * i + 1, w * gyro);
        c.emplace_back(2 * i + 1, 2 * i, -w * gyro);
    }
    SparsePencil p;
    p.M.resize(n, n);
    p.C.resize(n, n);
    p.K.resize(n, n);
    p.M.setFromTriplets(m.begin(), m.end());
    p.C.setFromTriplets(c.begin(), c.end());
    p.K.setFromTriplets(k.begin(), k.end());
    return p;
}

QuadraticSpectrum dense(const SparsePencil& p) {
    return solve_quadratic(QuadraticPencil{Eigen::MatrixXd(p.M), Eigen::MatrixXd(p.C), Eigen::MatrixXd(p.K)}, {});
}

}  // namespace

TEST_CASE("sparse shift-invert agrees with dense QZ", "[sparse]") {
    const SparsePencil p = chain(100, 300.0);   // 200 DOFs
    const QuadraticSpectrum ref = dense(p);
    for (std::complex<double> shift : {std::complex<double>(0, 0), std::complex<double>(0, 150.0)}) {
        SparseEigenOptions o;
        o.modes = 8;
        o.shift = shift;
        const SparseSpectrum s = solve_quadratic_sparse(p, o);
        REQUIRE(s.modes.size() == 8);
        for (const Mode& m : s.modes) {
            CHECK(m.backward_error <= 1e-12);
            double d = INFINITY;
            for (const Mode& r : ref.modes) d = std::min(d, std::abs(r.lambda - m.lambda));
            CHECK(d <= 1e-10 * std::abs(m.lambda));
        }
        // They are the 8 modes nearest the shift.
        std::vector<double> dist;
        for (const Mode& r : ref.modes) dist.push_back(std::abs(r.lambda - shift));
        std::sort(dist.begin(), dist.end());
        for (const Mode& m : s.modes) CHECK(std::abs(m.lambda - shift) <= dist[7] * (1 + 1e-9));
    }
}

TEST_CASE("sparse solver reports a singular shift and non-convergence", "[sparse]") {
    SparsePencil p = chain(20, 0.0);
    const QuadraticSpectrum ref = dense(p);
    SparseEigenOptions o;
    o.shift = ref.modes[3].lambda;   // exactly an eigenvalue up to rounding: P(shift) numerically singular or not
    o.modes = 4;
    // A shift at an eigenvalue either fails the factorization (InputError) or still
    // converges to that eigenvalue; never a silent wrong answer.
    try {
        const SparseSpectrum s = solve_quadratic_sparse(p, o);
        bool found = false;
        for (const Mode& m : s.modes) found = found || std::abs(m.lambda - ref.modes[3].lambda) <= 1e-8 * std::abs(m.lambda);
        CHECK(found);
    } catch (const InputError&) {
        SUCCEED();
    }
    // A free system (no stiffness) with shift 0: P(0) = 0 is singular.
    SparsePencil f = p;
    f.K.setZero();
    o.shift = 0.0;
    CHECK_THROWS_AS(solve_quadratic_sparse(f, o), InputError);
    // One restart is not enough: ARPACK says so.
    o.shift = {0.0, 100.0};
    o.max_iterations = 1;
    o.lanczos_vectors = 12;
    CHECK_THROWS_AS(solve_quadratic_sparse(p, o), SolverError);
}

TEST_CASE("real shift: real Arnoldi finds real and complex eigenvalues alike", "[sparse]") {
    // Mass-proportional damping 100 M overdamps the modes below 50 rad/s
    // (lambda = -50 +- sqrt(2500 - w^2)): the window about sigma = -50 holds
    // real eigenvalues (double: x and y) and complex pairs, so both kinds of
    // Ritz value of the real Arnoldi run are checked against dense QZ.
    SparsePencil p = chain(60, 0.0);
    p.C = p.C + 100.0 * p.M;
    const QuadraticSpectrum ref = dense(p);
    SparseEigenOptions o;
    o.modes = 10;
    o.shift = -50.0;
    const SparseSpectrum s = solve_quadratic_sparse(p, o);
    REQUIRE(s.modes.size() == 10);
    int real = 0, complex = 0;
    for (const Mode& m : s.modes) {
        (m.lambda.imag() == 0.0 ? real : complex) += 1;
        CHECK(m.backward_error <= 1e-12);
        CHECK(m.lambda.imag() >= 0.0);
        double d = INFINITY;
        for (const Mode& r : ref.modes) d = std::min(d, std::abs(r.lambda - m.lambda));
        CHECK(d <= 1e-10 * std::abs(m.lambda));
    }
    CHECK(real > 0);
    CHECK(complex > 0);
    // The same window through complex arithmetic (a shift off the real axis by
    // far less than the spacing) gives the same eigenvalues.
    o.shift = std::complex<double>(-50.0, 1e-9);
    const SparseSpectrum c = solve_quadratic_sparse(p, o);
    REQUIRE(c.modes.size() == s.modes.size());
    for (size_t i = 0; i < s.modes.size(); ++i) {
        double d = INFINITY;
        for (const Mode& m : c.modes) d = std::min(d, std::abs(m.lambda - s.modes[i].lambda));
        CHECK(d <= 1e-10 * std::abs(s.modes[i].lambda));
    }
}
