// report: the analyses a scene supports as one self-contained HTML page.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/output_file.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/reports/html_report.hpp>
#include <gyrokit/study/defaults.hpp>
#include <gyrokit/study/report_study.hpp>

#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace gyrokit::cli {

namespace {

struct Options {
    Common common;
    std::string out;
    int mode_shapes = defaults::report_mode_shapes;
};

}  // namespace

std::vector<Command> add_report_commands(CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* cmd = app.add_subcommand("report", "the analyses a scene supports (model, critical speed map, Campbell "
                                             "diagram and critical speeds, mode shapes, stability, the API 617 "
                                             "unbalance cases and Level I) as one self-contained HTML page");
    cmd->add_option("scene", o->common.scene, "scene file (TOML)")->required();
    cmd->add_option("--units", o->common.units, "unit of the speeds: rad/s, Hz or rpm; default: the scene's [speeds] "
                                                "units, else rad/s");
    cmd->add_option("--mode-shapes", o->mode_shapes, "the critical speeds whose mode shapes are drawn, lowest first")
        ->capture_default_str()
        ->check(CLI::Range(0, 20));
    add_output_option(cmd, "--out", o->out, "the report: an HTML file (FILE.html)")->required();
    return {{cmd, [o](std::ostream& out) {
                 if (!o->common.units.empty()) SpeedUnit::parse(o->common.units);   // before any work
                 ReportRequest r;
                 if (!o->common.units.empty()) r.unit = o->common.units;
                 r.mode_shapes = o->mode_shapes;
                 const Scene sc = load_scene(o->common.scene);
                 const Report rep = report_study(sc, r);
                 replace_file(o->out, html_report(rep), "report", "--out");
                 // The run's section and its table of inputs counted too: what the page holds.
                 std::size_t tables = 1, figures = 0;
                 for (const ReportSection& s : rep.sections) tables += s.tables.size(), figures += s.figures.size();
                 // On stderr where the page itself goes to stdout (--out -).
                 std::ostream& say = o->out == "-" || o->out == "/dev/stdout" ? std::cerr : out;
                 say << fmt::format("wrote {} ({} sections, {} tables, {} figures)\n", o->out, rep.sections.size() + 1,
                                    tables, figures);
                 const std::vector<std::string> failed = failed_sections(rep);
                 for (const std::string& f : failed) std::cerr << "warning: not computed: " << spelled_text(f) << "\n";
                 if (!failed.empty())
                     throw Error(fmt::format("{} of the report's {} analyses not computed (the page says why)",
                                             failed.size(), rep.sections.size()));
             }}};
}

}  // namespace gyrokit::cli
