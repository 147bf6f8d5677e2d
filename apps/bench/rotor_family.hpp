// Seeded random FE rotors as engineers write them, and the checks every one of
// them must pass on the default path: the family of the fast-path property test
// (tests/bench/test_rotor_family.cpp, a few of them) and of its benchmark
// (apps/bench/bench_family.cpp, hundreds). docs/benchmarks.md ("Rotor family")
// states the rules; docs/numerics.md the continuation they exercise.
// Header-only.
#pragma once

#include "bench_clock.hpp"

#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/materials.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace gyrokit::family {

struct RotorCase {
    unsigned seed = 0;
    bool refined = false;   // meshed four times finer (200-600 DOFs: the default sparse path above 400)
    FeRotor rotor;
    std::vector<double> speeds;     // rad/s, from 0
    int modes = kModesInRange;      // [analysis] modes: unset, 4, 6 or 8
    std::string description;
};

inline double uniform(std::mt19937& g, double a, double b) { return std::uniform_real_distribution<double>(a, b)(g); }
inline double log_uniform(std::mt19937& g, double a, double b) { return std::exp(uniform(g, std::log(a), std::log(b))); }
inline int integer(std::mt19937& g, int a, int b) { return std::uniform_int_distribution<int>(a, b)(g); }

// Rotor `seed` of the family: a steel shaft of 2-6 sections (journals, hubs, a
// span), 1-4 disks of steel on the inner sections, two bearings at the journals
// with stiffness 1e6-1e9 N/m, vertical stiffness 50-100 % of the horizontal, on
// one rotor in three cross-coupling kxy = -kyx up to 30 % of kxx, damping from a
// bearing damping ratio of 0.002 (light) to 5 (overdamped branches); speeds from 0
// to 1.5-4 times the lowest natural frequency at standstill in 101-151 steps;
// modes unset, 4, 6 or 8. `refined`: each element split in four.
inline RotorCase random_rotor(unsigned seed, bool refined) {
    std::mt19937 g(seed * 2654435761u + 12345u);
    RotorCase c;
    c.seed = seed;
    c.refined = refined;
    const Material steel = find_material("steel", {}, "rotor family");
    const int sections = integer(g, 2, 6);
    const double base = uniform(g, 0.04, 0.12);   // journal diameter, m
    std::vector<double> length(static_cast<size_t>(sections)), diameter(static_cast<size_t>(sections));
    std::vector<int> count(static_cast<size_t>(sections));
    for (int s = 0; s < sections; ++s) {
        // Journals at the ends of a shaft of three sections or more; at least ten
        // elements in all (below that a full solve costs microseconds, and a ratio to
        // it measures overheads).
        const bool journal = sections > 2 && (s == 0 || s == sections - 1);
        length[static_cast<size_t>(s)] = journal ? uniform(g, 0.05, 0.15) : uniform(g, 0.15, 0.6);
        diameter[static_cast<size_t>(s)] = journal ? base : base * uniform(g, 1.1, 1.8);
        count[static_cast<size_t>(s)] = journal ? 2 : integer(g, sections == 2 ? 5 : 3, 8);
    }
    const int split = refined ? 4 : 1;
    std::vector<double> node_z{0.0};
    for (int s = 0; s < sections; ++s)
        for (int e = 0; e < count[static_cast<size_t>(s)] * split; ++e) {
            FeShaftElement el;
            el.length = length[static_cast<size_t>(s)] / (count[static_cast<size_t>(s)] * split);
            el.outer_diameter = diameter[static_cast<size_t>(s)];
            el.youngs_modulus = steel.youngs_modulus;
            el.poisson_ratio = steel.poisson_ratio;
            el.density = steel.density;
            c.rotor.elements.push_back(el);
            node_z.push_back(node_z.back() + el.length);
        }
    const int nodes = static_cast<int>(node_z.size());
    // The span between the journals (between the bearings on a shaft of two sections).
    const int first_inner = sections > 2 ? count.front() * split : split;
    const int last_inner = sections > 2 ? nodes - 1 - count.back() * split : nodes - 1 - split;
    double shaft_mass = 0.0;
    for (const FeShaftElement& e : c.rotor.elements) shaft_mass += fe_element_mass(e);
    // Disks on distinct inner nodes.
    const int disks = integer(g, 1, 4);
    std::vector<int> used;
    double disk_mass = 0.0;
    for (int d = 0; d < disks; ++d) {
        // Where along the inner sections (a fraction: a rotor and its refinement share it).
        const int node = first_inner + static_cast<int>(std::lround(uniform(g, 0.1, 0.9) * (last_inner - first_inner)));
        const double r_in = 0.5 * base, r_out = r_in * uniform(g, 2.0, 5.0), width = uniform(g, 0.02, 0.08);
        if (std::find(used.begin(), used.end(), node) != used.end()) continue;
        used.push_back(node);
        FeDisk disk;
        disk.node = node;
        disk.mass = steel.density * kPi * (r_out * r_out - r_in * r_in) * width;
        disk.polar_inertia = 0.5 * disk.mass * (r_out * r_out + r_in * r_in);
        disk.diametral_inertia = 0.25 * disk.mass * (r_out * r_out + r_in * r_in) + disk.mass * width * width / 12.0;
        c.rotor.disks.push_back(disk);
        disk_mass += disk.mass;
    }
    // Bearings at the middle of the journals.
    const double k = log_uniform(g, 1e6, 1e9);
    const double anisotropy = uniform(g, 0.5, 1.0);
    const double cross = integer(g, 0, 2) == 0 ? uniform(g, -0.3, 0.3) * k : 0.0;
    const double zeta_b = log_uniform(g, 0.002, 5.0);
    const double c_b = 2.0 * zeta_b * std::sqrt(k * 0.5 * (shaft_mass + disk_mass));
    for (const int node : {split, nodes - 1 - split}) {
        FeBearing b;
        b.node = node;
        b.kxx = k;
        b.kyy = anisotropy * k;
        b.kxy = cross;
        b.kyx = -cross;
        b.cxx = c_b;
        b.cyy = anisotropy * c_b;
        c.rotor.bearings.push_back(b);
    }
    // Speeds from the lowest natural frequency at standstill (of the coarse mesh,
    // so a rotor and its refinement share their range).
    if (refined) {
        const RotorCase coarse = random_rotor(seed, false);
        c.speeds = coarse.speeds;
        c.modes = coarse.modes;
    } else {
        const QuadraticSpectrum s = solve_at_speed(make_system(c.rotor), 0.0);
        double lowest = std::numeric_limits<double>::infinity();
        for (const Mode& m : s.modes)
            if (m.frequency() > 0.0) lowest = std::min(lowest, std::abs(m.lambda));
        const double top = uniform(g, 1.5, 4.0) * lowest;
        const int n_speeds = integer(g, 101, 151);
        for (int i = 0; i < n_speeds; ++i) c.speeds.push_back(top * i / (n_speeds - 1));
        const int pick = integer(g, 0, 3);
        c.modes = pick == 0 ? kModesInRange : 2 + 2 * pick;
    }
    c.description = fmt::format("seed {}{}: {} sections, {} disks, k {:.3g} N/m (kyy/kxx {:.2f}, kxy {:.3g}), bearing "
                                "zeta {:.3g}, {} speeds to {:.6g} rad/s, modes {}",
                                seed, refined ? " (refined)" : "", sections, c.rotor.disks.size(), k, anisotropy, cross,
                                zeta_b, c.speeds.size(), c.speeds.back(),
                                c.modes == kModesInRange ? std::string("unset") : std::to_string(c.modes));
    return c;
}

