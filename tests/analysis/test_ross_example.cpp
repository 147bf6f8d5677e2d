// A rotor exported from another package (data/ross_rotor_example: 42 DOFs, 6 per
// node, free axial and torsional DOFs so K is singular, no damping): every
// analysis against independent computations and the exporter's reference values.
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/solve/spectrum_solver.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>
#include <gyrokit/scene/scene.hpp>

#include <catch2/catch.hpp>
#include <cmath>

using namespace gyrokit;

namespace {

Scene ross() { return load_scene(std::string(GYROKIT_DATA_DIR) + "/ross_rotor_example/scene.toml"); }

std::vector<double> grid(double from, double to, int n) {
    std::vector<double> w;
    for (int k = 0; k < n; ++k) w.push_back(from + (to - from) * k / (n - 1));
    return w;
}

using ld = long double;
using cld = std::complex<long double>;

// One Newton step on det P for the eigenvalue, in long double:
// dl = -y^H P(l) x / y^H P'(l) x. Its size bounds the error of l to first order,
// computed in 64-bit-mantissa arithmetic, independent of LAPACK.
ld newton_correction(const QuadraticPencil& p, const Mode& m) {
    const Eigen::Index n = p.M.rows();
    const cld l(m.lambda.real(), m.lambda.imag());
    cld num = 0, den = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        cld r = 0, d = 0;
        for (Eigen::Index j = 0; j < n; ++j) {
            const cld xj(m.right(j).real(), m.right(j).imag());
            r += (l * l * ld(p.M(i, j)) + l * ld(p.C(i, j)) + ld(p.K(i, j))) * xj;
            d += (ld(2) * l * ld(p.M(i, j)) + ld(p.C(i, j))) * xj;
        }
        const cld yi = std::conj(cld(m.left(i).real(), m.left(i).imag()));
        num += yi * r;
        den += yi * d;
    }
    return std::abs(num / den);
}

}  // namespace

TEST_CASE("ROSS example: dense eigenvalues against the exporter and a long-double Newton check, rigid-body modes "
          "put apart",
          "[ross]") {
    const Scene sc = ross();
    REQUIRE(sc.system.size() == 42);
    const GyroscopicSystem& sys = sc.system;
    // The exporter's values at 500 rad/s (Im > 0, |lambda| > 0.1), printed to 6 digits.
    const double reference[] = {91.560, 96.457, 265.406, 305.353, 658.347, 774.350, 821.325, 1062.921};
    EigenOptions left;
    left.left_vectors = true;
    for (double w : {0.0, 250.0, 500.0, 1000.0}) {
        INFO("speed " << w);
        const QuadraticSpectrum s = solve_at_speed(sys, w, left);
        // Free axial translation and free torsion, each q = a + b t: four zero eigenvalues.
        CHECK(s.rigid_body.size() == 4);
        const QuadraticPencil p = sys.at_speed(w);
        for (const Mode& r : s.rigid_body) {
            CHECK(std::abs(r.lambda) <= 1e-6 * s.scale);
            CHECK((p.K * r.right).norm() <= 1e-6 * p.K.norm());
            // They move only the axial (z) and torsional (t) DOFs.
            for (int node = 0; node < 7; ++node)
                for (int local : {0, 1, 3, 4}) {
                    CAPTURE(local);
                    CHECK(std::abs(r.right(6 * node + local)) <= 1e-6);
                }
        }
        CHECK(s.modes.size() == 42 - 2);   // 84 eigenvalues: 4 rigid, 80 in 40 conjugate pairs
        for (const Mode& m : s.modes) {
            CHECK(m.backward_error <= 1e-14);
            CHECK(m.stability() == Stability::Neutral);   // undamped: no real part beyond rounding
            CHECK(m.lambda.imag() > 1.0);
            CHECK(newton_correction(p, m) <= 1e-11L * std::abs(m.lambda));
        }
        if (w == 500.0)
            for (size_t k = 0; k < 8; ++k) {
                CAPTURE(k);
                CHECK(std::abs(s.modes[k].frequency() - reference[k]) <= 5e-4);
            }
        // The axial and torsional modes do not whirl; the bending modes do (or are planar at standstill).
        int none = 0;
        for (const Mode& m : s.modes) none += m.whirl == Whirl::None;
        CHECK(none >= 4);
        CHECK(s.modes[0].whirl == (w == 0.0 ? Whirl::Planar : Whirl::Backward));
    }
}

TEST_CASE("ROSS example: the sparse solver moves its shift off the rigid-body modes and agrees with QZ to 1e-10",
          "[ross][sparse]") {
    const Scene sc = ross();
    const GyroscopicSystem& sys = sc.system;
    for (double w : {0.0, 500.0, 1000.0}) {
        INFO("speed " << w);
        SparseEigenOptions o;
        o.modes = 10;
        const SparseSpectrum s = solve_quadratic_sparse(to_sparse(sys.at_speed(w)), o, sys.whirl_pairs);
        const QuadraticSpectrum d = solve_at_speed(sys, w);
        REQUIRE(s.modes.size() == 10);
        CHECK(!s.notes.empty());   // P(0) = K is singular: the shift was moved
        CHECK(s.shift.real() < 0.0);
        CHECK(s.shift.real() > -1.0);
        CHECK(!s.rigid_body.empty());
        for (size_t k = 0; k < s.modes.size(); ++k) {
            CAPTURE(k);
            CHECK(s.modes[k].backward_error <= 1e-10);
            CHECK(std::abs(s.modes[k].lambda - d.modes[k].lambda) <= 1e-10 * std::abs(d.modes[k].lambda));
            CHECK(s.modes[k].whirl == d.modes[k].whirl);
            CHECK(s.modes[k].stability() == Stability::Neutral);
        }
    }
}

