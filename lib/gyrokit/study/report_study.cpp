#include <gyrokit/study/report_study.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>
#include <gyrokit/core/input_file.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/reports/api_unbalance_reports.hpp>
#include <gyrokit/reports/campbell_reports.hpp>
#include <gyrokit/reports/critical_map_reports.hpp>
#include <gyrokit/reports/critical_reports.hpp>
#include <gyrokit/reports/level1_reports.hpp>
#include <gyrokit/reports/mode_shape_reports.hpp>
#include <gyrokit/reports/model_reports.hpp>
#include <gyrokit/study/api_unbalance_study.hpp>
#include <gyrokit/study/critical_map_study.hpp>
#include <gyrokit/study/level1_study.hpp>
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <fmt/format.h>
#include <Eigen/Core>
#include <ctime>
#include <new>
#include <functional>

#ifndef GYROKIT_VERSION
#define GYROKIT_VERSION "unknown"
#endif

namespace gyrokit {

namespace {

// One section: `run` fills it; an error it throws becomes the section's failure.
ReportSection section(const std::string& key, const std::string& title,
                      const std::function<void(ReportSection&)>& run) {
    ReportSection s;
    s.key = key;
    s.title = title;
    const auto fail = [&](const std::string& why) {
        s.tables.clear();
        s.figures.clear();
        s.failed = why;
    };
    try {
        run(s);
    } catch (const Interrupted&) {
        throw;   // Ctrl-C stops the whole report
    } catch (const Error& e) {
        fail(e.marked_text());   // its option fields spelled by the front end that prints it
    } catch (const std::bad_alloc&) {
        fail("out of memory (the model is too large for this analysis)");
    }
    return s;
}

void model_section(const Scene& sc, ReportSection& s) {
    s.tables.push_back(model_summary(sc));
    if (sc.fe_rotor()) s.figures.push_back(fe_rotor_figure(sc));
}

void map_section(const Scene& sc, const SpeedUnit& u, ReportSection& s) {
    const CriticalSpeedMap map = critical_map_study(sc);
    s.text.push_back("The undamped critical speeds against bearing stiffness, with the bearings' own stiffness "
                     "curves: where a curve meets a critical speed line the rotor runs near resonance.");
    s.tables.push_back(critical_map_table(map, u));
    s.figures.push_back(critical_map_figure(map, u, sc.title));
}

// The Campbell diagram with its critical speeds and their AF, the mode shapes of the
// lowest critical speeds, and the stability changes of the same tracked diagram.
void rotor_sections(const Scene& sc, const StudyOptions& opt, int shapes, std::vector<ReportSection>& out) {
    CriticalSpeedStudy cs;
    out.push_back(section("campbell", "Campbell diagram and critical speeds", [&](ReportSection& s) {
        cs = critical_speed_study(sc.system, opt);
        s.tables.push_back(campbell_summary(cs.tracked, cs.critical, opt.unit, "the figure below"));
        for (const Table& t : critical_tables(cs.critical, opt.unit)) s.tables.push_back(t);
        s.figures.push_back(campbell_figure(cs.tracked.diagram, cs.critical, opt.harmonics, opt.unit, sc.title));
        s.diagnostics = cs.tracked.diagnostics;
    }));
    const bool tracked = out.back().failed.empty();
    out.push_back(section("modes", "Mode shapes at the critical speeds", [&](ReportSection& s) {
        if (!tracked) throw Error("no Campbell diagram (see its section)");
        // The API 684 critical speeds of the 1x line (AF >= 2.5), lowest first; the mode
        // numbered as the critical speed table numbers it (its Campbell branch).
        int drawn = 0, critical = 0;
        for (const CriticalSpeed& c : cs.critical) {
            if (c.harmonic != 1 || !(c.speed > 0) || !c.api684_critical()) continue;
            ++critical;
            if (drawn >= shapes) continue;
            std::vector<ModeShape> one{mode_shape(c.mode, sc.system)};
            one[0].number = c.branch;
            s.figures.push_back(mode_shape_figure(one, c.speed, opt.unit,
                                                  fmt::format("{} whirl, critical speed", to_string(c.mode.whirl)),
                                                  sc.length_unit(), axis_marks(sc)));
            ++drawn;
        }
        if (critical == 0)
            s.text.push_back("No 1x critical speed (API 684: amplification factor 2.5 or more) lies in the speed "
                             "range: no mode shape to draw.");
        else if (drawn < critical)
            s.text.push_back(fmt::format("The lowest {} of the {} critical speeds of the 1x line ({} for more).",
                                         drawn, critical, option_field("mode_shapes")));
    }));
    out.push_back(section("stability", "Stability", [&](ReportSection& s) {
        if (!tracked) throw Error("no Campbell diagram (see its section)");
        const StabilityStudy st = stability_of(sc.system, cs.tracked, opt);
        if (!st.changes.empty()) s.tables.push_back(stability_table(st.changes, opt.unit));
        s.diagnostics = st.tracked.diagnostics;
    }));
}

void api_sections(const Scene& sc, const std::string& unit, std::vector<ReportSection>& out) {
    out.push_back(section("api_unbalance", "API 617 unbalance cases", [&](ReportSection& s) {
        ApiUnbalanceRequest r;
        r.unit = unit;
        const ApiUnbalanceStudy a = api_unbalance_study(sc, r);
        s.tables = api_unbalance_tables(a);
        s.figures.push_back(api_unbalance_figure(a, sc.title));
        s.diagnostics = a.diagnostics;
    }));
    out.push_back(section("level1", "API 617 Level I stability", [&](ReportSection& s) {
        Level1Request r;
        r.unit = unit;
        const Level1Study l = level1_study(sc, r);
        s.tables = level1_tables(l);
        s.figures.push_back(level1_figure(l, sc.title));
        s.diagnostics = l.diagnostics;
    }));
}

std::vector<ReportInput> fingerprints(const Scene& sc) {
    std::vector<ReportInput> out;
    for (const std::string& path : sc.inputs) {
        const std::shared_ptr<const std::string> bytes = read_input(path, "report input", kMaxDataInputBytes);
        out.push_back({path, fmt::format("{:016x}", fingerprint_bytes(bytes->data(), bytes->size()))});
    }
    return out;
}

}  // namespace

Report report_study(const Scene& sc, const ReportRequest& r) {
    if (r.mode_shapes < 0 || r.mode_shapes > 20)
        throw InputError(fmt::format("{} {}: allowed: 0 to 20", option_field("mode_shapes"), r.mode_shapes));
    RotorRequest rr;
    rr.unit = r.unit;
    const StudyOptions opt = resolve_request(sc, rr);
    Report rep;
    rep.title = sc.title.empty() ? sc.path : sc.title;
    rep.unit = opt.unit.name;
    rep.version = GYROKIT_VERSION;
    rep.sections.push_back(section("model", "Model", [&](ReportSection& s) { model_section(sc, s); }));
    if (sc.rotor_model())
        rep.sections.push_back(section("map", "Undamped critical speed map",
                                       [&](ReportSection& s) { map_section(sc, opt.unit, s); }));
    rotor_sections(sc, opt, r.mode_shapes, rep.sections);
    if (sc.rotor_model() && sc.api)
        api_sections(sc, opt.unit.name, rep.sections);
    else if (sc.rotor_model())
        rep.sections.push_back(section("api", "API 617 analyses", [](ReportSection& s) {
            s.text.push_back("Not run: the scene has no [api] table (the maximum continuous speed, the operating "
                             "range and the stages; docs/scene_format.md).");
        }));
    rep.inputs = fingerprints(sc);
    rep.settings = fmt::format("{} speeds from {:.6g} to {:.6g} {}; excitation lines {}; modes: {}; f_cut {}",
                               opt.speeds.size(), opt.unit.factor * opt.speeds.front(),
                               opt.unit.factor * opt.speeds.back(), opt.unit.name, [&] {
                                   std::string h;
                                   for (const int k : opt.harmonics) h += (h.empty() ? "" : ", ") + std::to_string(k) + "x";
                                   return h;
                               }(),
                               opt.solver.modes == kModesInRange ? std::string("those in range")
                               : opt.solver.modes == 0           ? std::string("every mode")
                                                                 : std::to_string(opt.solver.modes) + " lowest",
                               opt.f_cut ? fmt::format("{:.6g} {}", opt.unit.factor * *opt.f_cut, opt.unit.name)
                                         : std::string("1.5 x the highest excitation frequency"));
    rep.build = fmt::format("Eigen {}.{}.{}; compiled by {}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION,
                            EIGEN_MINOR_VERSION, __VERSION__);
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char when[32];
    std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
    rep.generated = when;
    return rep;
}

std::vector<std::string> failed_sections(const Report& report) {
    std::vector<std::string> out;
    for (const ReportSection& s : report.sections)
        if (!s.failed.empty()) out.push_back(s.title + ": " + s.failed);
    return out;
}

}  // namespace gyrokit
