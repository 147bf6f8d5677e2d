// The continuation (along the branches, and on the projected pencil) against the
// full dense solve, on every scene in data/ it can run: the same modes within the
// band at every speed, eigenvalues within the two error bounds each path reports;
// the tracking along slopes without ambiguity on the three-disk rotor.
#include "test_helpers.hpp"
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/solve/continuation.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace gyrokit;

namespace {

const std::string data = GYROKIT_DATA_DIR;

// At most `count` speeds of the scene's grid, ends included.
std::vector<double> thinned(const std::vector<double>& grid, size_t count) {
    if (grid.size() <= count) return grid;
    std::vector<double> out;
    for (size_t k = 0; k < count; ++k) out.push_back(grid[k * (grid.size() - 1) / (count - 1)]);
    return out;
}

// Every mode of `a` has one in `b` within the sum of their bounds, and the
// reverse; modes within 1e-6 of the band's edge may be on one side only.
void same_modes(const QuadraticSpectrum& a, const QuadraticSpectrum& b, double band, const std::string& where) {
    const auto edge = [&](const Mode& m) {
        const double f = std::abs(m.lambda.imag()) <= a.real_tol ? std::abs(m.lambda) : m.lambda.imag();
        return std::abs(f - band) <= 1e-6 * band;
    };
    for (const auto& [from, to] : {std::pair{&a, &b}, std::pair{&b, &a}})
        for (const Mode& m : from->modes) {
            if (edge(m)) continue;
            double best = INFINITY, allowed = 0;
            for (const Mode& o : to->modes)
                if (std::abs(o.lambda - m.lambda) < best)
                    best = std::abs(o.lambda - m.lambda), allowed = m.error_bound + o.error_bound;
            INFO(where << ": lambda = " << m.lambda << ", nearest at " << best << ", bounds " << allowed);
            CHECK(best <= allowed);
        }
}

// The full solve's modes within the band (the continuation reports no others).
QuadraticSpectrum within(QuadraticSpectrum f, double band) {
    std::vector<Mode> kept;
    for (Mode& m : f.modes)
        if (within_band(m, band, f.real_tol)) kept.push_back(std::move(m));
    f.modes = std::move(kept);
    return f;
}

// The rotor scenes of data/ with a speed grid and min_dofs to 400 DOFs (the dense
// solver's), by file name; the balancer, Sommerfeld and fluid scenes have their own tools.
std::vector<std::pair<std::string, Scene>> dense_rotor_scenes(int min_dofs) {
    std::vector<std::pair<std::string, Scene>> out;
    for (const auto& entry : std::filesystem::directory_iterator(data)) {
        if (entry.path().extension() != ".toml") continue;
        Scene sc;
        try {
            sc = load_scene(entry.path().string());
        } catch (const Error&) {
            continue;
        }
        if (sc.speeds && sc.dofs() <= 400 && sc.dofs() >= min_dofs)
            out.emplace_back(entry.path().filename().string(), std::move(sc));
    }
    return out;
}

}  // namespace

TEST_CASE("continuation: the modes in range equal the full solve's within their bounds on every data/ scene",
          "[continuation][slow]") {
    int used = 0;
    for (const auto& [name, sc] : dense_rotor_scenes(2)) {
        const std::vector<double> grid = thinned(sc.speed_points(), 26);
        const double band = excitation_band(grid, sc.analysis.harmonics);
        if (!std::isfinite(band)) continue;
        const auto model = std::make_shared<const GyroscopicSystem>(sc.system);
        for (const bool along : {true, false}) {
            ContinuationOptions o;
            o.band = band;
            o.anchor_stride = 5;
            o.max_basis_fraction = 1.0;   // continue even where it would not pay: the answers are what is tested
            o.along_branches = along;     // each path on its own: along the branches, the projected pencil
            ContinuationReport rep;
            const SolverFactory cont = continuation_solver(model, grid, o, &rep);
            if (!along) {
                REQUIRE(rep.used);
                ++used;
            }
            const SpectrumSolver reduced = cont(), full = dense_solver(sc.system)();
            for (double w : grid) {
                const QuadraticSpectrum f = within(full(w), band);
                const QuadraticSpectrum r = reduced(w);
                for (const Mode& m : r.modes) CHECK(m.backward_error <= 1e-10);
                same_modes(r, f, band, name + " at " + std::to_string(w) + " rad/s");
            }
            // Between the grid speeds too (a root search's speeds).
            for (size_t k = 0; k + 1 < grid.size(); k += 7) {
                const double w = 0.5 * (grid[k] + grid[k + 1]);
                same_modes(reduced(w), within(full(w), band), band, name + " at " + std::to_string(w) + " rad/s");
            }
        }
    }
    CHECK(used >= 5);
}

