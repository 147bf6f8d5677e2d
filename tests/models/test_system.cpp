// The one system type and the library's solver choice: storage, pencils,
// validation before any analysis, solvers that own their system.
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/gyrostat.hpp>
#include "test_helpers.hpp"

#include <catch2/catch.hpp>

using namespace gyrokit;

using test::centrifuge;

TEST_CASE("system: dense and sparse pencils are the same matrices", "[system]") {
    const GyroscopicSystem s = fe_uniform_shaft(1.0, 10, 0.05, 0.0, 2.1e11, 0.3, 7800).assemble().to_system();
    for (double w : {0.0, 10.0, 1234.5}) {
        CAPTURE(w);
        const QuadraticPencil d = s.at_speed(w);
        const SparsePencil p = s.sparse_at_speed(w);
        CHECK((d.M - Eigen::MatrixXd(p.M)).norm() == 0.0);
        CHECK((d.C - Eigen::MatrixXd(p.C)).norm() == 0.0);
        CHECK((d.K - Eigen::MatrixXd(p.K)).norm() == 0.0);
    }
    // Assigned from a dense expression, stored without its zeros.
    GyroscopicSystem t;
    t.M = Eigen::Matrix3d::Identity();
    CHECK(t.M.nonZeros() == 3);
    CHECK(t.M.dense() == Eigen::Matrix3d::Identity());
}

