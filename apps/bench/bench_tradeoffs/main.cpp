// gyrokit-bench-tradeoffs: the speed-accuracy trade across the toolkit in one
// run. Every row is one setting of one knob (eigensolver, speed grid, Campbell
// step, mesh, truncation, ODE tolerance, averaged equations) with its time per
// call and its largest error against a high-accuracy reference; a second table
// gives the time per speed point of the dense and the sparse eigensolver
// against model size, with the fitted growth exponents (docs/benchmarks.md).
// Exit status: 0 success, 2 bad input, 1 anything else.
//
// This file: the options, the choice of areas and the tables. The rows of each
// area: eigen_rows.cpp (eig, mesh, size), speed_rows.cpp (critical, campbell,
// fluid), balancer_rows.cpp (balancer, averaged); the models they are measured
// on: models.cpp; the long-double reference eigenvalues: reference.cpp.
#include "tradeoffs.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/table.hpp>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fmt/format.h>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace gyrokit;
using namespace gyrokit::bench;
using namespace tradeoffs;

namespace {

const std::vector<std::string> kAreas{"eig", "critical", "campbell", "mesh", "fluid", "balancer", "averaged", "size"};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Speed-accuracy trade across gyrokit: time per call and error against a reference for every "
                 "knob, and time per speed point against model size"};
    Settings s;
    std::string format = "table", only, table;
    app.add_flag("--quick", s.quick, "small sizes and few settings (a smoke run)");
    app.add_option("--only", only, "run only these areas (comma-separated): eig, critical, campbell, mesh, fluid, "
                                   "balancer, averaged, size");
    app.add_option("--min-time", s.min_time, "minimum measuring time per row, s (median of the calls)")
        ->check(CLI::Range(0.0, 3600.0));
    app.add_option("--format", format, "output format: table, csv or json")->capture_default_str();
    app.add_option("--table", table, "only this table: tradeoffs, size, growth (CSV holds the first unless one is "
                                     "named)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "error: " << e.what() << " (see --help)\n";
        return 2;
    }
    if (s.quick) {
        s.min_repeats = 1;
        if (app.count("--min-time") == 0) s.min_time = 0.02;
    }

    return bench::guarded_main([&] {
        const TableFormat fmt_out = parse_table_format(format);
        std::set<std::string> areas(kAreas.begin(), kAreas.end());
        if (!only.empty()) {
            areas.clear();
            std::stringstream ss(only);
            for (std::string a; std::getline(ss, a, ',');) {
                if (std::find(kAreas.begin(), kAreas.end(), a) == kAreas.end())
                    throw InputError(fmt::format("--only {}: unknown area '{}'; allowed: eig, critical, campbell, "
                                                 "mesh, fluid, balancer, averaged, size",
                                                 only, a));
                areas.insert(a);
            }
        }
        Table trade({"area", "model", "knob", "setting", "seconds", "error", "error_of", "reference", "note"});
        trade.key = "tradeoffs";
        trade.title = "Speed-accuracy trade: seconds per call (median), largest error against the reference";
        if (areas.count("eig")) eig_rows(trade, s);
        if (areas.count("critical")) critical_rows(trade, s);
        if (areas.count("campbell")) campbell_rows(trade, s);
        if (areas.count("mesh")) mesh_rows(trade, s);
        if (areas.count("fluid")) fluid_rows(trade, s);
        if (areas.count("balancer")) balancer_rows(trade, s);
        if (areas.count("averaged")) averaged_rows(trade, s);
        std::vector<Table> out;
        if (trade.rows() > 0) out.push_back(trade);
        if (areas.count("size")) {
            Table size({"path", "n", "elements", "seconds_per_point", "modes", "max_backward_error", "note"});
            size.key = "size";
            size.title = "Time per speed point against model size (FE rotor, 300 rad/s)";
            Table fit({"path", "sizes", "growth_exponent"});
            fit.key = "growth";
            fit.title = "Growth exponent: slope of log(seconds) against log(n)";
            size_rows(size, fit, s);
            out.push_back(size);
            out.push_back(fit);
        }
        std::vector<std::string> left_out;
        write_result(std::cout, out, fmt_out, table, "--table", left_out);
        for (const auto& k : left_out) std::cerr << "note: CSV holds one table; --table " << k << " gives another\n";
    });
}