TEST_CASE("three-disk rotor: default Campbell tracks the modes in range without an ambiguous step, and its "
          "critical speeds equal the full solve's",
          "[continuation]") {
    const Scene sc = load_scene(data + "/three_disk_rotor.toml");
    const std::vector<double> grid = sc.speed_points();
    SolverOptions so;
    so.modes = kModesInRange;
    const SolverChoice plan = choose_solver(sc.system, so);
    const CampbellOptions co = tracking_options(plan, kModesInRange, grid, sc.analysis.harmonics, 2);
    CHECK(co.band == Approx(kBandMargin * 15000 * M_PI / 30));
    const SolverFactory solver = tracking_solver(plan.make, co, grid);
    const CampbellDiagram cd = campbell(solver, grid, co);
    CHECK(cd.ambiguous_steps == 0);
    // Most speeds are stepped along the branches (the anchor, and a few steps next to
    // crossings or at checks, are full solves).
    size_t stepped = 0;
    for (const QuadraticSpectrum& s : solve_speeds(solver, grid, 1))
        stepped += s.method == "continuation (along the branches, verified)";
    CHECK(stepped >= grid.size() / 2);
    CHECK(cd.branches.size() >= 8);
    for (const Branch& b : cd.branches)
        for (const BranchPoint& p : b.points) CHECK(p.mode.backward_error <= 1e-10);
    const auto cs = critical_speeds(solver, cd, {1}, 2);
    // The full path: every mode, every speed.
    CampbellOptions every = co;
    every.band = INFINITY;
    const CampbellDiagram full = campbell(plan.make, grid, every);
    const auto fcs = critical_speeds(plan.make, full, {1}, 2);
    REQUIRE(cs.size() == 4);
    REQUIRE(fcs.size() == cs.size());
    for (size_t k = 0; k < cs.size(); ++k) {
        // Each root within the speed tolerance of the two searches (relative 1e-9 of the speed).
        CHECK(std::abs(cs[k].speed - fcs[k].speed) <= 1e-8 * fcs[k].speed);
        CHECK(cs[k].mode.whirl == fcs[k].mode.whirl);
    }
}

