// Dense quadratic eigensolver: backward errors at the extremes, the Hamiltonian
// eigenvalue symmetry of undamped gyroscopic systems, left vectors, singular M.
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include "test_helpers.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

using namespace gyrokit;

namespace {

// Every eigenpair of the scaled QZ path has a relative backward error near
// machine precision (QZ is normwise backward stable on the scaled linearization).
void require_backward_stable(const GyroscopicSystem& s, double w, int expect_modes) {
    const auto sp = solve_at_speed(s, w);
    INFO("speed " << w);
    CHECK(static_cast<int>(sp.modes.size() + sp.rigid_body.size()) >= expect_modes);
    for (const auto& m : sp.modes) {
        CAPTURE(m);
        CHECK(std::isfinite(m.lambda.real()));
        CHECK(std::isfinite(m.lambda.imag()));
        CHECK(m.backward_error <= 1e-12);
    }
}

// Undamped: the extreme case at speeds from standstill to 1e5 rad/s.
void sweep_extremes(GyrostatParameters p) {
    const GyroscopicSystem s = make_system(p);
    for (double w : {0.0, 1.0, 100.0, 1e4, 1e5}) require_backward_stable(s, w, 6);
}

GyroscopicSystem random_gyroscopic(std::mt19937& g, int n, bool definite) {
    GyroscopicSystem s;
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return test::uniform(g, -1, 1); });
    s.M = A * A.transpose() + n * Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return test::uniform(g, -1, 1); });
    s.K = B + B.transpose() + (definite ? 3.0 * n : 0.0) * Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd C = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return test::uniform(g, -1, 1); });
    s.G = C - C.transpose();
    for (int i = 0; i < n; ++i) s.dofs.names.push_back("q" + std::to_string(i));
    return s;
}

}  // namespace

TEST_CASE("scaled QZ: backward error <= 1e-12 at the extremes", "[eig][extremes]") {
    GyrostatParameters p = test::centrifuge();
    SECTION("ordinary, damped") { sweep_extremes(p); }
    p.d_G = p.d_T = p.d_R = 0.0;
    SECTION("zero damping") { sweep_extremes(p); }
    SECTION("stiff shaft 1e12") {
        p.c_T = p.c_R = 1e12;
        sweep_extremes(p);
    }
    SECTION("tiny rotor inertia") {
        p.A_R = 1e-9;
        p.C_R = 1.1e-9;
        sweep_extremes(p);
    }
    SECTION("free cage (singular K, rigid-body modes)") {
        p.c_G = 0.0;
        sweep_extremes(p);
        for (double w : {0.0, 100.0}) {
            CAPTURE(w);
            CHECK(!solve_at_speed(make_system(p), w).rigid_body.empty());
        }
    }
    SECTION("everything at once") {
        p.c_T = p.c_R = 1e12;
        p.A_R = 1e-9;
        p.C_R = 1.1e-9;
        sweep_extremes(p);
    }
    SECTION("badly scaled units (DOFs in m, mm, um)") {
        GyroscopicSystem s = make_system(test::centrifuge());
        const Eigen::VectorXd t = (Eigen::VectorXd(6) << 1e3, 1e-3, 1e4, 1e-4, 1.0, 1e2).finished();
        const GyroscopicSystem ref = s;
        s.M = t.asDiagonal() * s.M * t.asDiagonal();
        s.K = t.asDiagonal() * s.K * t.asDiagonal();
        s.G = t.asDiagonal() * s.G * t.asDiagonal();
        for (auto& c : s.damping) c.D = t.asDiagonal() * c.D * t.asDiagonal();
        for (double w : {0.0, 30.0, 1e4}) {
            CAPTURE(w);
            require_backward_stable(s, w, 6);
            // A congruence leaves the eigenvalues unchanged.
            const auto a = solve_at_speed(s, w), b = solve_at_speed(ref, w);
            REQUIRE(a.modes.size() == b.modes.size());
            for (size_t i = 0; i < a.modes.size(); ++i)
                CHECK(std::abs(a.modes[i].lambda - b.modes[i].lambda) <= 1e-8 * std::abs(b.modes[i].lambda));
        }
    }
}

