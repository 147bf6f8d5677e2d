// Large-model path: bearing tables (interpolation, input errors), sparse matrix
// scenes and finite-element scenes, the sparse solver behind Campbell tracking
// (agreement with dense QZ, worker processes, start-vector reuse).
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/solve/workers.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/bearing_csv.hpp>
#include <gyrokit/io/matrix_market.hpp>
#include <gyrokit/scene/scene.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <map>

using namespace gyrokit;

namespace {

std::string data(const std::string& name) { return std::string(GYROKIT_DATA_DIR) + "/" + name; }

std::string write_temp(const std::string& name, const std::string& text) {
    const std::string path = "/tmp/gyrokit_test_" + name;
    std::ofstream(path) << text;
    return path;
}

const char* kHeader = "speed,dof_x,dof_y,kxx,kxy,kyx,kyy,cxx,cxy,cyx,cyy\n";

// The input error message of f(), or "" if it does not throw one.
template <class F>
std::string input_error(const F& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("bearing table: linear interpolation, end rows held, extrapolation reported", "[bearings]") {
    // An extra first column (ignored) and a comment line.
    const std::string path = write_temp("b1.csv", std::string("# comment\n") + "label," + kHeader +
                                                      "a,100,2,3,1e7,1e5,-1e5,2e7,100,1,1,200\n"
                                                      "b,300,2,3,3e7,3e5,-3e5,4e7,300,3,3,400\n");
    const BearingTable t = read_bearing_csv(path, 10);
    CHECK(t.dof_x == 2);
    CHECK(t.dof_y == 3);
    REQUIRE(t.speeds == std::vector<double>{100, 300});
    const BearingCoefficients mid = t.at(150.0);   // a quarter of the way
    CHECK(mid.K(0, 0) == Approx(1.5e7).epsilon(1e-15));
    CHECK(mid.K(0, 1) == Approx(1.5e5).epsilon(1e-15));
    CHECK(mid.K(1, 0) == Approx(-1.5e5).epsilon(1e-15));
    CHECK(mid.C(1, 1) == Approx(250.0).epsilon(1e-15));
    CHECK(t.at(100.0).K(1, 1) == 2e7);            // exact at table speeds
    CHECK(t.at(0.0).K(0, 0) == 1e7);              // held below
    CHECK(t.at(1e4).K(0, 0) == 3e7);              // held above
    CHECK(t.covers(200.0));
    CHECK_FALSE(t.covers(50.0));
    CHECK(extrapolation_notes({t}, 100.0, 300.0).empty());
    REQUIRE(extrapolation_notes({t}, 0.0, 500.0).size() == 1);
    CHECK(extrapolation_notes({t}, 0.0, 500.0)[0].find("covers 100 to 300 rad/s") != std::string::npos);
}

TEST_CASE("bearing table: bad tables give one clear error", "[bearings]") {
    const auto err = [](const std::string& name, const std::string& body, int dofs = 10) {
        return input_error([&] { read_bearing_csv(write_temp(name, body), dofs); });
    };
    CHECK(err("one.csv", std::string(kHeader) + "100,0,1,1,0,0,1,0,0,0,0\n").find("at least 2 rows") !=
          std::string::npos);
    CHECK(err("unsorted.csv", std::string(kHeader) + "200,0,1,1,0,0,1,0,0,0,0\n100,0,1,1,0,0,1,0,0,0,0\n")
              .find("strictly increasing") != std::string::npos);
    CHECK(err("range.csv", std::string(kHeader) + "100,0,12,1,0,0,1,0,0,0,0\n200,0,12,1,0,0,1,0,0,0,0\n")
              .find("dof_y = 12 is out of range; allowed: a whole number from 0 to 9") != std::string::npos);
    CHECK(err("column.csv", "speed,dof_x,dof_y,kxx\n1,0,1,2\n").find("no column 'kxy'") != std::string::npos);
    CHECK(err("nan.csv", std::string(kHeader) + "100,0,1,abc,0,0,1,0,0,0,0\n").find("kxx = 'abc'") !=
          std::string::npos);
    CHECK(err("pair.csv", std::string(kHeader) + "100,0,1,1,0,0,1,0,0,0,0\n200,2,3,1,0,0,1,0,0,0,0\n")
              .find("one DOF pair per table") != std::string::npos);
    CHECK(input_error([] { read_bearing_csv("/nonexistent/b.csv", 4); }).find("not found") != std::string::npos);
}

TEST_CASE("sparse Matrix Market reader equals the dense one", "[bearings][matrix_market]") {
    const std::vector<std::string> files = {
        "%%MatrixMarket matrix coordinate real symmetric\n3 3 4\n1 1 2.5\n2 1 -1\n3 3 4\n3 2 0.5\n",
        "%%MatrixMarket matrix coordinate real skew-symmetric\n3 3 2\n2 1 1.5\n3 1 -2\n",
        "%%MatrixMarket matrix coordinate real general\n2 3 3\n1 3 7\n2 1 -3\n2 2 0\n",
        "%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n"};
    for (size_t i = 0; i < files.size(); ++i) {
        CAPTURE(i);
        const std::string path = write_temp("mm" + std::to_string(i) + ".mtx", files[i]);
        const Eigen::MatrixXd A = read_matrix_market(path);
        const Eigen::MatrixXd B(read_matrix_market_sparse(path));
        REQUIRE(A.rows() == B.rows());
        REQUIRE(A.cols() == B.cols());
        CHECK((A - B).cwiseAbs().maxCoeff() == 0.0);
    }
    CHECK(input_error([&] {
              read_matrix_market_sparse(write_temp("mmdup.mtx", "%%MatrixMarket matrix coordinate real general\n"
                                                                "2 2 2\n1 1 1\n1 1 2\n"));
          }).find("repeats the entry on line") != std::string::npos);
}

TEST_CASE("speed-dependent bearings enter K and C of dense and sparse systems alike", "[bearings]") {
    const Scene sc = load_scene(data("fe_rotor.toml"));
    REQUIRE(sc.system.bearings.size() == 2);
    for (double w : {0.0, 333.0, 1250.0, 5000.0}) {
        CAPTURE(w);
        const QuadraticPencil d = sc.system.at_speed(w);
        const SparsePencil s = sc.system.sparse_at_speed(w);
        CHECK((d.K - Eigen::MatrixXd(s.K)).cwiseAbs().maxCoeff() <= 1e-15 * d.K.cwiseAbs().maxCoeff());
        CHECK((d.C - Eigen::MatrixXd(s.C)).cwiseAbs().maxCoeff() <= 1e-15 * d.C.cwiseAbs().maxCoeff());
        // The bearing at node 0 (DOFs x0, y0 = 0, 1) adds its interpolated coefficients.
        const BearingCoefficients b = sc.system.bearings[0].at(w);
        const GyroscopicSystem bare = [&] {
            GyroscopicSystem x = sc.system;
            x.bearings.clear();
            return x;
        }();
        const Eigen::MatrixXd dK = d.K - Eigen::MatrixXd(bare.sparse_at_speed(w).K);
        CHECK((dK.block(0, 0, 2, 2) - b.K).cwiseAbs().maxCoeff() <= 1e-8 * b.K.cwiseAbs().maxCoeff());
    }
}

TEST_CASE("sparse Campbell diagram agrees with dense QZ on the finite-element rotor", "[sparse][campbell]") {
    const Scene sc = load_scene(data("fe_rotor.toml"));
    const std::vector<double> speeds = SpeedRange{0.0, 3000.0, 16}.points();
    CampbellOptions co;
    co.modes = 4;
    const CampbellDiagram dense = campbell(dense_solver(sc.system), speeds, co);
    SparseEigenOptions so;
    so.modes = 6;   // a window a little wider than the tracked modes
    const CampbellDiagram sparse1 = campbell(sparse_solver(sc.system, so), speeds, co);
    co.threads = 2;   // worker processes
    const CampbellDiagram sparse2 = campbell(sparse_solver(sc.system, so), speeds, co);

    // Every point of the four lowest branches: sparse equals dense to 1e-10
    // (well-separated eigenvalues, backward errors ~1e-14).
    for (int b = 0; b < 4; ++b) {
        const Branch& bd = dense.branches[static_cast<size_t>(b)];
        const Branch& bs = sparse1.branches[static_cast<size_t>(b)];
        std::map<double, std::complex<double>> at;
        for (const auto& p : bd.points) at[p.speed] = p.mode.lambda;
        int compared = 0;
        for (const auto& p : bs.points) {
            CAPTURE(p);
            if (!at.count(p.speed)) continue;
            CHECK(std::abs(p.mode.lambda - at[p.speed]) <= 1e-10 * std::abs(at[p.speed]));
            CHECK(p.mode.backward_error < 1e-12);
            ++compared;
        }
        CHECK(compared >= 16);
    }
    // The worker processes return the same diagram.
    REQUIRE(sparse1.branches.size() == sparse2.branches.size());
    for (size_t b = 0; b < sparse1.branches.size(); ++b) {
        CAPTURE(b);
        REQUIRE(sparse1.branches[b].points.size() == sparse2.branches[b].points.size());
        for (size_t k = 0; k < sparse1.branches[b].points.size(); ++k)
            CHECK(std::abs(sparse1.branches[b].points[k].mode.lambda - sparse2.branches[b].points[k].mode.lambda) <=
                  1e-10 * std::abs(sparse1.branches[b].points[k].mode.lambda));
    }
    // Critical speeds from the sparse branches equal the dense ones.
    const auto cd = critical_speeds(dense_solver(sc.system), dense, {1});
    const auto cs = critical_speeds(sparse_solver(sc.system, so), sparse1, {1});
    REQUIRE(cd.size() >= 2);
    for (size_t i = 0; i < 2; ++i) {
        CAPTURE(i);
        CHECK(cs.at(i).speed == Approx(cd[i].speed).epsilon(1e-9));
    }
}

TEST_CASE("dense Campbell on two threads equals one thread, bit for bit", "[campbell]") {
    // QZ is deterministic, so speeds solved concurrently must give exactly the
    // serial diagram; a BLAS/LAPACK that is not safe for concurrent calls (as a
    // serial OpenBLAS build without locking) breaks this silently. Repeated,
    // since a race shows only now and then.
    const Scene sc = load_scene(data("fe_rotor.toml"));
    const std::vector<double> speeds = SpeedRange{0.0, 2000.0, 11}.points();
    CampbellOptions co;
    co.modes = 4;
    const CampbellDiagram serial = campbell(dense_solver(sc.system), speeds, co);
    co.threads = 2;
    for (int run = 0; run < 5; ++run) {
        CAPTURE(run);
        const CampbellDiagram parallel = campbell(dense_solver(sc.system), speeds, co);
        REQUIRE(parallel.branches.size() == serial.branches.size());
        for (size_t b = 0; b < serial.branches.size(); ++b) {
            CAPTURE(b);
            REQUIRE(parallel.branches[b].points.size() == serial.branches[b].points.size());
            for (size_t k = 0; k < serial.branches[b].points.size(); ++k)
                REQUIRE(parallel.branches[b].points[k].mode.lambda == serial.branches[b].points[k].mode.lambda);
        }
    }
}

TEST_CASE("dense Campbell with K modes: same branches as with all modes, no bisection for high modes",
          "[campbell]") {
    // The 100-DOF rotor: with all 100 modes tracked, veerings among the high
    // modes force bisections; with K = 4 only the low branches decide, and
    // they are exactly the low branches of the full diagram at every grid speed.
    const Scene sc = load_scene(data("fe_rotor.toml"));
    const std::vector<double> speeds = SpeedRange{0.0, 4000.0, 41}.points();
    CampbellOptions co;
    const CampbellDiagram all = campbell(dense_solver(sc.system), speeds, co);
    co.modes = 4;
    const CampbellDiagram low = campbell(dense_solver(sc.system), speeds, co);
    REQUIRE(low.branches.size() == 4);
    CHECK(low.inserted_speeds < all.inserted_speeds);
    for (size_t b = 0; b < 4; ++b) {
        CAPTURE(b);
        std::map<double, std::complex<double>> at;
        for (const auto& p : all.branches[b].points) at[p.speed] = p.mode.lambda;
        int compared = 0;
        for (const auto& p : low.branches[b].points) {
            CAPTURE(p);
            if (!at.count(p.speed)) continue;
            CHECK(p.mode.lambda == at[p.speed]);   // the same QZ solve at the same speed
            ++compared;
        }
        CHECK(compared >= 41);
    }
}

TEST_CASE("start-vector reuse gives the same modes", "[sparse]") {
    const Scene sc = load_scene(data("fe_rotor.toml"));
    SparseEigenOptions so;
    so.modes = 6;
    SpectrumSolver fresh = sparse_solver(sc.system, so, false)();
    SpectrumSolver reused = sparse_solver(sc.system, so, true)();
    for (double w : {1000.0, 1010.0, 1020.0}) {
        CAPTURE(w);
        const QuadraticSpectrum a = fresh(w), b = reused(w);
        REQUIRE(a.modes.size() == b.modes.size());
        // Both runs converge to machine precision (backward errors up to ~1e-12
        // for the highest of these modes); the eigenvalues agree within the sum of
        // their error bounds (condition times backward error: the x/y pairs of this
        // nearly isotropic rotor are close, so a backward error alone is too tight).
        double eta = 0.0;
        for (const Mode& m : a.modes) eta = std::max(eta, m.backward_error);
        for (const Mode& m : b.modes) eta = std::max(eta, m.backward_error);
        CHECK(eta < 1e-11);
        for (const Mode& m : a.modes) {
            double gap = INFINITY, allowed = 0.0;
            for (const Mode& n : b.modes)
                if (std::abs(m.lambda - n.lambda) < gap)
                    gap = std::abs(m.lambda - n.lambda), allowed = m.error_bound + n.error_bound;
            CHECK(gap <= allowed + 1e-14 * std::abs(m.lambda));
        }
    }
}

TEST_CASE("a sparse sweep continued along the branches gives the fresh window solves' modes within their bounds",
          "[sparse][continuation]") {
    // The window's modes from the first speed, continued speed to speed (inverse
    // iteration on the band LU, verified two-sided), against ARPACK afresh at every
    // speed with a wider window: each continued mode is one of the fresh ones within
    // the sum of the two error bounds, and its own pair verifies.
    const Scene sc = load_scene(data("fe_rotor.toml"));
    const std::vector<double> speeds = SpeedRange{0.0, 3000.0, 31}.points();
    SparseEigenOptions so;
    so.modes = 4;
    const auto walked = solve_speeds(sparse_solver(sc.system, so), speeds, Workers{2});
    so.modes = 8;
    const auto fresh = solve_speeds(sparse_solver(sc.system, so, false), speeds, Workers{2});
    int continued = 0, compared = 0;
    for (size_t k = 0; k < speeds.size(); ++k) {
        CAPTURE(speeds[k], walked[k].method);
        REQUIRE(walked[k].modes.size() == 4);
        continued += walked[k].method == "continuation of the window (along the branches, verified)";
        for (const Mode& m : walked[k].modes) {
            CHECK(m.backward_error <= 1e-10);
            double gap = INFINITY, allowed = 0.0;
            for (const Mode& n : fresh[k].modes)
                if (std::abs(m.lambda - n.lambda) < gap)
                    gap = std::abs(m.lambda - n.lambda), allowed = m.error_bound + n.error_bound;
            CHECK(gap <= allowed);
            ++compared;
        }
    }
    CHECK(compared == 4 * 31);
    // The first speed is a window solve, and so is the step from it on this rotor (its
    // standstill pairs are double and their vectors not the splitting directions); the
    // other 29 are continued here (at least 25 asked, rounding may decide a step near a check's limit).
    CHECK(continued >= 25);
}

TEST_CASE("sparse unbalance response equals the dense one", "[sparse][response]") {
    const Scene sc = load_scene(data("fe_rotor.toml"));
    for (double w : {50.0, 700.0, 2500.0}) {
        CAPTURE(w);
        const Eigen::VectorXcd a = unbalance_response(sc.system, w, SolverKind::Dense),
                               b = unbalance_response(sc.system, w, SolverKind::Sparse);
        CHECK((a - b).norm() <= 1e-10 * a.norm());
    }
}

TEST_CASE("fe_rotor and matrices scenes: bad input names the key", "[bearings][scene]") {
    const auto scene = [](const std::string& name, const std::string& body) {
        return input_error([&] { load_scene(write_temp(name, body)); });
    };
    const std::string base = "[model]\ntype = \"fe_rotor\"\nE = 2e11\ndensity = 7800\n[[model.shaft]]\nlength = 1.0\n"
                             "elements = 4\nouter_diameter = 0.05\n";
    CHECK(scene("fe1.toml", base + "[[model.disk]]\nz = 0.3\nmass = 1\n").find("is not a node of the mesh") !=
          std::string::npos);
    CHECK(scene("fe2.toml", base + "[[model.bearing]]\nz = 0.0\nk = -1\n").find("k = -1: out of range") !=
          std::string::npos);
    CHECK(scene("fe3.toml", "[model]\ntype = \"fe_rotor\"\n[[model.shaft]]\nlength = 1.0\nouter_diameter = 0.05\n")
              .find("E' is missing") != std::string::npos);
    CHECK(scene("fe4.toml", base + "[[model.shaft]]\nlength = 1\nouter_diameter = 0.05\ninner_diameter = 0.06\n")
              .find("is not below outer_diameter") != std::string::npos);
    CHECK(scene("fe5.toml", base + "[[model.bearing]]\nz = 0\ntable = \"missing.csv\"\n").find("not found") !=
          std::string::npos);
}

TEST_CASE("sparse window following the 1x line finds every 1x critical speed with four modes", "[sparse][critical]") {
    // The centre i(nu + k w) moves with the speed, so a window of four modes holds,
    // at each speed, the modes near the excitation line: every crossing of 1x in
    // 0..4000 rad/s must come out, as with the dense solver tracking all modes.
    const Scene sc = load_scene(data("fe_rotor.toml"));
    const std::vector<double> speeds = sc.speed_points();
    CampbellOptions low;
    low.modes = 14;   // all branches below 4000 rad/s at every speed, and more
    const CampbellDiagram dense = campbell(dense_solver(sc.system), speeds, low);
    const auto cd = critical_speeds(dense_solver(sc.system), dense, {1});

    SparseEigenOptions so;
    so.modes = 4;
    so.shift_order = 1.0;
    CampbellOptions co;
    co.modes = 4;
    const CampbellDiagram sparse = campbell(sparse_solver(sc.system, so), speeds, co);
    const auto cs = critical_speeds(sparse_solver(sc.system, so), sparse, {1});

    REQUIRE(cd.size() >= 8);   // more crossings than the window holds modes
    REQUIRE(cs.size() == cd.size());
    for (size_t i = 0; i < cd.size(); ++i) {
        CAPTURE(i);
        CHECK(cs[i].speed == Approx(cd[i].speed).epsilon(1e-9));
        CHECK(cs[i].mode.whirl == cd[i].mode.whirl);
    }
    // Without the continuation the fixed window (centre 0) sees only the lowest four.
    so.shift_order = 0.0;
    const CampbellDiagram fixed = campbell(sparse_solver(sc.system, so), speeds, co);
    CHECK(critical_speeds(sparse_solver(sc.system, so), fixed, {1}).size() < cd.size());
}

TEST_CASE("critical speeds refined on two workers equal the serial ones", "[critical][campbell]") {
    // The root searches are independent: on two threads (dense QZ) they must give
    // exactly the serial result, in worker processes (ARPACK) the same to 1e-10.
    const Scene cf = load_scene(data("centrifuge.toml"));
    const CampbellDiagram dense = campbell(dense_solver(cf.system), cf.speed_points());
    const auto d1 = critical_speeds(dense_solver(cf.system), dense, {1, 2}, 1);
    const auto d2 = critical_speeds(dense_solver(cf.system), dense, {1, 2}, 2);
    REQUIRE(d1.size() >= 5);
    REQUIRE(d2.size() == d1.size());
    for (size_t i = 0; i < d1.size(); ++i) {
        CAPTURE(i);
        CHECK(d2[i].speed == d1[i].speed);
        CHECK(d2[i].branch == d1[i].branch);
        CHECK(d2[i].mode.lambda == d1[i].mode.lambda);
    }
    const Scene sc = load_scene(data("fe_rotor.toml"));
    const std::vector<double> speeds = SpeedRange{0.0, 3000.0, 16}.points();
    CampbellOptions co;
    co.modes = 6;
    SparseEigenOptions so;
    so.modes = 8;
    const CampbellDiagram sparse = campbell(sparse_solver(sc.system, so), speeds, co);
    const auto s1 = critical_speeds(sparse_solver(sc.system, so), sparse, {1}, 1);
    const auto s2 = critical_speeds(sparse_solver(sc.system, so), sparse, {1}, 2);
    REQUIRE(s1.size() >= 5);
    REQUIRE(s2.size() == s1.size());
    for (size_t i = 0; i < s1.size(); ++i) {
        CAPTURE(i);
        CHECK(s2[i].speed == Approx(s1[i].speed).epsilon(1e-10));
    }
    // Stability changes use the same workers.
    const auto u1 = stability_changes(dense_solver(cf.system), dense, 1);
    const auto u2 = stability_changes(dense_solver(cf.system), dense, 2);
    REQUIRE(u2.size() == u1.size());
    for (size_t i = 0; i < u1.size(); ++i) {
        CAPTURE(i);
        CHECK(u2[i].speed == u1[i].speed);
    }
}

TEST_CASE("a worker process that dies is reaped and reported with the speed it was solving", "[workers][reliability]") {
    SolverFactory f([] {
        return SpectrumSolver([](double w) {
            if (w == 3.0) std::raise(SIGKILL);
            QuadraticSpectrum s;
            s.speed = w;
            return s;
        });
    });
    f.not_thread_safe();   // forces worker processes
    const std::vector<double> speeds{1.0, 2.0, 3.0, 4.0};
    try {
        solve_speeds(f, speeds, 2);
        FAIL("no error for a dead worker");
    } catch (const Error& e) {
        CHECK(std::string(e.what()).find("died (signal 9) while solving speed 3 rad/s") != std::string::npos);
    }
    // Without the crash the same workers give every speed.
    SolverFactory fine([] { return SpectrumSolver([](double w) { QuadraticSpectrum s; s.speed = w; return s; }); });
    fine.not_thread_safe();
    CHECK(solve_speeds(fine, speeds, 2).size() == 4);
}