namespace {

// A Jeffcott rotor: mass m on an isotropic shaft k with damping c, unbalance m e.
GyroscopicSystem jeffcott(double zeta) {
    const double m = 10.0, k = 4e6, c = 2.0 * zeta * std::sqrt(k * m), e = 1e-4;
    GyroscopicSystem s;
    s.M = Eigen::MatrixXd(m * Eigen::MatrixXd::Identity(2, 2));
    s.K = Eigen::MatrixXd(k * Eigen::MatrixXd::Identity(2, 2));
    s.damping.push_back({"c", Eigen::MatrixXd(c * Eigen::MatrixXd::Identity(2, 2))});
    s.unbalance = Eigen::VectorXcd(2);
    s.unbalance << std::complex<double>(m * e, 0.0), std::complex<double>(0.0, -m * e);
    s.dofs.names = {"x", "y"};
    s.dofs.units = {"m", "m"};
    s.whirl_pairs = {{0, 1}};
    return s;
}

// The half-power amplification factor of the Jeffcott unbalance response in closed
// form: |Z| ~ s / sqrt((1 - s)^2 + 4 zeta^2 s) with s = (w/wn)^2 peaks at
// s_p = 1/(1 - 2 zeta^2), a_p = 1/(2 zeta sqrt(1 - zeta^2)); the half-power points
// solve (a_p^2 - 2) s^2 + a_p^2 (4 zeta^2 - 2) s + a_p^2 = 0.
double jeffcott_af(double zeta) {
    const double sp = 1.0 / (1.0 - 2.0 * zeta * zeta), ap2 = 1.0 / (4.0 * zeta * zeta * (1.0 - zeta * zeta));
    const double a = ap2 - 2.0, b = ap2 * (4.0 * zeta * zeta - 2.0), c = ap2;
    const double d = std::sqrt(b * b - 4.0 * a * c);
    const double s1 = (-b - d) / (2.0 * a), s2 = (-b + d) / (2.0 * a);
    return std::sqrt(sp) / (std::sqrt(std::max(s1, s2)) - std::sqrt(std::min(s1, s2)));
}

}  // namespace

TEST_CASE("amplification factor: half-power on the Jeffcott rotor's unbalance response equals the closed form, "
          "and API 684 calls AF < 2.5 not critical",
          "[continuation]") {
    for (const double zeta : {0.01, 0.05, 0.1, 0.3}) {
        const GyroscopicSystem sys = jeffcott(zeta);
        const double wn = std::sqrt(4e6 / 10.0);
        const std::vector<double> grid = {0.0, 0.5 * wn, 1.5 * wn, 2.0 * wn};
        const SolverFactory solver = dense_solver(sys);
        const CampbellDiagram cd = campbell(solver, grid);
        std::vector<CriticalSpeed> cs = critical_speeds(solver, cd, {1});
        REQUIRE(cs.size() >= 1);
        set_amplification_factors(cs, sys);
        for (const CriticalSpeed& c : cs) {
            INFO("zeta " << zeta << ", crossing at " << c.speed);
            CHECK(c.speed == Approx(wn * std::sqrt(1.0 - zeta * zeta)).epsilon(1e-9));
            // The peak speed to sqrt(eps) relative on a flat top, the half-power roots to 1e-10: AF to 1e-6.
            CHECK(c.amplification_method == AmplificationMethod::HalfPower);
            // x and y of the circular orbit tie: the first is the probe, named.
            CHECK(c.amplification_dof == "x");
            CHECK(c.amplification_note.empty());
            CHECK(c.amplification == Approx(jeffcott_af(zeta)).epsilon(1e-6));
            CHECK(c.api684_critical() == (jeffcott_af(zeta) >= 2.5));
        }
    }
    // Without an unbalance: 1/(2 zeta).
    GyroscopicSystem bare = jeffcott(0.1);
    bare.unbalance.resize(0);
    const SolverFactory solver = dense_solver(bare);
    const double wn = std::sqrt(4e5);
    std::vector<CriticalSpeed> cs = critical_speeds(solver, campbell(solver, {0.0, 2.0 * wn}), {1});
    REQUIRE(!cs.empty());
    set_amplification_factors(cs, bare);
    CHECK(cs[0].amplification_method == AmplificationMethod::DampingRatio);
    CHECK(cs[0].amplification == Approx(5.0).epsilon(1e-9));
    CHECK(cs[0].amplification_dof.empty());
    CHECK(cs[0].amplification_note == "the model has no unbalance");
    // A 2x crossing: the unbalance excites 1x only.
    std::vector<CriticalSpeed> twice = critical_speeds(solver, campbell(solver, {0.0, 2.0 * wn}), {2});
    REQUIRE(!twice.empty());
    set_amplification_factors(twice, jeffcott(0.1));
    CHECK(twice[0].amplification_note == "harmonic 2: the unbalance excites 1x");
}