TEST_CASE("undamped gyroscopic systems: eigenvalues in quadruples, on the axis when stable", "[eig]") {
    std::mt19937 g(7);
    for (int trial = 0; trial < 10; ++trial) {
        CAPTURE(trial);
        const int n = 3 + trial;
        // Indefinite K: eigenvalues lambda, -lambda, conj(lambda), -conj(lambda) (Hamiltonian symmetry).
        const GyroscopicSystem s = random_gyroscopic(g, n, false);
        const auto sp = solve_at_speed(s, 2.0);
        for (const auto& m : sp.modes) {
            CAPTURE(m);
            CHECK(m.backward_error <= 1e-13);
            const std::complex<double> mirror = -std::conj(m.lambda);
            double d = INFINITY;
            for (const auto& o : sp.modes) d = std::min(d, std::abs(o.lambda - mirror));
            CHECK(d <= 1e-9 * std::max(1.0, std::abs(m.lambda)));
        }
        // Definite K: gyroscopically stable, purely imaginary.
        const GyroscopicSystem t = random_gyroscopic(g, n, true);
        for (const auto& m : solve_at_speed(t, 5.0).modes) {
            CAPTURE(m);
            CHECK(std::fabs(m.lambda.real()) <= 1e-11 * std::abs(m.lambda));
        }
    }
}

TEST_CASE("left eigenvectors satisfy y^H P(lambda) = 0", "[eig]") {
    const GyroscopicSystem s = make_system(test::centrifuge());
    const QuadraticPencil p = s.at_speed(20.0);
    EigenOptions o;
    o.left_vectors = true;
    for (const auto& m : solve_quadratic(p, o, s.whirl_pairs).modes) {
        CAPTURE(m);
        const Eigen::MatrixXcd P = p.evaluate(m.lambda);
        const double scale = std::norm(m.lambda) * p.M.norm() + std::abs(m.lambda) * p.C.norm() + p.K.norm();
        CHECK((m.left.adjoint() * P).norm() <= 1e-12 * scale);
        CHECK(m.left.norm() == Approx(1.0));
    }
}

TEST_CASE("state-matrix path: agrees on ordinary cases, refuses singular M", "[eig]") {
    const GyroscopicSystem s = make_system(test::centrifuge());
    const auto a = solve_at_speed(s, 30.0), b = solve_at_speed(s, 30.0, {EigenMethod::StateMatrix, false});
    REQUIRE(a.modes.size() == b.modes.size());
    for (size_t i = 0; i < a.modes.size(); ++i) {
        CAPTURE(i);
        CHECK(std::abs(a.modes[i].lambda - b.modes[i].lambda) <= 1e-10 * std::abs(a.modes[i].lambda));
        CHECK(b.modes[i].backward_error <= 1e-10);
    }
    // A massless DOF: M singular. QZ gives the finite eigenvalues and counts the infinite ones.
    GyroscopicSystem t;
    t.M = Eigen::Vector3d(1.0, 2.0, 0.0).asDiagonal();
    t.K = (Eigen::Matrix3d() << 4, -1, -1, -1, 5, -2, -1, -2, 6).finished();
    t.damping.push_back({"D", 0.1 * Eigen::Matrix3d::Identity()});
    t.dofs.names = {"a", "b", "c"};
    const auto q = solve_at_speed(t, 0.0);
    CHECK(q.infinite_count >= 1);
    for (const auto& m : q.modes) {
        CAPTURE(m);
        CHECK(m.backward_error <= 1e-12);
    }
    CHECK_THROWS_WITH(solve_at_speed(t, 0.0, {EigenMethod::StateMatrix, false}), Catch::Contains("M is singular"));
}

// A zero mass matrix made the companion form's scaling NaN, and LAPACK's multishift
// QZ (dggev3 through its _work form, which has no NaN check) wrote out of bounds on
// it: the fuzz target's empty input. Refused with an error naming M instead.
TEST_CASE("zero or non-finite pencils are refused before LAPACK sees them", "[eig][extremes]") {
    GyroscopicSystem z;
    z.M = Eigen::Matrix2d::Zero();
    z.K = Eigen::Matrix2d::Zero();
    z.dofs.names = {"a", "b"};
    CHECK_THROWS_WITH(solve_at_speed(z, 0.0), Catch::Contains("mass matrix M is zero"));
    z.K = Eigen::Matrix2d::Identity();
    CHECK_THROWS_WITH(solve_at_speed(z, 1.0), Catch::Contains("mass matrix M is zero"));
    z.M = Eigen::Matrix2d::Identity();
    Eigen::Matrix2d k = Eigen::Matrix2d::Identity();
    k(0, 1) = k(1, 0) = std::numeric_limits<double>::infinity();
    z.K = k;
    CHECK_THROWS_AS(solve_at_speed(z, 1.0), Error);
}

