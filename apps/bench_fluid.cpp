// Benchmark of the liquid-filled rotor: sloshing modes and J* series length
// against the critical-speed error and the time of one model build plus the
// undamped critical speeds. Prints a table (docs/benchmarks.md).
#include "analysis/fluid_critical_speeds.hpp"
#include "io/table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

using namespace gyrokit;

namespace {

FluidRotorParameters table_case(int N) {
    const double a[4] = {0.5, 1.0, 1.6, 2.0}, m0[4] = {400, 600, 600, 800}, I0[4] = {133, 200, 200, 267},
                 J0[4] = {75, 160, 160, 450};
    FluidRotorParameters p;
    p.R = 0.6; p.R0 = 0.4; p.a = a[N - 1]; p.l = 2.5; p.rho = 1000; p.nu = 1e-6;
    p.c1 = 6e8; p.c2 = 2e8; p.c11 = 3e6; p.m0 = m0[N - 1]; p.I0 = I0[N - 1]; p.J0 = J0[N - 1];
    return p;
}

std::vector<double> speeds(const FluidRotorParameters& p) {
    const FluidRotor f = build_fluid_rotor(p);
    return critical_speeds_quadratic(f, equivalent_inertia(f));
}

}  // namespace

int main(int argc, char** argv) {
    const TableFormat fmt = argc > 1 ? parse_table_format(argv[1]) : TableFormat::Text;
    Table t({"case", "modes", "jstar_terms", "max_rel_error", "seconds"});
    t.title = "fluid rotor: critical-speed error and time against truncation (reference: 400 modes, 20000 J* terms)";
    for (int N : {2, 4}) {
        FluidRotorParameters ref = table_case(N);
        ref.modes = 400;
        ref.jstar_terms = 20000;
        const std::vector<double> w_ref = speeds(ref);
        for (int modes : {1, 3, 5, 10, 30, 100})
            for (int nj : {3, 10, 30, 100, 1000}) {
                FluidRotorParameters p = table_case(N);
                p.modes = modes;
                p.jstar_terms = nj;
                std::vector<double> w;
                int reps = 0;
                const auto t0 = std::chrono::steady_clock::now();
                double el = 0;
                do {
                    w = speeds(p);
                    ++reps;
                    el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                } while (el < 0.05);
                double err = 0;
                if (w.size() != w_ref.size()) err = 1.0;   // a critical speed appears or vanishes
                else
                    for (size_t i = 0; i < w.size(); ++i) err = std::max(err, std::fabs(w[i] / w_ref[i] - 1));
                t.add_row({std::string("N") + std::to_string(N), static_cast<long long>(modes),
                           static_cast<long long>(nj), err, el / reps});
            }
    }
    write_table(std::cout, t, fmt);
    return 0;
}