TEST_CASE("amplification factors name their DOF, or why the damping ratio's 1/(2 zeta) stands in", "[continuation]") {
    // The three-disk rotor: its forward crossing's half-power AF at the mid-span x; its backward
    // crossing shows no peak of its own at x12 or y12 (the forward mode's covers it).
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    const CriticalSpeedStudy st = critical_speed_study(sc.system, study_options(sc));
    REQUIRE(st.critical.size() >= 2);
    const CriticalSpeed& backward = st.critical[0];
    const CriticalSpeed& forward = st.critical[1];
    CHECK(forward.mode.whirl == Whirl::Forward);
    CHECK(forward.amplification_method == AmplificationMethod::HalfPower);
    CHECK(forward.amplification_dof == "x12");
    CHECK(forward.amplification_note.empty());
    CHECK(backward.mode.whirl == Whirl::Backward);
    CHECK(backward.amplification_method == AmplificationMethod::DampingRatio);
    CHECK(backward.amplification_note == "no response peak of this crossing at x12 or y12");
}

TEST_CASE("a Campbell study gives the same bits on one worker, on two processes, on two threads and again",
          "[continuation][reproducible]") {
    // LAPACK 3.11's dggev3 read workspace before writing it: the last digits followed whatever
    // the memory held, so a second call or another worker printed other 12th digits.
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/three_disk_rotor.toml");
    StudyOptions so = study_options(sc);
    const auto diagram = [&](Workers w) {
        so.workers = w;
        return campbell_study(sc.system, so).diagram;
    };
    const CampbellDiagram one = diagram(Workers{1});
    for (const Workers& w : {Workers{2, WorkerKind::Processes}, Workers{2, WorkerKind::Threads}, Workers{1}}) {
        const CampbellDiagram other = diagram(w);
        REQUIRE(other.speeds == one.speeds);
        REQUIRE(other.branches.size() == one.branches.size());
        for (std::size_t b = 0; b < one.branches.size(); ++b) {
            REQUIRE(other.branches[b].points.size() == one.branches[b].points.size());
            for (std::size_t k = 0; k < one.branches[b].points.size(); ++k)
                CHECK(other.branches[b].points[k].mode.lambda == one.branches[b].points[k].mode.lambda);
        }
    }
}

TEST_CASE("the K lowest modes on the continuation: the same branches as a full solve at every speed, within their "
          "bounds, on every dense data/ scene",
          "[continuation]") {
    int compared = 0;
    // Up to 200 DOFs: the full solves of the reference dominate the time (the 336-DOF
    // compressor's continuation is checked by the modes-in-range case above).
    for (const auto& [where, sc] : dense_rotor_scenes(24)) {
        if (sc.dofs() > 200) continue;
        const std::vector<double> grid = thinned(sc.speed_points(), 26);
        if (grid.size() < 2) continue;
        CampbellOptions co;
        co.modes = 4;   // the reference: a full solve at every speed, its 4 lowest branches
        const CampbellDiagram full = campbell(dense_solver(sc.system), grid, co);
        for (const int k : {1, 4}) {
            StudyOptions so;
            so.speeds = grid;
            so.solver.modes = k;
            so.solver.kind = SolverKind::Dense;
            const CampbellDiagram cont = campbell_study(sc.system, so).diagram;
            INFO(where << ", " << k << " modes, band " << cont.band);
            // One continuation in a band of at least f_cut (the default: 1.5 times the top speed).
            CHECK(std::isfinite(cont.band));
            CHECK(cont.band >= excitation_band(grid, {1}));
            REQUIRE(cont.branches.size() == static_cast<size_t>(k));
            REQUIRE(full.branches.size() >= cont.branches.size());
            for (size_t b = 0; b < cont.branches.size(); ++b) {
                // Both diagrams hold the grid speeds; bisections may add others to either.
                for (const BranchPoint& p : full.branches[b].points) {
                    const auto q = std::find_if(cont.branches[b].points.begin(), cont.branches[b].points.end(),
                                                [&](const BranchPoint& c) { return c.speed == p.speed; });
                    if (q == cont.branches[b].points.end()) continue;
                    INFO("branch " << b + 1 << " at " << p.speed << " rad/s: " << q->mode.lambda << " vs "
                                   << p.mode.lambda);
                    CHECK(std::abs(q->mode.lambda - p.mode.lambda) <= q->mode.error_bound + p.mode.error_bound);
                    ++compared;
                }
            }
        }
    }
    CHECK(compared >= 500);
}