TEST_CASE("double eigenvalue: the plane is turned into backward and forward circular modes, a split pair is kept",
          "[whirl]") {
    // x, y with M = I, C = 0, K = diag(k, k (1 + a)): eigenvalues i sqrt(k) and
    // i sqrt(k (1 + a)) with the exact planar vectors e_x, e_y. a = 0: a double
    // eigenvalue, the circular basis must be chosen. a = 1e-9 (split 5e-10 > 1e-10):
    // a real split, the planar pair must stay. a = 1e-11 (split 5e-12): double by
    // the gap, but the given vectors are exact and a circular combination would
    // raise their residual from 0 to 5e-12: the planar pair must stay too.
    const std::vector<std::pair<int, int>> pairs{{0, 1}};
    const double k = 4.0;
    for (const double a : {0.0, 1e-11, 1e-9}) {
        const Eigen::Matrix2cd K = Eigen::Vector2cd(k, k * (1 + a)).asDiagonal();
        PencilAction action;
        action.apply = [&](const Eigen::VectorXcd& x, Eigen::VectorXcd& Mx, Eigen::VectorXcd& Cx,
                           Eigen::VectorXcd& Kx) {
            Mx = x;
            Cx = Eigen::VectorXcd::Zero(2);
            Kx = K * x;
        };
        action.norm_M = std::sqrt(2.0);
        action.norm_K = K.norm();
        std::vector<Mode> modes(2);
        modes[0].lambda = {0.0, std::sqrt(k)};
        modes[0].right = Eigen::Vector2cd(1.0, 0.0);
        modes[1].lambda = {0.0, std::sqrt(k * (1 + a))};
        modes[1].right = Eigen::Vector2cd(0.0, 1.0);
        separate_double_whirl(modes, pairs, 1e-7, action);
        const auto turn = [](const Mode& m) { return (m.right(0) * std::conj(m.right(1))).imag(); };
        INFO("a = " << a);
        if (a == 0.0) {
            CHECK(turn(modes[0]) == Approx(-0.5).margin(1e-15));   // backward circle, listed first
            CHECK(turn(modes[1]) == Approx(0.5).margin(1e-15));
            CHECK(modes[0].whirl == Whirl::Backward);
            CHECK(modes[1].whirl == Whirl::Forward);
            CHECK(modes[0].backward_error <= 1e-11);
        } else {
            CHECK(modes[0].right == Eigen::VectorXcd(Eigen::Vector2cd(1.0, 0.0)));
            CHECK(modes[1].right == Eigen::VectorXcd(Eigen::Vector2cd(0.0, 1.0)));
        }
    }
    // Three equal eigenvalues (a cluster, not a pair) are left alone.
    PencilAction zero;
    zero.apply = [](const Eigen::VectorXcd& x, Eigen::VectorXcd& Mx, Eigen::VectorXcd& Cx, Eigen::VectorXcd& Kx) {
        Mx = x;
        Cx = Eigen::VectorXcd::Zero(x.size());
        Kx = 4.0 * x;
    };
    std::vector<Mode> three(3);
    for (int i = 0; i < 3; ++i) {
        CAPTURE(i);
        three[static_cast<size_t>(i)].lambda = {0.0, 2.0};
        three[static_cast<size_t>(i)].right = Eigen::Vector2cd(i == 1 ? 0.0 : 1.0, i == 1 ? 1.0 : 0.0);
    }
    separate_double_whirl(three, pairs, 1e-7, zero);
    CHECK(three[0].right == Eigen::VectorXcd(Eigen::Vector2cd(1.0, 0.0)));
    CHECK(three[1].right == Eigen::VectorXcd(Eigen::Vector2cd(0.0, 1.0)));
}

TEST_CASE("a vector's phase and whirl do not depend on its scale, down to vectors whose squares underflow",
          "[eig][extremes]") {
    // A forward circular motion of pair (0, 1) with an axial DOF 2: the phase is taken from
    // the largest entry, the whirl from the pair; scaled by 1e-160 the squared moduli
    // underflow to zero, and the moduli are compared instead.
    Eigen::VectorXcd x(3);
    x << std::complex<double>(0.3, 0.4), std::complex<double>(-0.4, 0.3), std::complex<double>(0.1, 0.0);
    const std::vector<std::pair<int, int>> pairs{{0, 1}};
    const std::complex<double> l(-0.1, 10.0);
    const Eigen::VectorXcd u = unit_vector(x);
    CHECK(std::abs(u(0).imag()) <= 1e-15);   // the first of the two largest entries made real
    CHECK(u(0).real() > 0.0);
    for (double s : {1.0, 1e-160, 1e-300, 1e150}) {
        CAPTURE(s);
        const Eigen::VectorXcd xs = x * s;
        CHECK((unit_vector(xs) - u).norm() <= 1e-14);
        CHECK(classify_whirl(l, xs, pairs, 1e-9) == classify_whirl(l, x, pairs, 1e-9));
    }
    // A vector that moves only the axial DOF: no whirl at any scale.
    Eigen::VectorXcd axial = Eigen::VectorXcd::Zero(3);
    axial(2) = 1.0;
    for (double s : {1.0, 1e-160}) CHECK(classify_whirl(l, axial * s, pairs, 1e-9) == Whirl::None);
}

