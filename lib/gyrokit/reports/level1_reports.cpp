#include <gyrokit/reports/level1_reports.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/reports/critical_reports.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

double log_decrement_bound(const Level1Point& p) {
    const double im = std::fabs(p.lambda.imag()), re = std::fabs(p.lambda.real());
    if (!(im > 0)) return std::numeric_limits<double>::infinity();
    return 2.0 * kPi * p.error_bound * (im + re) / (im * im);
}

namespace {

std::string vouched(double x, double bound, const char* unit) {
    const double r = round_to_bound(x, bound);
    if (!(bound > 0) || !std::isfinite(bound)) return fmt::format("{:.6g}{}", r, unit);
    return fmt::format("{:.12g}{} (bound {:.1g})", r, unit, bound);
}

std::string station_text(const Level1Screen& s) {
    std::string t;
    for (std::size_t i = 0; i < s.stations.size(); ++i)
        t += fmt::format("{}node {} at z = {:.6g} {}{}", i ? ", " : "", s.stations[i].node,
                         s.length_unit.in_unit(s.station_z[i]), s.length_unit.name,
                         s.stations.size() > 1 ? fmt::format(" ({:.3g} of Q)", s.stations[i].share) : std::string());
    return t;
}

}  // namespace

Table level1_summary(const Level1Screen& s) {
    Table t({"quantity", "value"});
    t.key = "level1_summary";
    t.title = "API 617 Level I stability: summary";
    const SpeedUnit& u = s.unit;
    const auto speed = [&](double w) { return fmt::format("{:.6g} {}", u.factor * w, u.name); };
    const auto row = [&](const char* q, const std::string& v) { t.add_row({std::string(q), v}); };
    row("verdict", s.level2_required ? "Level II required" : "Level I passed");
    for (const std::string& r : s.reasons) row(s.level2_required ? "reason" : "because", r);
    row("machine", std::string(to_string(s.machine.kind)) +
                       (s.machine.kind == MachineKind::centrifugal ? " compressor (Bc = 3, density ratio)"
                                                                   : " compressor or turbine (Bt = 1.5)"));
    row("maximum continuous speed", speed(*s.machine.mcs));
    row("operating speed (QA)", speed(s.machine.operating_speed.value_or(*s.machine.mcs)));
    row("QA", fmt::format("{:.6g} N/m{}", s.qa,
                          s.stage_qa.empty() || s.machine.qa
                              ? std::string(" (given)")
                              : fmt::format(" (the sum of {} stage{})", s.stage_qa.size(),
                                            s.stage_qa.size() == 1 ? "" : "s")));
    row("Q acts at", fmt::format("{} ({})", station_text(s), s.layout));
    row(s.curve.passed.empty() ? "first forward mode at Q = 0" : "first forward mode Q loads, at Q = 0",
        fmt::format("frequency {}, log decrement {}", speed(s.at_zero.lambda.imag()),
                    vouched(s.at_zero.log_decrement, log_decrement_bound(s.at_zero), "")));
    for (const PassedMode& m : s.curve.passed) row("passed over", passed_text(m, u));
    row("log decrement at QA", vouched(s.at_qa.log_decrement, log_decrement_bound(s.at_qa), ""));
    if (s.curve.q0 && *s.curve.q0 == 0.0)
        row("Q0", "0 N/m: the mode is not stable at Q = 0 (unstable, or neutral: undamped)");
    else if (s.curve.q0)
        row("Q0", fmt::format("{} ; Q0/QA = {:.4g}", vouched(*s.curve.q0, s.curve.q0_bound, " N/m"), *s.curve.q0 / s.qa));
    else
        row("Q0", fmt::format("> {:.6g} N/m = {:.3g} QA (the log decrement stays positive)",
                              s.machine.q_ratio * s.qa, s.machine.q_ratio));
    if (s.rigid_critical)
        row("first critical speed on rigid supports", fmt::format("{} ; critical speed ratio {:.4g}",
                                                                  speed(*s.rigid_critical), *s.csr));
    if (s.machine.gas_density)
        row("average gas density", fmt::format("{:.6g} kg/m^3 ; region B above a critical speed ratio of {:.4g}",
                                               *s.machine.gas_density, *s.region_boundary));
    row("eigenvalue solves", std::to_string(s.curve.solves));
    return t;
}

Table level1_stages(const Level1Screen& s) {
    const LengthUnit& l = s.length_unit;
    Table t({l.column("z"), "power_W", l.column("diameter"), l.column("width"), "density_ratio", "qa_N_m"});
    t.key = "level1_stages";
    t.title = "API 617 Level I: the stages' anticipated cross-coupling";
    for (std::size_t i = 0; i < s.machine.stages.size() && i < s.stage_qa.size(); ++i) {
        const AeroStage& a = s.machine.stages[i];
        t.add_row({l.in_unit(a.z), a.power, l.in_unit(a.diameter), l.in_unit(a.width),
                   s.machine.kind == MachineKind::centrifugal && a.density_ratio ? Cell(*a.density_ratio)
                                                                                 : Cell(std::string("-")),
                   s.stage_qa[i]});
    }
    return t;
}