TEST_CASE("a step that fails whole is taken in halves: every speed between the anchors stepped along the "
          "branches, equal to the full solve within the bounds",
          "[continuation]") {
    // ROSS's rotor_example, 0 to 1000 rad/s in 10 rad/s steps, the 6 lowest modes: the
    // whole step to 10 rad/s fails (a near-double pair at 2605 rad/s splits faster than
    // its slopes tell) and so does the one to 140 rad/s (two predictions 0.05 rad/s
    // apart at a crossing); their halves pass.
    const Scene sc = load_scene(data + "/ross_rotor_example/scene.toml");
    const std::vector<double> grid = SpeedRange{0.0, 1000.0, 101}.points();
    ContinuationOptions o;
    o.lowest = 6;
    ContinuationReport rep;
    const SolverFactory cont = continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o, &rep);
    const std::vector<QuadraticSpectrum> stepped = solve_speeds(cont, grid, 1);
    const SpectrumSolver full = dense_solver(sc.system)();
    for (size_t k = 0; k < grid.size(); ++k) {
        const bool anchor = std::find(rep.anchors.begin(), rep.anchors.end(), grid[k]) != rep.anchors.end();
        INFO("at " << grid[k] << " rad/s: " << stepped[k].method);
        CHECK((anchor || stepped[k].method == "continuation (along the branches, verified)"));
        for (const Mode& m : stepped[k].modes) CHECK(m.backward_error <= 1e-10);
        same_modes(stepped[k], within(full(grid[k]), rep.band), rep.band, "rotor_example");
    }
    // The mode at 2042 rad/s at standstill (beyond twice the band of 968 rad/s) comes
    // down to 1924 rad/s by the check speed 250 rad/s: it joins the followed modes by
    // inverse iteration at its eigenvalue there, not by a full solve.
    CHECK(cont.work().joined == 1);
    CHECK(cont.work().local_solves == 0);
}