TEST_CASE("the eigenvalues alone equal the full solve's: from the state matrix where M is well conditioned, "
          "from QZ where it is singular or nearly so",
          "[eig]") {
    std::mt19937 g(11);
    // Each eigenvalue of the full solve (modes and rigid-body) has its own among the values
    // alone, within its error bound or 1e-10 of the natural scale (both paths are backward
    // stable on well-scaled pencils; a cond(M) of 1e12 is taken by QZ, not the state matrix).
    const auto same = [](const QuadraticPencil& P) {
        EigenOptions o;
        o.left_vectors = true;
        const QuadraticSpectrum s = solve_quadratic(P, o);
        const EigenvalueSet e = quadratic_eigenvalues(P);
        CHECK(e.values.size() == s.modes.size() + s.rigid_body.size());
        std::vector<char> used(e.values.size(), 0);
        for (const auto* list : {&s.modes, &s.rigid_body})
            for (const Mode& m : *list) {
                size_t best = e.values.size();
                double d = std::numeric_limits<double>::infinity();
                for (size_t j = 0; j < e.values.size(); ++j)
                    if (const double dj = std::min(std::abs(e.values[j] - m.lambda), std::abs(std::conj(e.values[j]) - m.lambda));
                        !used[j] && dj < d)
                        d = dj, best = j;
                CAPTURE(m.lambda, d, m.error_bound);
                REQUIRE(best < e.values.size());
                used[best] = 1;
                CHECK(d <= std::max(m.error_bound, 1e-10 * std::max(std::abs(m.lambda), e.scale)));
            }
    };
    for (int n : {3, 12, 40}) {
        QuadraticPencil P = random_gyroscopic(g, n, true).at_speed(3.0);
        const Eigen::MatrixXd D = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return test::uniform(g, 0, 0.1); });
        P.C += D * D.transpose();   // damped
        same(P);                    // state matrix
        QuadraticPencil singular = P;   // a massless DOF: QZ, its infinite eigenvalues dropped
        singular.M.row(0).setZero();
        singular.M.col(0).setZero();
        same(singular);
        QuadraticPencil light = P;   // cond(M) about 1e12: QZ
        light.M.row(0) *= 1e-6;
        light.M.col(0) *= 1e-6;
        same(light);
    }
}