Table level1_curve_table(const Level1Screen& s) {
    Table t({"Q_N_m", "Q_over_QA", "log_decrement", "log_decrement_bound", s.unit.column("frequency"), "whirl"});
    t.key = "level1_curve";
    t.title = "API 617 Level I: the first forward mode against the cross-coupling Q";
    for (const Level1Point& p : s.curve.points) {
        const double b = log_decrement_bound(p);
        t.add_row({p.q, p.q / s.qa, round_to_bound(p.log_decrement, b), b, s.unit.factor * p.lambda.imag(),
                   to_string(p.whirl)});
    }
    return t;
}

namespace {

// The rows of per-set tables under one header, each row led by its set's name.
Table by_set(const std::vector<Table>& tables, const std::vector<std::string>& names, const Table* lead) {
    std::vector<std::string> columns{"bearing_set"};
    for (const std::string& c : tables.front().columns()) columns.push_back(c);
    Table t(columns);
    t.key = tables.front().key;
    t.title = tables.front().title + " at each end of the bearings' tolerance bands";
    if (lead)
        for (std::size_t r = 0; r < lead->rows(); ++r) {
            std::vector<Cell> row{std::string("all")};
            for (const Cell& c : lead->row(r)) row.push_back(c);
            t.add_row(row);
        }
    for (std::size_t i = 0; i < tables.size(); ++i)
        for (std::size_t r = 0; r < tables[i].rows(); ++r) {
            std::vector<Cell> row{names[i]};
            for (const Cell& c : tables[i].row(r)) row.push_back(c);
            t.add_row(row);
        }
    return t;
}

const char* const kSetColors[] = {"#1f77b4", "#ff7f0e", "#9467bd", "#8c564b"};

}  // namespace

std::vector<Table> level1_tables(const Level1Study& st) {
    const Level1Screen& g = st.verdict();
    if (st.screens.size() == 1) {
        std::vector<Table> out{level1_summary(g)};
        if (!g.stage_qa.empty()) out.push_back(level1_stages(g));
        out.push_back(level1_curve_table(g));
        return out;
    }
    std::vector<Table> summaries, curves;
    std::vector<std::string> names;
    for (const Level1Screen& s : st.screens) {
        summaries.push_back(level1_summary(s));
        curves.push_back(level1_curve_table(s));
        names.push_back(s.bearing_set);
    }
    Table lead({"quantity", "value"});
    lead.add_row({std::string("verdict"), std::string(g.level2_required ? "Level II required" : "Level I passed")});
    lead.add_row({std::string("governing bearing set"),
                  fmt::format("{} (the worse of {} sets)", g.bearing_set, st.screens.size())});
    std::vector<Table> out{by_set(summaries, names, &lead)};
    if (!g.stage_qa.empty()) out.push_back(level1_stages(g));   // QA does not depend on the bearings
    out.push_back(by_set(curves, names, nullptr));
    return out;
}

Figure level1_figure(const Level1Study& st, const std::string& title) {
    Figure f;
    f.title = (title.empty() ? std::string() : title + ": ") + "API 617 Level I stability";
    Panel p;
    p.xlabel = "cross-coupled stiffness Q [N/m]";
    p.ylabel = "log decrement of the first forward mode";
    const bool several = st.screens.size() > 1;
    // QA and Q0 as vertical lines across the curves' span (a point alone is hard to see).
    double lo = 0.0, hi = 0.0;
    for (const Level1Screen& s : st.screens)
        for (const Level1Point& q : s.curve.points)
            lo = std::min(lo, q.log_decrement), hi = std::max(hi, q.log_decrement);
    const auto vertical = [&](double x, const std::string& label, const char* color) {
        Series v;
        v.label = label;
        v.style = "dashed";
        v.color = color;
        v.x = {x, x};
        v.y = {lo, hi};
        p.series.push_back(v);
    };
    for (std::size_t i = 0; i < st.screens.size(); ++i) {
        const Level1Screen& s = st.screens[i];
        Series curve;
        curve.label = several ? "log decrement, " + s.bearing_set : std::string("log decrement");
        curve.style = "linespoints";
        if (several) curve.color = kSetColors[i % 4];
        for (const Level1Point& q : s.curve.points) {
            curve.x.push_back(q.q);
            curve.y.push_back(q.log_decrement);
        }
        p.series.push_back(curve);
    }
    const Level1Screen& g = st.verdict();
    vertical(g.qa, fmt::format("QA = {:.4g} N/m (log decrement {:.3g}{})", g.qa, g.at_qa.log_decrement,
                               several ? ", " + g.bearing_set : std::string()),
             "#d62728");
    for (std::size_t i = 0; i < st.screens.size(); ++i) {
        const Level1Screen& s = st.screens[i];
        if (s.curve.q0 && *s.curve.q0 > 0)
            vertical(*s.curve.q0,
                     fmt::format("Q0 = {:.4g} N/m{}", *s.curve.q0, several ? ", " + s.bearing_set : std::string()),
                     several ? kSetColors[i % 4] : "#2ca02c");
    }
    Series limit;
    limit.label = fmt::format("log decrement {}", kLevel1MinLogDecrement);
    limit.style = "dotted";
    limit.color = "#7f7f7f";
    limit.x = {0.0, g.curve.points.back().q};
    limit.y = {kLevel1MinLogDecrement, kLevel1MinLogDecrement};
    p.series.push_back(limit);
    f.panels.push_back(p);
    return f;
}

}  // namespace gyrokit