TEST_CASE("a mode that comes from beyond twice the band is caught by the eigenvalues at the next check speed",
          "[continuation]") {
    // Bearings that soften with speed (kxx from 1e9 down to 1e5 N/m, kyy 1.5 times): the
    // bearing modes at 3357 and 3383 rad/s at standstill fall to 366 and 480 rad/s at 750
    // rad/s. With the band at 400 rad/s only the modes near 651 rad/s are continued from
    // the first speed; the falling ones are beyond twice the band there, so the continued
    // modes cannot account for them at the check speed 750 rad/s, which is solved in
    // full. Every other speed is stepped along the branches, and none misses a mode (the
    // lower one enters the band between 700 and 750 rad/s).
    const std::string text = R"(
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 1.0
elements = 6
outer_diameter = 0.08
[[model.disk]]
z = 0.5
outer_diameter = 0.3
width = 0.05
[[model.bearing]]
z = 0.0
speeds = [0, 125, 250, 375, 500, 625, 750, 875, 1000]
kxx = [1e9, 3.16e8, 1e8, 3.16e7, 1e7, 3.16e6, 1e6, 3.16e5, 1e5]
kyy = [1.5e9, 4.74e8, 1.5e8, 4.74e7, 1.5e7, 4.74e6, 1.5e6, 4.74e5, 1.5e5]
cxx = [1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2]
cyy = [1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2]
[[model.bearing]]
z = 1.0
speeds = [0, 125, 250, 375, 500, 625, 750, 875, 1000]
kxx = [1e9, 3.16e8, 1e8, 3.16e7, 1e7, 3.16e6, 1e6, 3.16e5, 1e5]
kyy = [1.5e9, 4.74e8, 1.5e8, 4.74e7, 1.5e7, 4.74e6, 1.5e6, 4.74e5, 1.5e5]
cxx = [1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2]
cyy = [1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2, 1e2]
)";
    const Scene sc = parse_scene(text, "softening.toml");
    const std::vector<double> grid = SpeedRange{0.0, 1000.0, 21}.points();
    ContinuationOptions o;
    o.band = 400.0;
    o.check_stride = 5;
    ContinuationReport rep;
    const SolverFactory cont = continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o, &rep);
    CHECK(rep.anchors == std::vector<double>{0.0});
    CHECK(rep.checks == std::vector<double>{250.0, 500.0, 750.0, 1000.0});
    const std::vector<QuadraticSpectrum> got = solve_speeds(cont, grid, 1);
    const SpectrumSolver full = dense_solver(sc.system)();
    const QuadraticSpectrum at0 = full(0.0);
    REQUIRE(at0.modes.size() >= 4);
    CHECK(at0.modes[2].lambda.imag() > 2.0 * o.band);   // the pair that falls, beyond twice the band
    for (size_t k = 0; k < grid.size(); ++k) {
        INFO("at " << grid[k] << " rad/s: " << got[k].method);
        CHECK(got[k].method == (k == 0 || k == 15 ? "scaled QZ" : "continuation (along the branches, verified)"));
        same_modes(got[k], within(full(grid[k]), o.band), o.band, "softening bearings");
    }
    CHECK(got[14].modes.size() == 2);
    CHECK(got[15].modes.size() == 3);   // 750 rad/s: the lower falling mode is in the band
}

TEST_CASE("the band of the K lowest modes: 1.25 times the largest of the K lowest at the anchors",
          "[continuation]") {
    const Scene sc = load_scene(data + "/ross_rotor_example/scene.toml");
    const std::vector<double> grid = SpeedRange{0.0, 1000.0, 11}.points();
    ContinuationOptions o;
    o.lowest = 6;
    o.anchor_stride = 5;
    ContinuationReport rep;
    (void)continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o, &rep);
    REQUIRE(rep.anchors == std::vector<double>{0.0, 500.0, 1000.0});
    double top = 0.0;
    const SpectrumSolver full = dense_solver(sc.system)();
    for (double w : rep.anchors) {
        std::vector<Mode> m = full(w).modes;
        sort_by_frequency(m);
        for (size_t i = 0; i < 6; ++i) top = std::max(top, m[i].lambda.imag());
    }
    CHECK(rep.band == Approx(1.25 * top).epsilon(1e-12));
    o.lowest = -1;
    CHECK_THROWS_AS(continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o), InputError);
    o.lowest = 6;
    o.band_margin = 0.5;   // a band below the modes it should hold
    CHECK_THROWS_WITH(continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o),
                      Catch::Contains("a margin >= 1"));
    o.band_margin = 1.25;
    o.anchor_stride = -1;
    CHECK_THROWS_WITH(continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o),
                      Catch::Contains("anchor_stride -1: allowed: 0"));
    o.anchor_stride = 0;
    o.check_stride = 0;
    CHECK_THROWS_WITH(continuation_solver(std::make_shared<const GyroscopicSystem>(sc.system), grid, o),
                      Catch::Contains("check_stride 0: allowed: 1 or more"));
}

