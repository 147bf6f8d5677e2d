// The fast path on rotors as engineers write them: a seeded subset of the
// random FE rotor family (apps/bench/rotor_family.hpp; the whole family, with timed
// costs, is gyrokit-bench-family). Each rotor on the default dense path: a few
// full solves (the solver's own count), no ambiguous step, every 1x crossing
// inside the range found in its bracket of an independent count on a grid of
// full solves, whatever the mode count K, and the least-damped mode among the
// shown branches.
#include "rotor_family.hpp"

#include <catch2/catch.hpp>

using namespace gyrokit;

TEST_CASE("rotor family: crossings, counts and the least-damped mode on seeded random FE rotors",
          "[continuation][family]") {
    // Seeds 1-8; 196: overdamped bearings (zeta 3.8), whose real eigenvalue at standstill
    // once counted as a "crossing" at 0 rad/s (it lies on every line there); 67 (zeta 2.5):
    // a near-double real pair at standstill that turns complex at once, and 99 (zeta 4):
    // real eigenvalues that meet, both once solved in full at every failed step, now
    // stepped as groups.
    for (const unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 196u, 67u, 99u}) {
        const family::RotorCase c = family::random_rotor(seed, false);
        INFO(c.description);
        // The cost is timed by the benchmark; here the solver's counts stand for it.
        const family::CaseResult r = family::run_case(c, std::numeric_limits<double>::infinity(), 401);
        INFO("dofs " << r.dofs << ", full solves " << r.work.full_solves << ", local " << r.work.local_solves
                     << ", steps " << r.work.steps << ", crossings " << r.crossings << " of " << r.expected);
        CHECK(r.solver == "dense");
        CHECK(r.work.full_solves <= 10);
        CHECK(r.work.steps >= static_cast<long>(c.speeds.size()) - 10);
        CHECK(r.ambiguous == 0);
        CHECK(r.expected > 0);
        CHECK(r.brackets);
        CHECK(r.least_shown);
        if (c.modes > 0) CHECK(r.shown == c.modes);
        if (seed == 67u || seed == 99u) CHECK(r.work.cluster_steps >= 1);
        if (seed == 67u) CHECK(r.work.local_solves == 0);
    }
}

TEST_CASE("rotor family on refined meshes: the default sparse window widened to f_cut finds every crossing",
          "[continuation][family]") {
    // Seed 1 meshed four times finer (212 DOFs, modes = 4: the sparse solver by default)
    // had one of its two 1x crossings missed by a window of the 4 asked for; seed 6
    // (228 DOFs, modes = 4) has four. A grid of 101 full solves counts them (their
    // brackets are wider than the benchmark's 401, the count the same).
    for (const unsigned seed : {1u, 6u}) {
        const family::RotorCase c = family::random_rotor(seed, true);
        INFO(c.description);
        const family::CaseResult r = family::run_case(c, std::numeric_limits<double>::infinity(), 101);
        INFO("dofs " << r.dofs << ", windows " << r.work.window_solves << ", steps " << r.work.steps << ", crossings "
                     << r.crossings << " of " << r.expected);
        CHECK(r.solver == "sparse");
        CHECK(r.work.full_solves == 0);
        CHECK(r.work.window_solves <= 20);
        CHECK(r.ambiguous == 0);
        CHECK(r.expected > 0);
        CHECK(r.brackets);
        CHECK(r.least_shown);
        CHECK(r.shown == c.modes);
    }
}