// The 1x crossings of a model over `speeds`, counted independently of the
// tracking: on a grid of `points` speeds, N(w) = the number of eigenvalues with
// Im lambda > w (the eigenvalues alone, every mode, at every grid speed) changes
// only where a branch crosses the line Im lambda = w; each change of N between
// two grid speeds is a crossing in that bracket.
struct Bracket {
    double from = 0.0, to = 0.0;
    int crossings = 0;
};
inline std::vector<Bracket> crossing_brackets(const GyroscopicSystem& sys, double top, int points = 401) {
    std::vector<Bracket> out;
    int before = -1;
    double w_before = 0.0;
    for (int i = 0; i < points; ++i) {
        const double w = top * i / (points - 1);
        const EigenvalueSet e = quadratic_eigenvalues(sys.at_speed(w));
        int n = 0;
        for (const auto& l : e.values) n += l.imag() > w && l.imag() > e.real_tol;
        if (before >= 0 && n != before) out.push_back({w_before, w, std::abs(n - before)});
        before = n;
        w_before = w;
    }
    return out;
}

// What one rotor did on the default path.
struct CaseResult {
    int dofs = 0;
    std::string solver;
    double campbell_seconds = 0.0;   // the Campbell diagram (tracking, one worker)
    double full_seconds = 0.0;       // median of three full dense solves at the middle speed
    double cost = 0.0;               // campbell_seconds / full_seconds
    SolverWork work;
    int shown = 0;                   // branches the diagram shows
    int ambiguous = 0;
    int crossings = 0;               // found by the critical speeds (every 1x crossing, critical or not)
    int expected = 0;                // counted on the grid
    bool brackets = true;            // each found speed in the grid bracket of a crossing, the numbers equal
    bool least_shown = true;         // the least-damped mode is one of the shown branches
    std::vector<std::string> failures;
    bool ok() const { return failures.empty(); }
};