TEST_CASE("a double eigenvalue at standstill gets the slopes of its split, equal to a difference quotient",
          "[continuation][slopes]") {
    // An isotropic rotor (equal kxx, kyy, cxx, cyy): at standstill each pair is double and
    // is returned as its backward and forward circular mode; gyroscopic coupling splits it
    // linearly in the speed. The slopes set_slopes gives those modes are the split's:
    // (lambda(h) - lambda(0)) / h of the same whirl, to O(h) (h = 0.01 rad/s).
    const std::string text = R"(
[model]
type = "fe_rotor"
material = "steel"
[[model.shaft]]
length = 1.0
elements = 10
outer_diameter = 0.08
[[model.disk]]
z = 0.5
outer_diameter = 0.4
width = 0.05
[[model.bearing]]
z = 0.0
kxx = 2e7
kyy = 2e7
cxx = 2e3
cyy = 2e3
[[model.bearing]]
z = 1.0
kxx = 2e7
kyy = 2e7
cxx = 2e3
cyy = 2e3
)";
    const Scene sc = parse_scene(text, "isotropic.toml");
    const SpectrumSolver solve = dense_solver(sc.system)();
    const double h = 0.01;
    const QuadraticSpectrum s0 = solve(0.0), sh = solve(h);
    int doubles = 0;
    for (size_t i = 0; i < 6; ++i) {
        const Mode& m = s0.modes[i];
        CAPTURE(i, m.lambda, m.slope);
        // The same whirl, nearest at h.
        const Mode* at = nullptr;
        for (const Mode& o : sh.modes)
            if (o.whirl == m.whirl && (!at || std::abs(o.lambda - m.lambda) < std::abs(at->lambda - m.lambda))) at = &o;
        REQUIRE(at);
        const std::complex<double> quotient = (at->lambda - m.lambda) / h;
        bool pair = false;
        for (const Mode& o : s0.modes)
            if (&o != &m && std::abs(o.lambda - m.lambda) <= 1e-6 * std::abs(m.lambda)) pair = true;
        doubles += pair;
        REQUIRE(std::isfinite(m.slope.real()));
        CHECK(std::abs(m.slope - quotient) <= 1e-3 * std::abs(quotient) + 1e-9);
    }
    CHECK(doubles == 6);   // three double pairs
}

TEST_CASE("f_cut sets the modes judged: the band as asked, every mode below it at some speed judged, those above "
          "it named; from the scene key as from the option",
          "[continuation]") {
    Scene sc = load_scene(data + "/three_disk_rotor.toml");
    const std::vector<double> grid = thinned(sc.speed_points(), 31);
    StudyOptions so = study_options(sc);
    so.speeds = grid;
    CHECK_FALSE(so.f_cut);
    const double band = excitation_band(grid, sc.analysis.harmonics);
    // The default and a cut-off a third of it, away from any mode's frequency.
    const CampbellDiagram wide = campbell_study(sc.system, so).diagram;
    CHECK(wide.band == band);
    sc.analysis.f_cut = band / 3.0;
    validate_settings(sc);
    so = study_options(sc);
    so.speeds = grid;
    REQUIRE(so.f_cut);
    const CampbellDiagram cut = campbell_study(sc.system, so).diagram;
    CHECK(cut.band == band / 3.0);
    const auto lowest = [](const Branch& b) {
        double f = std::numeric_limits<double>::infinity();
        for (const BranchPoint& p : b.points) f = std::min(f, std::abs(p.mode.lambda.imag()));
        return f;
    };
    const auto judged = [&](const CampbellDiagram& cd, double f_cut) {
        size_t n = 0;
        for (const auto* list : {&cd.branches, &cd.untracked})
            for (const Branch& b : *list) {
                INFO("judged branch " << b.id << ", lowest frequency " << lowest(b) << ", f_cut " << f_cut);
                CHECK(lowest(b) <= f_cut * (1 + 1e-9));
                ++n;
            }
        for (const Branch& b : cd.out_of_range) {
            INFO("out-of-range branch " << b.id << ", lowest frequency " << lowest(b) << ", f_cut " << f_cut);
            CHECK(lowest(b) > f_cut * (1 - 1e-9));
        }
        return n;
    };
    const size_t n_wide = judged(wide, band), n_cut = judged(cut, band / 3.0);
    CHECK(n_cut >= 2);
    CHECK(n_cut < n_wide);
    // The same through the option; an f_cut that is no frequency is refused by name.
    so.f_cut = 0.0;
    CHECK_THROWS_WITH(campbell_study(sc.system, so), Catch::Contains("f_cut") && Catch::Contains("> 0"));
    sc.analysis.f_cut = -1.0;
    CHECK_THROWS_WITH(validate_settings(sc), Catch::Contains("f_cut = -1"));
}

