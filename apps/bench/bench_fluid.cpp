// Benchmark of the liquid-filled rotor: sloshing modes and J* series length
// against the critical-speed error and the time of one model build plus the
// undamped critical speeds. Prints a table (docs/benchmarks.md).
#include "bench_common.hpp"
#include <gyrokit/io/table.hpp>

#include <iostream>
#include <string>

using namespace gyrokit;
using namespace gyrokit::bench;

int main(int argc, char** argv) {
    const TableFormat fmt = argc > 1 ? parse_table_format(argv[1]) : TableFormat::Text;
    Table t({"case", "modes", "jstar_terms", "max_rel_error", "seconds"});
    t.title = "fluid rotor: critical-speed error and time against truncation (reference: 400 modes, 20000 J* terms)";
    for (int N : {2, 4}) {
        const std::vector<double> w_ref = fluid_undamped_speeds(fluid_reference_case(N));
        for (int modes : {1, 3, 5, 10, 30, 100})
            for (int nj : {3, 10, 30, 100, 1000}) {
                FluidRotorParameters p = fluid_table_case(N);
                p.modes = modes;
                p.jstar_terms = nj;
                std::vector<double> w;
                const double seconds = median_seconds([&] { w = fluid_undamped_speeds(p); }, 0.05);
                t.add_row({std::string("N") + std::to_string(N), static_cast<long long>(modes),
                           static_cast<long long>(nj), max_rel_deviation(w, w_ref), seconds});
            }
    }
    write_table(std::cout, t, fmt);
    return 0;
}
