// A DOF whose mass is below rounding against its stiffness (a support of 1e20 N/m
// beside masses of kilograms): its finite eigenvalue, far above the pencil's natural
// scale, is a mode with its bound, never dropped as "infinite"; M is singular only
// where it is, and the state-matrix method says what it cannot resolve.
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

using namespace gyrokit;

namespace {

GyroscopicSystem diagonal(const Eigen::Vector4d& m, const Eigen::Vector4d& k) {
    GyroscopicSystem s;
    s.M = m.asDiagonal();
    s.K = k.asDiagonal();
    s.dofs.names = {"x", "y", "psi", "theta"};
    s.whirl_pairs = {{0, 1}, {2, 3}};
    return s;
}

// The modes' frequencies, each checked against `expected` within its own bound
// (and the bound vouched for: at most 1e-6 of the frequency).
void require_modes(const QuadraticSpectrum& s, const std::vector<double>& expected) {
    REQUIRE(s.modes.size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        CAPTURE(i, s.modes[i]);
        CHECK(std::abs(s.modes[i].lambda - std::complex<double>(0.0, expected[i])) <= s.modes[i].error_bound);
        CHECK(s.modes[i].error_bound <= 1e-6 * expected[i]);
    }
}

}  // namespace

TEST_CASE("a DOF of 1e20 N/m beside kilograms: its 4.47e9 rad/s mode is kept, by QZ and by eigenvalues alone",
          "[eig][extremes]") {
    // K = diag(1, 1e20, 1, 1), M = diag(5, 5, 0.02, 0.02): omega = sqrt(k/m).
    const GyroscopicSystem s = diagonal({5.0, 5.0, 0.02, 0.02}, {1.0, 1e20, 1.0, 1.0});
    const std::vector<double> expected{std::sqrt(0.2), std::sqrt(50.0), std::sqrt(50.0), std::sqrt(2e19)};
    for (const EigenMethod method : {EigenMethod::ScaledQZ, EigenMethod::ClassicQZ}) {
        const QuadraticSpectrum q = solve_at_speed(s, 0.0, {method, false});
        CHECK(q.infinite_count == 0);
        CHECK(q.notes.empty());
        require_modes(q, expected);
    }
    const EigenvalueSet e = quadratic_eigenvalues(s.at_speed(0.0));
    REQUIRE(e.values.size() == 4);   // two DOFs' pairs (x: 0.447, psi/theta: 7.07 twice) and y's
    int huge = 0;
    for (const auto& l : e.values) huge += std::abs(l.imag() - std::sqrt(2e19)) <= 1e-6 * std::sqrt(2e19);
    CHECK(huge == 1);
    // The state matrix cannot resolve it and says why (M is not singular).
    CHECK_THROWS_WITH(solve_at_speed(s, 0.0, {EigenMethod::StateMatrix, false}),
                      Catch::Contains("M is invertible") && Catch::Contains("4.47e+09 rad/s") &&
                          Catch::Contains("QZ method"));
}

TEST_CASE("a stiff DOF coupled to soft ones: every pair within its bound of an independent computation",
          "[eig][extremes]") {
    // M = I, K a chain [2 -1; -1 2 -1; ...] whose first DOF holds a support of 1e20:
    // the soft pairs are those of the chain clamped there (the Schur complement
    // K22 - k21 k12 / K11, well scaled), the stiff one sqrt(K11 + k12^2 / K11) to rounding.
    const int n = 5;
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
        K(i, i) = 2.0;
        if (i + 1 < n) K(i, i + 1) = K(i + 1, i) = -1.0;
    }
    K(0, 0) = 1e20;
    GyroscopicSystem s;
    s.M = Eigen::MatrixXd::Identity(n, n);
    s.K = K;
    s.dofs.names = {"a", "b", "c", "d", "e"};
    s.whirl_pairs = {};
    const Eigen::MatrixXd schur =
        K.bottomRightCorner(n - 1, n - 1) - K.block(1, 0, n - 1, 1) * K.block(0, 1, 1, n - 1) / K(0, 0);
    const Eigen::VectorXd soft = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(schur).eigenvalues();
    std::vector<double> expected;
    for (int i = 0; i < n - 1; ++i) expected.push_back(std::sqrt(soft(i)));
    expected.push_back(std::sqrt(K(0, 0) + 1.0 / K(0, 0)));
    require_modes(solve_at_speed(s, 0.0), expected);
}

TEST_CASE("a massless DOF stays infinite beside a stiff one", "[eig][extremes]") {
    // M = diag(5, 5, 0, 1), DOF 3 massless with a damper: one infinite eigenvalue
    // and a real one, -k/c = -3; DOF 2's finite pair is kept beside them.
    GyroscopicSystem s = diagonal({5.0, 5.0, 0.0, 1.0}, {1.0, 1e20, 3.0, 4.0});
    s.damping.push_back({"D", Eigen::Vector4d(0.0, 0.0, 1.0, 0.0).asDiagonal()});
    const QuadraticSpectrum q = solve_at_speed(s, 0.0);
    CHECK(q.infinite_count == 1);
    REQUIRE(q.modes.size() == 4);
    for (const std::complex<double> l : {std::complex<double>(-3.0, 0.0), std::complex<double>(0.0, std::sqrt(0.2)),
                                         std::complex<double>(0.0, 2.0), std::complex<double>(0.0, std::sqrt(2e19))}) {
        CAPTURE(l);
        CHECK(std::count_if(q.modes.begin(), q.modes.end(),
                            [&](const Mode& m) { return std::abs(m.lambda - l) <= m.error_bound; }) == 1);
    }
    CHECK_THROWS_WITH(solve_at_speed(s, 0.0, {EigenMethod::StateMatrix, false}), Catch::Contains("M is singular"));
}