TEST_CASE("ROSS example: the pencils carry a band order of 7 off-diagonals, found once per system", "[ross][pencil_lu]") {
    // 6 DOFs per node (x, y, z, alpha, beta, theta): a lateral DOF couples with the
    // next node's, 10 places on. The axial and torsional DOFs couple with no lateral
    // one, so the lateral DOFs alone, node by node (4 each), need 7 off-diagonals.
    const Scene sc = ross();
    const GyroscopicSystem& sys = sc.system;
    const SparsePencil p = sys.sparse_at_speed(500.0);
    int kl = 0, ku = 0;
    pattern_bandwidths({&p.M, &p.C, &p.K}, nullptr, kl, ku);
    CHECK(kl == 10);
    CHECK(ku == 10);
    REQUIRE(p.band_order);
    pattern_bandwidths({&p.M, &p.C, &p.K}, p.band_order.get(), kl, ku);
    CHECK(kl <= 7);
    CHECK(ku <= 7);
    // Every speed's pencil shares the order; a copy of the system finds its own.
    CHECK(sys.sparse_at_speed(0.0).band_order == p.band_order);
    const GyroscopicSystem copy = sys;
    const SparsePencil q = copy.sparse_at_speed(500.0);
    REQUIRE(q.band_order);
    CHECK(q.band_order != p.band_order);
    CHECK(q.band_order->old_of == p.band_order->old_of);
}

TEST_CASE("ROSS example: six lowest branches over 0-1000 rad/s without ambiguity, critical speeds equal the "
          "direct method to 1e-9, nothing unstable",
          "[ross][campbell]") {
    const Scene sc = ross();
    const GyroscopicSystem& sys = sc.system;
    CampbellOptions co;
    co.modes = 8;
    const CampbellDiagram cd = campbell(sys, grid(0.0, 1000.0, 101), co);
    CHECK(cd.ambiguous_steps == 0);
    CHECK(cd.rigid_body == 4);
    REQUIRE(cd.branches.size() == 8);
    for (const Branch& b : cd.branches) {
        CHECK(b.points.size() == cd.speeds.size());
        for (const BranchPoint& q : b.points) CHECK(q.mode.frequency() > 50.0);   // no rigid-body zero among them
    }
    CHECK(stability_changes(sys, cd).empty());
    CHECK(unstable_ranges(cd).empty());
    // Independent: K x = w^2 (M - i G) x, a linear Hermitian pencil (zggev).
    const std::vector<CriticalSpeed> direct = critical_speeds_direct(sys, 1, 0.0, 1000.0);
    const std::vector<CriticalSpeed> branch = critical_speeds(sys, cd, {1});
    // The exporter lists 774.35 rad/s as well: its axial mode, which moves no whirl pair,
    // so the rotor's unbalance cannot excite it. It is no critical speed here (the branch
    // crosses the 1x line all the same, in the diagram).
    const double published[] = {91.788, 96.296, 271.25, 300.35, 636.02, 866.83};
    REQUIRE(direct.size() == 6);
    REQUIRE(branch.size() == 6);
    for (size_t k = 0; k < 6; ++k) {
        INFO("critical speed " << k);
        CHECK(std::abs(branch[k].speed - direct[k].speed) <= 1e-9 * direct[k].speed);
        CHECK(std::abs(direct[k].speed - published[k]) <= 0.006);
        CHECK(branch[k].mode.whirl == direct[k].mode.whirl);
        CHECK(branch[k].mode.whirl != Whirl::None);
    }
    bool axial_branch = false;   // the axial branch is in the diagram, at 774.35 rad/s
    for (const Branch& b : cd.branches)
        for (const BranchPoint& q : b.points)
            axial_branch |= q.mode.whirl == Whirl::None && std::abs(q.mode.frequency() - 774.35) < 0.01;
    CHECK(axial_branch);
}

TEST_CASE("ROSS example with damped bearings: rigid-body modes stay apart, every mode stable, critical speeds are "
          "where Im lambda = w",
          "[ross][damped]") {
    Scene sc = ross();
    GyroscopicSystem& sys = sc.system;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(42, 42);
    for (int dof : {0, 1, 36, 37}) D(dof, dof) = 500.0;   // bearings at nodes 0 and 6, N s/m
    sys.damping.push_back({"bearings", D, {}});
    CampbellOptions co;
    co.modes = 6;
    const CampbellDiagram cd = campbell(sys, grid(0.0, 1000.0, 101), co);
    CHECK(cd.ambiguous_steps == 0);
    CHECK(cd.rigid_body == 4);   // damping does not reach the free axial and torsional motion
    CHECK(stability_changes(sys, cd).empty());
    for (const Branch& b : cd.branches)
        for (const BranchPoint& q : b.points)
            if (q.mode.whirl != Whirl::None) CHECK(q.mode.stability() == Stability::Stable);
    const std::vector<CriticalSpeed> cs = critical_speeds(sys, cd, {1});
    REQUIRE(cs.size() >= 5);
    for (const CriticalSpeed& c : cs) {
        // A fresh solve at the critical speed has an eigenvalue with Im lambda = w.
        const QuadraticSpectrum s = solve_at_speed(sys, c.speed);
        double nearest = 1e300;
        for (const Mode& m : s.modes) nearest = std::min(nearest, std::abs(m.lambda.imag() - c.speed));
        CHECK(nearest <= 1e-9 * c.speed);
    }
}
