// gyrokit-bench-reynolds: what the finite-length fluid-film bearing costs and
// buys. For the finite-difference Reynolds solution on grids of N x A intervals
// (circumferential x axial) and for the short-bearing (Ocvirk) closed form: the
// time of one evaluation at a given load and speed (equilibrium and the 8
// coefficients, as an analysis calls it) and its error against the finest grid,
// at a few eccentricities and L/D (docs/benchmarks.md).
// Exit status: 0 success, 2 bad input, 1 anything else.
#include "bench_common.hpp"
#include <gyrokit/core/constants.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/models/journal_bearing.hpp>
#include <gyrokit/models/reynolds_bearing.hpp>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

using namespace gyrokit;
using namespace gyrokit::bench;

namespace {

struct Grid {
    int n, a;
};

// Errors of one evaluation against the reference state at the same load and speed:
// e relative, attitude in degrees, K and C relative to their largest entry.
struct Errors {
    double e = 0, attitude_deg = 0, K = 0, C = 0;
    double worst() const { return std::max({e, attitude_deg * kPi / 180, K, C}); }   // attitude in rad
};

Errors errors(const JournalBearingState& s, const JournalBearingState& ref) {
    const BearingCoefficients &c = s.coefficients, &r = ref.coefficients;
    return {std::fabs(s.eccentricity / ref.eccentricity - 1),
            std::fabs(s.attitude_angle - ref.attitude_angle) * 180 / kPi,
            (c.K - r.K).cwiseAbs().maxCoeff() / r.K.cwiseAbs().maxCoeff(),
            (c.C - r.C).cwiseAbs().maxCoeff() / r.C.cwiseAbs().maxCoeff()};
}

// Per solution (a grid or the closed form): the spread of times and the largest errors over the cases.
struct Summary {
    explicit Summary(std::string name) : solution(std::move(name)) {}
    std::string solution;
    double t_min = 1e300, t_max = 0;
    Errors worst;
    void add(double t, const Errors& x) {
        t_min = std::min(t_min, t), t_max = std::max(t_max, t);
        worst = {std::max(worst.e, x.e), std::max(worst.attitude_deg, x.attitude_deg), std::max(worst.K, x.K),
                 std::max(worst.C, x.C)};
    }
};

std::string grid_name(const Grid& g) { return fmt::format("{} x {}", g.n, g.a); }

// The command line.
struct Options {
    bool quick = false;
    int repeats = 5;
    double min_time = 0.05;
    std::string format = "table", table;
};

// Reads the command line into `o`. Returns the exit status when the program
// ends here: 0 after --help, 2 for bad input like the other benchmark programs.
std::optional<int> parse_options(int argc, char** argv, Options& o) {
    CLI::App app{"Finite-length fluid-film bearing: Reynolds grid vs time per evaluation and error against the "
                 "finest grid, beside the short-bearing closed form"};
    app.add_flag("--quick", o.quick, "reference 480 x 64, grids up to 240 x 32, one call per row (a smoke run)");
    app.add_option("--repeats", o.repeats, "calls per row at least (time: their median)")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--min-time", o.min_time, "minimum measuring time per row, s")
        ->check(CLI::Range(0.0, 3600.0))
        ->capture_default_str();
    app.add_option("--format", o.format, "output format: table, csv or json")->capture_default_str();
    app.add_option("--table", o.table, "only this table: cases, summary (CSV holds the first unless one is named)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {   // bad input: exit status 2 like the other benchmark programs
        std::cerr << "error: " << e.what() << " (see --help)\n";
        return 2;
    }
    if (o.quick) {
        if (app.count("--repeats") == 0) o.repeats = 1;
        if (app.count("--min-time") == 0) o.min_time = 0.0;
    }
    return std::nullopt;
}

// The grids of a run: those compared, the reference (finest) and the library's default.
struct Grids {
    std::vector<Grid> compared;
    Grid finest;
    Grid dflt;
};

Grids run_grids(bool quick) {
    // Both steps halve from row to row, so the error should fall 4 times per row (second order).
    std::vector<Grid> grids{{60, 8}, {120, 16}, {240, 32}, {480, 64}, {960, 128}};
    Grid finest{1920, 256};
    if (quick) grids.resize(3), finest = {480, 64};
    const Grid dflt{JournalBearing{}.grid_circumferential, JournalBearing{}.grid_axial};
    return {grids, finest, dflt};
}

// What a run measures: the table of cases, and per solution its times and errors
// (the compared grids in order, then the short bearing) and those of the reference.
struct Measurements {
    Table cases;
    std::vector<Summary> sums;
    Summary finest_sum;
};

Measurements start_measurements(const Grids& g) {
    Table cases(
        {"L/D", "e", "solution", "seconds", "e_error", "attitude_error_deg", "K_error", "C_error", "note"});
    cases.key = "cases";
    cases.title = fmt::format("Reynolds bearing: seconds per evaluation (median), error against {} at the "
                              "same load and speed",
                              grid_name(g.finest));
    std::vector<Summary> sums;
    for (const Grid& grid : g.compared) sums.emplace_back(grid_name(grid));
    sums.emplace_back("short (Ocvirk)");
    return {cases, sums, Summary(grid_name(g.finest) + " (reference)")};
}

// One case, L/D `ld` and eccentricity `e` on the finest grid: every grid and the
// short bearing timed and compared with the finest grid at the same load and speed.
void measure_case(double ld, double e, const Grids& g, const Options& o, Measurements& m) {
    const std::vector<Grid>& grids = g.compared;
    JournalBearing b;
    b.diameter = 0.1, b.length = 0.1 * ld, b.clearance = 1e-4, b.viscosity = 0.03, b.load = 2000;
    b.solution = FilmSolution::finite_difference;
    b.grid_circumferential = g.finest.n, b.grid_axial = g.finest.a;
    // The speed at which the finest grid has eccentricity e: every row is evaluated there.
    const double w = reynolds_bearing_speed_at(b, e);
    JournalBearingState ref;
    const double t_ref = median_seconds([&] { ref = reynolds_bearing(b, w); }, o.min_time, o.repeats);
    m.finest_sum.add(t_ref, {});
    const auto row = [&](Summary& sum, const std::string& name, const std::string& note, auto&& eval) {
        JournalBearingState s;
        const double t = median_seconds([&] { s = eval(); }, o.min_time, o.repeats);
        const Errors x = errors(s, ref);
        sum.add(t, x);
        m.cases.add_row({ld, e, name, t, x.e, x.attitude_deg, x.K, x.C, note});
    };
    for (size_t i = 0; i < grids.size(); ++i) {
        JournalBearing bg = b;
        bg.grid_circumferential = grids[i].n, bg.grid_axial = grids[i].a;
        const bool is_default = grids[i].n == g.dflt.n && grids[i].a == g.dflt.a;
        row(m.sums[i], grid_name(grids[i]), is_default ? "default" : "", [&] { return reynolds_bearing(bg, w); });
    }
    m.cases.add_row({ld, e, grid_name(g.finest), t_ref, 0.0, 0.0, 0.0, 0.0, std::string("reference")});
    JournalBearing bs = b;
    bs.solution = FilmSolution::short_bearing;
    row(m.sums.back(), "short (Ocvirk)", fmt::format("closed form, e = {:.3f}", short_bearing(bs, w).eccentricity),
        [&] { return short_bearing(bs, w); });
}

// The order between successive grids, from the largest of the four errors. Measured against
// the reference, a pure h^2 error drops 4 (1 - 4^-(k+1)) / (1 - 4^-k) times for a grid k
// halvings coarser than the reference: the last two rows read 2.07 and 2.32, not 2.
Table summary_table(const Grids& g, const Measurements& m) {
    const std::vector<Grid>& grids = g.compared;
    const std::vector<Summary>& sums = m.sums;
    Table summary({"solution", "seconds_min", "seconds_max", "e_error", "attitude_error_deg", "K_error", "C_error",
                   "order"});
    summary.key = "summary";
    summary.title = fmt::format("Largest error over L/D = 0.25, 0.5, 1 and e = 0.2, 0.5, 0.8 against {}; "
                                "order = log2 of the drop of the largest error from the grid above",
                                grid_name(g.finest));
    for (size_t i = 0; i < sums.size(); ++i) {
        const Summary& s = sums[i];
        const bool grid_row = i < grids.size();
        const Cell order = grid_row && i > 0 ? Cell(std::log2(sums[i - 1].worst.worst() / s.worst.worst()))
                                             : Cell(std::string("-"));
        const std::string name = grid_row && grids[i].n == g.dflt.n && grids[i].a == g.dflt.a
                                     ? s.solution + " (default)"
                                     : s.solution;
        summary.add_row({name, s.t_min, s.t_max, s.worst.e, s.worst.attitude_deg, s.worst.K, s.worst.C, order});
        if (i + 1 == grids.size()) {   // the reference's cost, after the finest compared grid
            const Cell none = std::string("-");
            const Summary& f = m.finest_sum;
            summary.add_row({f.solution, f.t_min, f.t_max, none, none, none, none, none});
        }
    }
    return summary;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    if (const std::optional<int> status = parse_options(argc, argv, o)) return *status;

    return guarded_main([&] {
        const TableFormat fmt_out = parse_table_format(o.format);
        const Grids g = run_grids(o.quick);
        Measurements m = start_measurements(g);
        for (const double ld : {0.25, 0.5, 1.0})
            for (const double e : {0.2, 0.5, 0.8}) measure_case(ld, e, g, o, m);
        const Table summary = summary_table(g, m);

        std::vector<std::string> left_out;
        write_result(std::cout, {m.cases, summary}, fmt_out, o.table, "--table", left_out);
        for (const auto& k : left_out) std::cerr << "note: CSV holds one table; --table " << k << " gives another\n";
    });
}
