// screen: a design study over a sweep file (see docs/screening.md).
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/screening/screening.hpp>

#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <sstream>
#include <memory>
#include <thread>
#include <unistd.h>

namespace gyrokit::cli {

namespace {

struct ScreenOptions {
    std::string sweep, shard = "0/1", resume, out, format = "csv", plot, axes;
    std::vector<std::string> merge;
    int jobs = defaults::jobs;
    long long limit = 0;
};

// A one-line bar redrawn in place; only drawn when stderr is a terminal.
void draw_progress(std::size_t done, std::size_t total) {
    const int width = 40;
    const double f = total ? static_cast<double>(done) / total : 1.0;
    const int filled = static_cast<int>(f * width);
    std::cerr << '\r' << '[' << std::string(filled, '#') << std::string(width - filled, '.') << "] " << done << '/'
              << total << (done == total ? "\n" : "") << std::flush;
}

std::vector<std::string> split_axes(const std::string& text) {
    const size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos)
        throw InputError(fmt::format("--axes '{}': allowed: two parameter names P1,P2", text));
    return {text.substr(0, comma), text.substr(comma + 1)};
}

}  // namespace

std::vector<Command> add_screen_commands(CLI::App& app) {
    auto o = std::make_shared<ScreenOptions>();
    std::vector<Command> cmds;
    auto* c = app.add_subcommand("screen", "design study: sweep a scene's parameters and check criteria");
    c->add_option("sweep", o->sweep, "sweep file (TOML)")->required();
    c->add_option("--jobs", o->jobs, "designs run in parallel; 0 = all cores")->capture_default_str();
    c->add_option("--shard", o->shard, "process shard K of N (0 <= K < N): the designs i with i mod N = K")
        ->capture_default_str();
    add_output_option(c, "--out", o->out, "write the rows (CSV) into FILE as they are done (overwrites FILE)");
    add_output_option(c, "--resume", o->resume, "continue the CSV result file OUT (created if missing)");
    c->add_option("--format", o->format, "format of the rows on stdout: csv, json or table")->capture_default_str();
    add_output_option(c, "--plot", o->plot, "draw the safe region over two parameters into FILE.svg or FILE.png");
    c->add_option("--axes", o->axes, "the two parameters of the plot, P1,P2 (default: [plot] axes, else the first two)");
    c->add_option("--merge", o->merge, "instead of running: merge result files (e.g. of all shards) in design order")
        ->expected(1, -1);
    c->add_option("--limit", o->limit, "compute at most this many designs in this run (0 = all)");
    cmds.push_back({c, [o](std::ostream& os) {
        const TableFormat fmt_out = parse_table_format(o->format);
        check_plot_path(o->plot);
        if (!o->out.empty() && !o->resume.empty()) throw InputError("--out and --resume: give one of them");
        if (o->limit < 0) throw InputError(fmt::format("--limit {}: allowed: >= 0", o->limit));
        RunOptions ro;
        ro.shard = Shard::parse(o->shard);
        std::vector<std::string> notes;
        ro.jobs = worker_count(o->jobs, &notes);
        for (const auto& n : notes) std::cerr << "note: " << spell_fields(n, flag_words) << "\n";
        ro.out = o->resume.empty() ? o->out : o->resume;
        ro.resume = !o->resume.empty();
        ro.limit = static_cast<std::size_t>(o->limit);
        std::vector<std::string> axes = o->axes.empty() ? std::vector<std::string>{} : split_axes(o->axes);

        const Sweep s = read_sweep(o->sweep);
        if (axes.empty()) axes = s.plot_axes;
        if (axes.empty() && s.parameters.size() >= 2) axes = {s.parameters[0].name, s.parameters[1].name};
        if (!o->plot.empty()) {
            if (axes.size() != 2) throw InputError("--plot needs two parameters; the sweep has fewer, or give --axes");
            for (const auto& a : axes) {
                bool found = false;
                for (const auto& p : s.parameters) found = found || p.name == a;
                if (!found) throw InputError(fmt::format("--axes: '{}' is not a parameter of {}", a, o->sweep));
            }
        }

        std::vector<ResultRow> rows;
        if (!o->merge.empty()) {
            rows = merge_results(s, o->merge, true, ro.out, o->resume.empty() ? "--out" : "--resume");
            if (ro.out.empty()) write_results(os, s, rows, fmt_out);
        } else {
            if (isatty(2)) ro.progress = draw_progress;
            const RunResult r = run_screening(s, ro);
            rows = r.rows;
            if (ro.out.empty()) write_results(os, s, rows, fmt_out);
            std::cerr << fmt::format("screen: shard {}/{}: {} designs, {} resumed, {} computed{}\n", ro.shard.index,
                                     ro.shard.count, r.shard_designs, r.resumed, r.computed,
                                     ro.out.empty() ? "" : ", rows in " + ro.out);
        }
        // With aligned text on stdout the summary follows the rows; otherwise
        // stdout stays machine-readable and the summary goes to stderr.
        const bool rows_on_stdout = ro.out.empty();
        if (rows_on_stdout && fmt_out == TableFormat::Text) {
            os << '\n';
            write_table(os, summary_table(s, rows), TableFormat::Text);
        } else {
            std::ostringstream sum;
            write_table(sum, summary_table(s, rows), TableFormat::Text);
            std::cerr << sum.str();
        }
        if (!o->plot.empty()) plot_if(o->plot, safe_region_figure(s, rows, axes[0], axes[1]));
    }});
    return cmds;
}

}  // namespace gyrokit::cli
