// Helpers shared by the benchmark programs (apps/bench/bench_*.cpp and the files of
// apps/bench/bench_tradeoffs/): speed grids, wall-time measurement, eigenvalue
// matching, and the cases and runs of the liquid-filled rotor, auto-balancer
// and Sommerfeld benchmarks, so that every program measures them the same way.
// Header-only.
#pragma once

#include <gyrokit/analysis/fluid_critical_speeds.hpp>
#include <gyrokit/scene/balancer_scene.hpp>
#include <gyrokit/balancing/runup.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/balancing/synchronous_states.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#ifndef GYROKIT_DATA_DIR
#define GYROKIT_DATA_DIR "data"
#endif

namespace gyrokit::bench {

// Runs a benchmark's body with the exit status of the benchmark programs: 0
// on success, 2 with one line on stderr for bad input, 1 for anything else.
template <class F>
int guarded_main(F&& body) {
    try {
        body();
    } catch (const InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

// `count` equally spaced values from `from` to `to` (just `from` for count 1).
inline std::vector<double> linspace(double from, double to, int count) {
    if (count == 1) return {from};
    std::vector<double> v(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) v[static_cast<size_t>(i)] = from + (to - from) * i / (count - 1);
    return v;
}

// Wall time of one call of f (std::chrono::steady_clock): the median of calls
// repeated until at least `min_time` seconds have passed and `min_repeats`
// calls were made. A call that alone takes longer than `single` seconds is
// not repeated (its one time is the result).
template <class F>
double median_seconds(F&& f, double min_time, int min_repeats = 3, double single = 5.0) {
    using clock = std::chrono::steady_clock;
    std::vector<double> times;
    double total = 0.0;
    while (total < min_time || static_cast<int>(times.size()) < min_repeats) {
        const auto t0 = clock::now();
        f();
        times.push_back(std::chrono::duration<double>(clock::now() - t0).count());
        total += times.back();
        if (times.size() == 1 && times.front() > single) break;
    }
    std::sort(times.begin(), times.end());
    const size_t m = times.size() / 2;
    return times.size() % 2 ? times[m] : 0.5 * (times[m - 1] + times[m]);
}

// Largest |lambda - nearest lambda_ref| / |lambda_ref| between two spectra,
// matched both ways so that an eigenvalue missing on either side shows up as
// well (infinite if one side is empty and the other not).
inline double max_rel_diff(const QuadraticSpectrum& a, const QuadraticSpectrum& ref) {
    // Each eigenvalue of `from` against its nearest in `to`; sizes are taken from the reference side.
    const auto one_way = [](const QuadraticSpectrum& from, const QuadraticSpectrum& to, bool from_is_ref,
                            double scale) {
        double worst = 0.0;
        for (const auto& m : from.modes) {
            double best = std::numeric_limits<double>::infinity();
            std::complex<double> nearest;
            for (const auto& t : to.modes)
                if (std::abs(m.lambda - t.lambda) < best) best = std::abs(m.lambda - t.lambda), nearest = t.lambda;
            if (std::isinf(best)) return best;
            const double size = std::abs(from_is_ref ? m.lambda : nearest);
            worst = std::max(worst, best / (size > 0.0 ? size : scale));
        }
        return worst;
    };
    return std::max(one_way(a, ref, false, ref.scale), one_way(ref, a, true, ref.scale));
}

// Largest |w_i / w_ref_i - 1| of two increasing lists of speeds; 1 when a
// speed appears or vanishes (the lists differ in length).
inline double max_rel_deviation(const std::vector<double>& w, const std::vector<double>& w_ref) {
    if (w.size() != w_ref.size()) return 1.0;
    double err = 0.0;
    for (size_t i = 0; i < w.size(); ++i) err = std::max(err, std::fabs(w[i] / w_ref[i] - 1.0));
    return err;
}

// --- Liquid-filled rotor (docs/fluid_rotor.md, Tabelle 2) ---

// Case N (1..4) of Tabelle 2.
inline FluidRotorParameters fluid_table_case(int N) {
    const double a[4] = {0.5, 1.0, 1.6, 2.0}, m0[4] = {400, 600, 600, 800}, I0[4] = {133, 200, 200, 267},
                 J0[4] = {75, 160, 160, 450};
    FluidRotorParameters p;
    p.R = 0.6; p.R0 = 0.4; p.a = a[N - 1]; p.l = 2.5; p.rho = 1000; p.nu = 1e-6;
    p.c1 = 6e8; p.c2 = 2e8; p.c11 = 3e6; p.m0 = m0[N - 1]; p.I0 = I0[N - 1]; p.J0 = J0[N - 1];
    return p;
}

// One model build plus its undamped critical speeds: what the fluid benchmarks time.
inline std::vector<double> fluid_undamped_speeds(const FluidRotorParameters& p) {
    const FluidRotor f = build_fluid_rotor(p);
    return critical_speeds_quadratic(f, equivalent_inertia(f));
}

// The reference of the fluid benchmarks: 400 sloshing modes, 20000 J* terms.
inline FluidRotorParameters fluid_reference_case(int N) {
    FluidRotorParameters p = fluid_table_case(N);
    p.modes = 400;
    p.jstar_terms = 20000;
    return p;
}

// --- Auto-balancer and Sommerfeld scenes ---

inline BalancerScene load_data_balancer_scene(const std::string& file) {
    return load_balancer_scene(std::string(GYROKIT_DATA_DIR) + "/" + file);
}

// The full equations of motion (18), or the averaged slow-phase equations, of
// the scene's simulation with ODE method `m` and abs = rel tolerance `tol`.
inline SimulationResult run_balancer(const BalancerScene& sc, bool averaged, OdeMethod m, double tol) {
    SimulationSettings s = sc.simulation;
    s.ode.method = m;
    s.ode.abs_tol = s.ode.rel_tol = tol;
    return averaged ? simulate_averaged(sc.params, s) : simulate(sc.params, s);
}

// The reference run of the balancer benchmarks: full equations, rk8pd, tolerance 1e-13.
inline SimulationResult balancer_reference(const BalancerScene& sc) {
    return run_balancer(sc, false, OdeMethod::Rk8pd, 1e-13);
}

// Largest distance on the circle between the final phases of two runs, rad.
inline double final_phase_error(const SimulationResult& r, const SimulationResult& ref) {
    double err = 0.0;
    for (size_t i = 0; i < r.final_alpha.size() && i < ref.final_alpha.size(); ++i)
        err = std::max(err, phase_distance(r.final_alpha[i], ref.final_alpha[i]));
    return err;
}

// The reference run-up of the Sommerfeld benchmarks: the scene's run-up without
// the fall, 20 000 output samples, rk8pd with tolerance 1e-12.
inline RunupSettings sommerfeld_reference_settings(const BalancerScene& sc) {
    RunupSettings ref = sc.runup;
    ref.fall = 0.0;
    ref.history_points = 20000;
    ref.ode.method = OdeMethod::Rk8pd;
    ref.ode.abs_tol = ref.ode.rel_tol = 1e-12;
    return ref;
}

}  // namespace gyrokit::bench