TEST_CASE("damped modes meet on the real axis and part there, or leave it: the continuation follows them through "
          "the exceptional points as a group, equal to the closed form",
          "[continuation][exceptional]") {
    // x and y each m = 1, c = 2, k(w) = k0 + s w^2 k2 with k2 = 0.01 and 0.012 (a stiffness
    // that changes with the speed squared): lambda = -1 +- sqrt(1 - k(w)). With k0 = 0.5 and
    // s = +1 two real eigenvalues per direction meet at -1 where k = 1 (w = 7.071 and 6.455
    // rad/s) and leave it as a complex pair; with k0 = 1.5 and s = -1 a complex pair comes
    // down to the real axis there and parts into two real eigenvalues. At standstill both
    // directions are the same: double eigenvalues.
    for (const auto& [k0, sign] : {std::pair{0.5, 1.0}, std::pair{1.5, -1.0}}) {
        GyroscopicSystem s;
        s.M = Eigen::MatrixXd(Eigen::MatrixXd::Identity(2, 2));
        s.K = Eigen::MatrixXd(k0 * Eigen::MatrixXd::Identity(2, 2));
        s.K2 = Eigen::MatrixXd((sign * Eigen::Vector2d(0.01, 0.012)).asDiagonal());
        s.damping.push_back({"c", Eigen::MatrixXd(2.0 * Eigen::MatrixXd::Identity(2, 2))});
        s.dofs.names = {"x", "y"};
        s.dofs.units = {"m", "m"};
        s.whirl_pairs = {{0, 1}};
        const std::vector<double> grid = SpeedRange{0.0, 10.0, 101}.points();
        ContinuationOptions o;
        o.band = 10.0;
        const SolverFactory cont = continuation_solver(std::make_shared<const GyroscopicSystem>(s), grid, o);
        const std::vector<QuadraticSpectrum> got = solve_speeds(cont, grid, 1);
        for (size_t k = 0; k < grid.size(); ++k) {
            const double w = grid[k];
            std::vector<std::complex<double>> exact;
            for (const double k2 : {0.01, 0.012}) {
                const double d = 1.0 - (k0 + sign * w * w * k2);
                if (d >= 0.0)
                    exact.push_back(-1.0 + std::sqrt(d)), exact.push_back(-1.0 - std::sqrt(d));
                else
                    exact.push_back({-1.0, std::sqrt(-d)});
            }
            INFO("k0 " << k0 << ", at " << w << " rad/s: " << got[k].method);
            REQUIRE(got[k].modes.size() == exact.size());
            for (const std::complex<double> e : exact) {
                // Each exact eigenvalue within the error bound of as many modes as it has (a double one twice).
                const auto near = std::count_if(got[k].modes.begin(), got[k].modes.end(), [&](const Mode& m) {
                    return std::abs(m.lambda - e) <= std::max(m.error_bound, 1e-12);
                });
                CHECK(near == std::count(exact.begin(), exact.end(), e));
            }
        }
        // Every speed but the first stepped: the groups at the two exceptional points
        // (and at the standstill doubles), no full solve but the anchor's.
        INFO("k0 " << k0);
        CHECK(cont.work().local_solves == 0);
        CHECK(cont.work().cluster_steps >= 2);
    }
}