using bench::seconds_since;

// Runs the default Campbell study and the critical speeds of case `c` and checks
// them: cost at most `max_cost`, no ambiguous step, every 1x crossing found in
// its bracket, the least-damped mode among the shown branches.
inline CaseResult run_case(const RotorCase& c, double max_cost = 10.0, int grid_points = 401) {
    CaseResult r;
    const GyroscopicSystem sys = make_system(c.rotor);
    r.dofs = sys.size();
    StudyOptions opt;
    opt.solver.modes = c.modes;
    opt.speeds = c.speeds;
    opt.harmonics = {1};
    opt.workers = 1;
    opt.amplification_factors = false;
    // The cost's unit: one full dense solve of every mode at the middle speed.
    std::vector<double> full;
    for (int k = 0; k < 3; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        (void)solve_at_speed(sys, c.speeds[c.speeds.size() / 2]);
        full.push_back(seconds_since(t0));
    }
    std::sort(full.begin(), full.end());
    r.full_seconds = full[1];
    const auto t0 = std::chrono::steady_clock::now();
    CampbellStudy st = campbell_study(sys, opt);
    r.campbell_seconds = seconds_since(t0);
    r.cost = r.campbell_seconds / r.full_seconds;
    r.solver = to_string(st.plan.kind);
    r.shown = static_cast<int>(st.diagram.branches.size());
    r.ambiguous = st.diagram.ambiguous_steps;
    const std::vector<CriticalSpeed> cs = critical_speeds_of(sys, st, opt);
    r.work = st.solver.work();
    r.crossings = static_cast<int>(cs.size());
    const std::vector<Bracket> brackets = crossing_brackets(sys, c.speeds.back(), grid_points);
    for (const Bracket& b : brackets) r.expected += b.crossings;
    // Each bracket holds as many found speeds as N changes by there (a speed on a
    // bracket's end belongs to it).
    for (const Bracket& b : brackets) {
        int found = 0;
        for (const CriticalSpeed& x : cs) found += x.speed >= b.from && x.speed <= b.to;
        if (found != b.crossings) r.brackets = false;
    }
    if (r.expected != r.crossings) r.brackets = false;
    if (const auto least = least_damped(st.diagram)) r.least_shown = least->branch >= 1 && least->branch <= r.shown;
    if (!(r.cost <= max_cost)) r.failures.push_back(fmt::format("cost {:.1f} > {}", r.cost, max_cost));
    if (r.ambiguous > 0) r.failures.push_back(fmt::format("{} ambiguous steps", r.ambiguous));
    if (!r.brackets)
        r.failures.push_back(fmt::format("{} crossings found, {} on the grid of {} full solves", r.crossings,
                                         r.expected, grid_points));
    if (!r.least_shown) r.failures.push_back("least-damped mode not among the shown branches");
    return r;
}

}  // namespace gyrokit::family