TEST_CASE("a pencil of uncoupled groups is solved group by group: the eigenvalues of each group, vectors zero "
          "outside it",
          "[eig]") {
    // Two damped gyroscopic pencils of 9 and 5 DOFs and a free DOF (mass only: a double
    // zero eigenvalue), their DOFs interleaved as a 6-DOF-per-node export interleaves
    // lateral, axial and torsional ones. Reference: each group's pencil alone.
    std::mt19937 g(23);
    const auto damped = [&](int n) {
        QuadraticPencil P = random_gyroscopic(g, n, true).at_speed(2.0);
        const Eigen::MatrixXd D = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return test::uniform(g, 0, 0.1); });
        P.C += D * D.transpose();
        return P;
    };
    const QuadraticPencil A = damped(9), B = damped(5);
    const int n = 15;
    std::vector<int> where(n);   // where[k]: the whole pencil's DOF of the k-th DOF of A, then B, then the free one
    for (int k = 0; k < n; ++k) where[static_cast<size_t>(k)] = (k * 4) % n;   // 4 and 15 coprime
    QuadraticPencil P{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
    const auto place = [&](const QuadraticPencil& Q, int first) {
        for (int i = 0; i < Q.M.rows(); ++i)
            for (int j = 0; j < Q.M.rows(); ++j) {
                const int r = where[static_cast<size_t>(first + i)], c = where[static_cast<size_t>(first + j)];
                P.M(r, c) = Q.M(i, j), P.C(r, c) = Q.C(i, j), P.K(r, c) = Q.K(i, j);
            }
    };
    place(A, 0);
    place(B, 9);
    P.M(where[14], where[14]) = 2.0;
    EigenOptions o;
    o.left_vectors = true;
    const QuadraticSpectrum s = solve_quadratic(P, o);
    std::vector<std::complex<double>> reference;
    for (const QuadraticPencil* Q : {&A, &B})
        for (const Mode& m : solve_quadratic(*Q, o).modes) reference.push_back(m.lambda);
    REQUIRE(s.modes.size() == reference.size());
    REQUIRE(s.rigid_body.size() == 2);   // the free DOF's double zero (a Jordan chain: q = a + b t)
    std::vector<char> used(reference.size(), 0);
    for (const Mode& m : s.modes) {
        CAPTURE(m.lambda, m.error_bound);
        CHECK(m.backward_error <= 1e-13);
        CHECK(m.error_bound <= 1e-10 * std::abs(m.lambda));   // the left vectors in place too
        size_t best = reference.size();
        double d = std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < reference.size(); ++j)
            if (!used[j] && std::abs(reference[j] - m.lambda) < d) d = std::abs(reference[j] - m.lambda), best = j;
        REQUIRE(best < reference.size());
        used[best] = 1;
        CHECK(d <= 1e-12 * std::abs(m.lambda));
        // The vector lives on one group: A's DOFs or B's.
        double on_a = 0.0, on_b = 0.0;
        for (int k = 0; k < 9; ++k) on_a += std::norm(m.right[where[static_cast<size_t>(k)]]);
        for (int k = 9; k < 14; ++k) on_b += std::norm(m.right[where[static_cast<size_t>(k)]]);
        CHECK(std::min(on_a, on_b) == 0.0);
        CHECK(std::norm(m.right[where[14]]) == 0.0);
    }
    // The eigenvalues alone: the same, group by group.
    const EigenvalueSet e = quadratic_eigenvalues(P);
    CHECK(e.values.size() == s.modes.size() + 2);   // the free DOF's double zero, both on the real axis
    for (const Mode& m : s.modes) {
        double d = std::numeric_limits<double>::infinity();
        for (const std::complex<double> v : e.values) d = std::min(d, std::abs(v - m.lambda));
        CHECK(d <= 1e-10 * std::abs(m.lambda));
    }
    // A free chain much stiffer than the rest (a torsional pair of 1e8 N m/rad): its groups
    // are scaled as the whole pencil is, so the group solve keeps what a solve of the
    // whole keeps. Reference: the same pencil with a coupling entry of 1e-300 (it joins
    // the groups and changes no eigenvalue beyond rounding): as many modes and rigid-body
    // pairs (the split of the chain's double zero is rounding, not compared), the others
    // equal within their bounds.
    {
        const int m = 11;
        QuadraticPencil Q{Eigen::MatrixXd::Zero(m, m), Eigen::MatrixXd::Zero(m, m), Eigen::MatrixXd::Zero(m, m)};
        Q.M.topLeftCorner(9, 9) = A.M, Q.C.topLeftCorner(9, 9) = A.C, Q.K.topLeftCorner(9, 9) = A.K;
        const double k = 1e8, j1 = 0.5, j2 = 2.0;
        Q.M(9, 9) = j1, Q.M(10, 10) = j2;
        Q.K.bottomRightCorner(2, 2) << k, -k, -k, k;
        QuadraticPencil joined = Q;
        joined.M(0, 9) = joined.M(9, 0) = 1e-300;
        const QuadraticSpectrum q = solve_quadratic(Q, o), r = solve_quadratic(joined, o);
        REQUIRE(q.modes.size() == r.modes.size());
        CHECK(q.rigid_body.size() == r.rigid_body.size());
        const double torsion = std::sqrt(k * (1.0 / j1 + 1.0 / j2));
        bool found = false;
        for (size_t i = 0; i < q.modes.size(); ++i) {
            found = found || std::abs(q.modes[i].lambda - std::complex<double>(0.0, torsion)) <= 1e-12 * torsion;
            if (std::abs(r.modes[i].lambda) <= 1e-3 * r.scale) continue;   // the chain's split zero
            CHECK(std::abs(q.modes[i].lambda - r.modes[i].lambda) <= q.modes[i].error_bound + r.modes[i].error_bound);
        }
        CHECK(found);
    }
    // A group without mass (a massless DOF coupled to nothing): the pencil is solved whole,
    // the DOF's eigenvalue -K/C kept, its infinite one dropped.
    QuadraticPencil massless = P;
    massless.M(where[14], where[14]) = 0.0;
    massless.C(where[14], where[14]) = 1.0;
    massless.K(where[14], where[14]) = 3.0;
    const QuadraticSpectrum t = solve_quadratic(massless, o);
    CHECK(t.infinite_count == 1);
    bool found = false;
    for (const Mode& m : t.modes) found = found || std::abs(m.lambda - std::complex<double>(-3.0, 0.0)) <= 1e-12 * 3.0;
    CHECK(found);
}