TEST_CASE("system: every analysis validates before it solves", "[system][validation]") {
    GyroscopicSystem bad;
    bad.M = Eigen::Matrix2d::Identity();
    bad.K = Eigen::Matrix3d::Identity();   // 3x3 against a 2x2 M
    bad.dofs.names = {"x", "y"};
    const std::vector<double> speeds{0.0, 1.0, 2.0};
    const auto message = [&](const std::function<void()>& f) {
        try {
            f();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no InputError");
    };
    CHECK(message([&] { campbell(bad, speeds); }).find("matrix K is 3x3, expected 2x2") != std::string::npos);
    CHECK(message([&] { choose_solver(bad, {}); }).find("matrix K is 3x3") != std::string::npos);
    SparseEigenOptions so;
    CHECK(message([&] { sparse_solver(bad, so); }).find("matrix K is 3x3") != std::string::npos);
    GyroscopicSystem nan = make_system(centrifuge());
    nan.K.coeffRef(0, 0) = std::nan("");
    CHECK(message([&] { choose_solver(nan, {}); }).find("NaN") != std::string::npos);
    // Options are checked by field name.
    SolverOptions o;
    o.modes = -2;   // -1 is kModesInRange
    CHECK(message([&] { choose_solver(make_system(centrifuge()), o); }).rfind("modes = -2", 0) == 0);
}

TEST_CASE("system: solvers own their system, a temporary model is safe", "[system]") {
    // The factory and its solvers outlive the temporary GyroscopicSystem.
    const SolverFactory dense = dense_solver(make_system(centrifuge()));
    const SolverChoice choice = choose_solver(make_system(centrifuge()), {});
    const QuadraticSpectrum a = dense()(20.0), b = choice.make()(20.0);
    const QuadraticSpectrum ref = solve_at_speed(make_system(centrifuge()), 20.0);
    REQUIRE(a.modes.size() == ref.modes.size());
    REQUIRE(b.modes.size() == ref.modes.size());
    for (std::size_t i = 0; i < ref.modes.size(); ++i) {
        CAPTURE(i);
        CHECK(a.modes[i].lambda == ref.modes[i].lambda);
        CHECK(b.modes[i].lambda == ref.modes[i].lambda);
    }
}

TEST_CASE("system: the automatic choice by size, dense refused above its limit", "[system][solver]") {
    const auto shaft = [](int elements) {   // pinned at both ends
        FeRotor r = fe_uniform_shaft(2.0, elements, 0.05, 0.0, 2.1e11, 0.3, 7800);
        r.supports = {FeSupport{0}, FeSupport{elements}};
        return r.assemble().to_system();
    };
    const GyroscopicSystem small = shaft(10), large = shaft(60), huge = shaft(760);
    CHECK(small.size() <= kAutoSparseDofs);
    CHECK(large.size() > kAutoSparseDofs);
    CHECK(huge.size() > kDenseLimit);
    CHECK(choose_solver(small, {}).kind == SolverKind::Dense);
    const SolverChoice sparse = choose_solver(large, {});
    CHECK(sparse.kind == SolverKind::Sparse);
    CHECK(sparse.modes == kDefaultSparseModes);
    CHECK(sparse.notes.size() == 1);   // the default window is said
    // The modes in range: dense (every mode, continued) up to kAutoDenseInRangeDofs.
    const GyroscopicSystem mid = shaft(99), above = shaft(101);   // about 400 DOFs, either side
    CHECK(mid.size() > kAutoSparseDofs);
    CHECK(mid.size() <= kAutoDenseInRangeDofs);
    CHECK(above.size() > kAutoDenseInRangeDofs);
    SolverOptions in_range;
    in_range.modes = kModesInRange;
    CHECK(choose_solver(mid, in_range).kind == SolverKind::Dense);
    CHECK(choose_solver(mid, {}).kind == SolverKind::Sparse);
    CHECK(choose_solver(above, in_range).kind == SolverKind::Sparse);
    SolverOptions dense;
    dense.kind = SolverKind::Dense;
    CHECK_THROWS_WITH(choose_solver(huge, dense), Catch::Contains("above the dense limit of 3000"));
    // The sparse choice on the small model gives its lowest modes as the dense one does.
    SolverOptions so;
    so.kind = SolverKind::Sparse;
    so.modes = 4;
    const QuadraticSpectrum s = choose_solver(small, so).make()(0.0), d = choose_solver(small, {}).make()(0.0);
    REQUIRE(s.modes.size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        CAPTURE(i);
        CHECK(std::abs(s.modes[i].lambda - d.modes[i].lambda) <= 1e-10 * std::abs(d.modes[i].lambda));
    }
}

TEST_CASE("workers: threads, processes and one worker give the same sparse spectra", "[system][workers]") {
    FeRotor r = fe_uniform_shaft(2.0, 60, 0.05, 0.0, 2.1e11, 0.3, 7800);
    r.supports = {FeSupport{0}, FeSupport{60}};
    const GyroscopicSystem sys = r.assemble().to_system();
    SparseEigenOptions so;
    so.modes = 4;
    const SolverFactory make = sparse_solver(sys, so, false);   // no reuse: each speed alone
    REQUIRE(!make.thread_safe());
    std::vector<double> speeds;
    for (int k = 0; k < 8; ++k) speeds.push_back(100.0 * k);
    const auto one = solve_speeds(make, speeds, 1);
    const auto threads = solve_speeds(make, speeds, Workers{2, WorkerKind::Threads});
    const auto processes = solve_speeds(make, speeds, Workers{2, WorkerKind::Processes});
    for (std::size_t i = 0; i < speeds.size(); ++i)
        for (const auto* other : {&threads, &processes}) {
            CAPTURE(i);
            REQUIRE((*other)[i].modes.size() == one[i].modes.size());
            for (std::size_t k = 0; k < one[i].modes.size(); ++k) {
                CAPTURE(k);
                CHECK(std::abs((*other)[i].modes[k].lambda - one[i].modes[k].lambda) <=
                      1e-10 * std::abs(one[i].modes[k].lambda));
            }
        }
}

TEST_CASE("spectra say which solver made them and what it took", "[system][status]") {
    const GyroscopicSystem g = make_system(centrifuge());
    CHECK(solve_at_speed(g, 10.0).method == "scaled QZ");
    EigenOptions state;
    state.method = EigenMethod::StateMatrix;
    CHECK(solve_at_speed(g, 10.0, state).method == "state matrix");
    SparseEigenOptions so;
    so.modes = 2;
    const QuadraticSpectrum s = sparse_solver(g, so)()(10.0);
    CHECK(s.method == "ARPACK shift-invert");
    CHECK(s.iterations >= 1);
    CHECK(s.partial);
    // Through a worker process the account arrives whole (speeds solved afresh: no
    // continuation, so the speeds go to the workers).
    const auto viaprocess =
        solve_speeds(sparse_solver(g, so, false), {10.0, 20.0}, Workers{2, WorkerKind::Processes});
    CHECK(viaprocess[0].method == "ARPACK shift-invert");
    CHECK(viaprocess[1].iterations >= 1);
    // A sweep continues the window's modes from speed to speed: the second speed says so.
    const auto walked = solve_speeds(sparse_solver(g, so), {10.0, 20.0}, Workers{2, WorkerKind::Processes});
    CHECK(walked[0].method == "ARPACK shift-invert");
    CHECK(walked[1].method == "continuation of the window (along the branches, verified)");
    CHECK(walked[1].iterations == 0);
    CHECK(walked[1].partial);
}
