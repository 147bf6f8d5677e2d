// Results that do not depend on the machine: stiff supports, the state-matrix
// method's bounds, sparse thresholds against dense ones, a window edge through a
// double eigenvalue. Each check compares within bounds the code itself reports.
#include "test_helpers.hpp"
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace gyrokit;

namespace {

// A steel shaft 1 m, 30 mm, 20 elements, on two bearings of stiffness k (k = 0: pinned ends).
GyroscopicSystem shaft_on(double k) {
    FeRotor r = fe_uniform_shaft(1.0, 20, 0.03, 0.0, 2.11e11, 0.3, 7810.0);
    for (int node : {0, 20}) {
        if (k > 0.0) {
            FeBearing b;
            b.node = node;
            b.kxx = b.kyy = k;
            r.bearings.push_back(b);
        } else {
            r.supports.push_back({node, true, true, false, false});
        }
    }
    return make_system(r);
}

bool has_note(const QuadraticSpectrum& s, const std::string& part) {
    for (const auto& n : s.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("stiff supports (1e12 ... 1e20 N/m) give the pinned shaft's first pairs, vouched for", "[vouched]") {
    const QuadraticSpectrum pinned = solve_at_speed(shaft_on(0.0), 0.0);
    REQUIRE(pinned.modes.size() >= 6);
    // The supports' compliance moves the frequencies by about 20 EI / (k L^3) <= 2e-7
    // relative at 1e12 N/m; the bounds are ~1e-9 relative.
    for (double k : {1e12, 1e14, 1e16, 1e18, 1e20}) {
        INFO("k = " << k);
        const QuadraticSpectrum s = solve_at_speed(shaft_on(k), 0.0);
        CHECK(s.rigid_body.empty());
        REQUIRE(s.modes.size() >= 6);
        for (size_t i = 0; i < 4; ++i) {   // the first two pairs
            CHECK(s.modes[i].lambda.imag() == Approx(pinned.modes[i].lambda.imag()).epsilon(1e-6));
            CHECK(s.modes[i].error_bound <= 1e-6 * std::abs(s.modes[i].lambda));
            CHECK(s.modes[i].stability() == Stability::Neutral);   // undamped
            CHECK(s.modes[i].real_part() == 0.0);
            CHECK(s.modes[i].damping_ratio() == 0.0);
        }
        // The first bending pair is a critical speed pair, as on pinned supports.
        const auto crit = critical_speeds_direct(shaft_on(k), 1, 0.0, 1.2 * pinned.modes[1].lambda.imag());
        CHECK(crit.size() == 2);
    }
}

TEST_CASE("the state-matrix method agrees with QZ within the printed bounds or says it cannot vouch", "[vouched]") {
    for (double k : {1e8, 1e12, 1e20}) {
        INFO("k = " << k);
        const GyroscopicSystem sys = shaft_on(k);
        const QuadraticSpectrum qz = solve_at_speed(sys, 100.0, {EigenMethod::ScaledQZ, false});
        EigenOptions st;
        st.method = EigenMethod::StateMatrix;
        const QuadraticSpectrum s = solve_at_speed(sys, 100.0, st);
        int loose = 0;
        for (const Mode& m : s.modes) {
            double nearest = INFINITY;
            const Mode* q = nullptr;
            for (const Mode& o : qz.modes)
                if (std::abs(o.lambda - m.lambda) < nearest) nearest = std::abs(o.lambda - m.lambda), q = &o;
            REQUIRE(q != nullptr);
            const bool vouched = m.error_bound <= std::max(kVouchTolerance * std::abs(m.lambda), s.real_tol);
            loose += !vouched;
            // A vouched eigenvalue lies within its bound (and QZ's) of QZ's.
            if (vouched) CHECK(nearest <= m.error_bound + q->error_bound);
        }
        CHECK(has_note(s, "cannot vouch") == (loose > 0));
    }
    // The stiffest supports: the state matrix of the scaled pencil, each pair refined on
    // the quadratic, keeps the shaft's low modes (unscaled and unrefined it lost them):
    // every one within its bound and QZ's of QZ's, and most of them vouched for.
    EigenOptions st;
    st.method = EigenMethod::StateMatrix;
    const QuadraticSpectrum stiff = solve_at_speed(shaft_on(1e20), 0.0, st);
    const QuadraticSpectrum stiff_qz = solve_at_speed(shaft_on(1e20), 0.0, {EigenMethod::ScaledQZ, false});
    int shaft_modes = 0, vouched = 0;
    for (const Mode& m : stiff.modes) {
        if (m.lambda.imag() >= 1e9) continue;
        CAPTURE(m.lambda);
        ++shaft_modes;
        vouched += m.error_bound <= kVouchTolerance * std::abs(m.lambda);
        double nearest = INFINITY, bound = 0.0;
        for (const Mode& o : stiff_qz.modes)
            if (std::abs(o.lambda - m.lambda) < nearest) nearest = std::abs(o.lambda - m.lambda), bound = o.error_bound;
        CHECK(nearest <= m.error_bound + bound);
    }
    CHECK(vouched >= shaft_modes - 2);   // the lowest pair, double at standstill, may not be
    // QZ vouches for every shaft mode; only the two modes of the supports' own bounce
    // (4e10 rad/s, the shaft's end nodes on 1e20 N/m) are resolved to 3e-4 alone.
    const QuadraticSpectrum qz = solve_at_speed(shaft_on(1e20), 0.0, {EigenMethod::ScaledQZ, false});
    for (const Mode& m : qz.modes)
        if (m.lambda.imag() < 1e9) CHECK(m.error_bound <= kVouchTolerance * std::abs(m.lambda));
}

TEST_CASE("the default dense method answers by the state matrix where every pair is verified and vouched for, "
          "by QZ elsewhere", "[vouched]") {
    const auto same_as = [](const QuadraticSpectrum& a, const QuadraticSpectrum& b) {
        REQUIRE(a.modes.size() == b.modes.size());
        REQUIRE(a.rigid_body.size() == b.rigid_body.size());
        for (size_t i = 0; i < a.modes.size(); ++i) CHECK(a.modes[i].lambda == b.modes[i].lambda);
    };
    // An 84-DOF shaft on ordinary bearings, spinning (the gyroscopic moments couple its
    // planes): the state matrix answers, every pair verified, each eigenvalue within the
    // sum of its bound and QZ's of QZ's.
    for (double w : {100.0, 3000.0}) {
        INFO("speed " << w);
        const GyroscopicSystem sys = shaft_on(1e8);
        REQUIRE(sys.size() >= kAutoStateDofs);
        const QuadraticSpectrum a = solve_at_speed(sys, w);
        const QuadraticSpectrum qz = solve_at_speed(sys, w, {EigenMethod::ScaledQZ, false});
        CHECK(a.method == "state matrix");
        CHECK(a.notes.empty());
        REQUIRE(a.modes.size() == qz.modes.size());
        for (size_t i = 0; i < a.modes.size(); ++i) {
            CAPTURE(i, a.modes[i].lambda, qz.modes[i].lambda);
            CHECK(a.modes[i].backward_error <= kStateVerifyTolerance);
            CHECK(std::abs(a.modes[i].lambda - qz.modes[i].lambda) <= a.modes[i].error_bound + qz.modes[i].error_bound);
        }
    }
    // At standstill its planes are uncoupled groups: QZ answers, group by group.
    same_as(solve_at_speed(shaft_on(1e8), 0.0), solve_at_speed(shaft_on(1e8), 0.0, {EigenMethod::ScaledQZ, false}));
    CHECK(solve_at_speed(shaft_on(1e8), 0.0).method == "scaled QZ");
    // Supports of 1e20 N/m, spinning: whichever method answers, each eigenvalue lies within
    // the sum of its bound and QZ's of QZ's, and a state-matrix answer bounds every mode
    // within 1e-6 of its modulus.
    {
        const QuadraticSpectrum a = solve_at_speed(shaft_on(1e20), 100.0);
        const QuadraticSpectrum qz = solve_at_speed(shaft_on(1e20), 100.0, {EigenMethod::ScaledQZ, false});
        REQUIRE(a.modes.size() == qz.modes.size());
        for (size_t i = 0; i < a.modes.size(); ++i) {
            CAPTURE(i, a.method, a.modes[i].lambda, qz.modes[i].lambda);
            CHECK(std::abs(a.modes[i].lambda - qz.modes[i].lambda) <= a.modes[i].error_bound + qz.modes[i].error_bound);
            if (a.method == "state matrix")
                CHECK(a.modes[i].error_bound <= kVouchTolerance * std::abs(a.modes[i].lambda));
        }
    }
    // A massless rotation DOF (M singular): the state matrix refuses, QZ answers.
    {
        GyroscopicSystem sys = shaft_on(1e8);
        const Eigen::Index j = 3;   // a rotation of the first node
        Eigen::MatrixXd M = Eigen::MatrixXd(sys.M);
        M.row(j).setZero();
        M.col(j).setZero();
        sys.M = M;
        CHECK_THROWS_AS(solve_at_speed(sys, 100.0, {EigenMethod::StateMatrix, false}), SolverError);
        const QuadraticSpectrum a = solve_at_speed(sys, 100.0);
        CHECK(a.method == "scaled QZ");
        same_as(a, solve_at_speed(sys, 100.0, {EigenMethod::ScaledQZ, false}));
    }
    // Below kAutoStateDofs QZ answers (as fast there, and no refinement).
    const QuadraticSpectrum small = solve_at_speed(make_system(test::centrifuge()), 30.0);
    CHECK(small.method == "scaled QZ");
}

TEST_CASE("sparse stability thresholds equal the dense ones within their bounds, for two targets", "[vouched]") {
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/fe_rotor.toml");
    std::vector<double> speeds;
    for (int k = 0; k <= 40; ++k) speeds.push_back(10.0 * k);
    CampbellOptions co;
    co.modes = 6;
    const auto dense = stability_changes(sc.system, campbell(sc.system, speeds, co));
    REQUIRE(dense.size() == 1);
    REQUIRE(dense[0].bound < 1e-4 * dense[0].speed);
    for (double target : {0.0, 300.0}) {
        INFO("target = " << target);
        SolverOptions so;
        so.kind = SolverKind::Sparse;
        so.modes = 4;
        so.target = target;
        const SolverChoice c = choose_solver(sc.system, so);
        CampbellOptions sco;
        sco.modes = c.modes;
        const CampbellDiagram cd = campbell(c.make, speeds, sco);
        const auto sparse = stability_changes(c.make, cd);
        REQUIRE(sparse.size() == 1);
        CHECK(sparse[0].becomes_unstable);
        CHECK(sparse[0].bound < 1e-4 * sparse[0].speed);
        CHECK(std::abs(sparse[0].speed - dense[0].speed) <= sparse[0].bound + dense[0].bound);
    }
}

TEST_CASE("a sparse window whose edge cuts a double eigenvalue keeps both halves and says so", "[vouched]") {
    // Free-free shaft at standstill: rigid-body eigenvalues at 0, then double bending pairs.
    FeRotor r = fe_uniform_shaft(1.0, 20, 0.03, 0.0, 2.11e11, 0.3, 7810.0);
    const GyroscopicSystem sys = make_system(r);
    const QuadraticSpectrum dense = solve_at_speed(sys, 0.0);
    REQUIRE(dense.modes.size() >= 4);
    REQUIRE(std::abs(dense.modes[2].lambda - dense.modes[3].lambda) <= 1e-9 * std::abs(dense.modes[2].lambda));
    SparseEigenOptions o;
    o.modes = 3;   // the edge falls inside the second pair
    const SparseSpectrum s = solve_quadratic_sparse(sys.sparse_at_speed(0.0), o, sys.whirl_pairs);
    REQUIRE(s.modes.size() == 4);
    bool noted = false;
    for (const auto& n : s.notes) noted = noted || n.find("cuts a double eigenvalue") != std::string::npos;
    CHECK(noted);
    for (size_t i = 0; i < 4; ++i)
        CHECK(s.modes[i].lambda.imag() == Approx(dense.modes[i].lambda.imag()).epsilon(1e-9));
    CHECK(s.modes[2].whirl != s.modes[3].whirl);   // one backward, one forward half
}
