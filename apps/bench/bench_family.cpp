// gyrokit-bench-family: the default Campbell path on a seeded family of random FE
// rotors as engineers write them (apps/bench/rotor_family.hpp), coarse meshes and the
// same rotors meshed four times finer: per rotor the cost (Campbell time over
// one full dense solve's, measured in the same run), the solver's own counts,
// ambiguous steps, the 1x crossings found against an independent count on a grid
// of full solves, and whether the least-damped mode is one the diagram shows;
// then the median and worst cost and the failures. docs/benchmarks.md.
// Exit status: 0 every rotor passes, 1 some fail or an error, 2 bad input.
#include "bench_common.hpp"
#include "rotor_family.hpp"

#include <gyrokit/io/table.hpp>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>

using namespace gyrokit;

int main(int argc, char** argv) {
    CLI::App app{"gyrokit-bench-family: the default Campbell path on seeded random FE rotors"};
    unsigned first = 1;
    int count = 100;
    int grid = 401;
    double max_cost = 10.0;
    bool coarse_only = false, refined_only = false, failures_only = false;
    app.add_option("--first", first, "first seed")->capture_default_str();
    app.add_option("--count", count, "rotors (each coarse and refined)")->capture_default_str()->check(CLI::Range(1, 100000));
    app.add_option("--grid", grid, "speeds of the independent crossing count")->capture_default_str()->check(CLI::Range(11, 100001));
    app.add_option("--max-cost", max_cost, "the cost a rotor may take")->capture_default_str();
    app.add_flag("--coarse", coarse_only, "coarse meshes only");
    app.add_flag("--refined", refined_only, "refined meshes only");
    app.add_flag("--failures", failures_only, "print only the rotors that fail");
    CLI11_PARSE(app, argc, argv);
    bool all_ok = true;
    const int status = bench::guarded_main([&] {
        Table t({"seed", "mesh", "dofs", "solver", "modes", "cost", "full", "checks", "steps", "split", "groups", "joined",
                 "local", "windows", "followed", "shown", "crossings", "expected", "result"});
        std::vector<double> costs[2];
        int failed[2] = {0, 0}, runs[2] = {0, 0};
        for (unsigned seed = first; seed < first + static_cast<unsigned>(count); ++seed)
            for (const bool refined : {false, true}) {
                if ((refined && coarse_only) || (!refined && refined_only)) continue;
                const family::RotorCase c = family::random_rotor(seed, refined);
                const family::CaseResult r = family::run_case(c, max_cost, grid);
                costs[refined].push_back(r.cost);
                ++runs[refined];
                std::string result = "ok";
                if (!r.ok()) {
                    ++failed[refined];
                    all_ok = false;
                    result.clear();
                    for (const std::string& f : r.failures) result += (result.empty() ? "" : "; ") + f;
                    std::cerr << c.description << ": " << result << "\n";
                }
                if (failures_only && r.ok()) continue;
                t.add_row({static_cast<long long>(seed), std::string(refined ? "refined" : "coarse"),
                           static_cast<long long>(r.dofs), r.solver,
                           c.modes == kModesInRange ? std::string("unset") : std::to_string(c.modes),
                           fmt::format("{:.1f}", r.cost), static_cast<long long>(r.work.full_solves),
                           static_cast<long long>(r.work.eigenvalue_checks), static_cast<long long>(r.work.steps),
                           static_cast<long long>(r.work.split_steps), static_cast<long long>(r.work.cluster_steps),
                           static_cast<long long>(r.work.joined), static_cast<long long>(r.work.local_solves),
                           static_cast<long long>(r.work.window_solves), static_cast<long long>(r.work.followed),
                           static_cast<long long>(r.shown), static_cast<long long>(r.crossings),
                           static_cast<long long>(r.expected), result});
            }
        write_table(std::cout, t, TableFormat::Text);
        std::cout << "\n";
        for (const bool refined : {false, true}) {
            std::vector<double>& v = costs[refined];
            if (v.empty()) continue;
            std::sort(v.begin(), v.end());
            const double median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
            std::cout << fmt::format("{} meshes: {} rotors, cost median {:.1f}, worst {:.1f}; {} fail\n",
                                     refined ? "refined" : "coarse", runs[refined], median, v.back(), failed[refined]);
        }
    });
    return status != 0 ? status : (all_ok ? 0 : 1);
}
