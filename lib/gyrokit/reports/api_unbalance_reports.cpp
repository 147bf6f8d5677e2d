#include <gyrokit/reports/api_unbalance_reports.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/reports/critical_reports.hpp>
#include <gyrokit/reports/detail/cells.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

using detail::ll;

namespace {

constexpr double kMicro = 1e6;   // m -> um: API states orbits and limits in um
constexpr double kAmplitudeResolution = 1e-8;

std::string speed_text(const SpeedUnit& u, double w) { return fmt::format("{:.6g} {}", u.factor * w, u.name); }

// An amplitude in um, "inf" where unbounded; rounded to 1e-8 of `scale` (the case's
// largest orbit): the dynamic stiffness's solve is not vouched for below that, and a
// node of the mode's shape shows its rounding, not an orbit.
Cell um(double metres, double scale = 0.0) {
    if (std::isinf(metres)) return std::string("inf");
    return round_to_bound(metres, kAmplitudeResolution * scale) * kMicro;
}

double largest_orbit(const ApiUnbalanceCase& c) {
    double m = 0.0;
    for (const ApiAmplitude& a : c.amplitudes)
        if (std::isfinite(a.peak_to_peak)) m = std::max(m, a.peak_to_peak);
    return m;
}
Cell ratio_cell(double r) {
    if (std::isinf(r)) return std::string("inf");
    return std::stod(fmt::format("{:.4g}", r));
}

std::string criticals_text(const ApiUnbalanceStudy& s, const ApiUnbalanceCase& c) {
    std::string t;
    for (const ApiCritical& k : c.criticals) t += (t.empty() ? "" : ", ") + speed_text(s.unit, k.critical.speed);
    return t;
}

}  // namespace

Table api_unbalance_summary(const ApiUnbalanceStudy& s) {
    Table t({"quantity", "value"});
    t.key = "api_unbalance_summary";
    t.title = "API 617 unbalance response: summary";
    const auto row = [&](const char* q, const std::string& v) { t.add_row({std::string(q), v}); };
    row("verdict", to_string(s.verdict));
    for (const std::string& r : s.reasons) row("reason", r);
    row("operating range", fmt::format("{} to {} (mcs)", speed_text(s.unit, s.min_speed), speed_text(s.unit, s.mcs)));
    row("trip speed", speed_text(s.unit, s.trip_speed) + " (the responses run from 0 to it)");
    row("critical speeds sought", fmt::format("0 to {} (the higher of {} x the trip speed and {} x the mcs)",
                                              speed_text(s.unit, s.search_to), kApiTripReach, kApiMarginReach));
    row("unbalance", fmt::format("U = {} x {} W/N g mm (W kg, N the mcs in rpm)", kApiUnbalanceMultiple,
                                 kApiUnbalanceConstant));
    std::size_t probes = 0;
    for (const ApiLocation& l : s.locations) probes += l.probe ? 1 : 0;
    row("locations", fmt::format("{} probes (at the bearings), {} close clearances", probes,
                                 s.locations.size() - probes));
    row("cases", std::to_string(s.cases.size()));
    for (std::size_t i = 0; i < s.cases.size(); ++i)
        row("case", fmt::format("{}: {} ; {}", i + 1, to_string(s.cases[i].placement.layout),
                                to_string(s.cases[i].verdict)));
    row("response solves", std::to_string(s.solves));
    return t;
}

Table api_unbalance_cases(const ApiUnbalanceStudy& s) {
    Table t({"case", "layout", "critical_speeds_" + s.unit.name, "margins_met", "A1_um", "Avl_um", "Scc",
             "worst_clearance_ratio", "verdict", "reasons"});
    t.key = "api_unbalance_cases";
    t.title = "API 617 unbalance cases (A1: the probes' orbit at the critical speed of concern; Scc = Avl / A1 in "
              "[0.5, 6])";
    for (std::size_t i = 0; i < s.cases.size(); ++i) {
        const ApiUnbalanceCase& c = s.cases[i];
        double worst = 0.0;
        bool any = false;
        for (std::size_t k = 0; k < s.locations.size(); ++k)
            if (!s.locations[k].probe) any = true, worst = std::max(worst, c.amplitudes[k].ratio);
        std::string why;
        for (const std::string& r : c.reasons) why += (why.empty() ? "" : "; ") + r;
        t.add_row({ll(static_cast<int>(i + 1)), std::string(to_string(c.placement.layout)), criticals_text(s, c),
                   c.margins_met, um(c.a1, largest_orbit(c)), um(c.avl), std::stod(fmt::format("{:.3g}", c.scale)),
                   any ? ratio_cell(worst) : Cell(std::string("-")), std::string(to_string(c.verdict)), why});
    }
    return t;
}

Table api_unbalance_loads(const ApiUnbalanceStudy& s) {
    const LengthUnit& l = s.length_unit;
    Table t({"case", "node", l.column("z"), "weight_kg", "weight_of", "unbalance_g_mm", "phase_deg"});
    t.key = "api_unbalance_loads";
    t.title = "API 617 unbalance cases: the unbalances (U = 2 x 6350 W / N g mm)";
    for (std::size_t i = 0; i < s.cases.size(); ++i)
        for (const ApiUnbalanceLoad& u : s.cases[i].loads)
            t.add_row({ll(static_cast<int>(i + 1)), ll(u.node), l.in_unit(u.z), u.weight, u.weight_of,
                       u.unbalance * 1e6, detail::degrees(u.phase)});
    return t;
}

Table api_unbalance_margins(const ApiUnbalanceStudy& s) {
    const SpeedUnit& u = s.unit;
    Table t({"case", u.column("speed"), "whirl", "amplification", "af_method", "af_dof", "af_note", "side",
             "margin_percent", "required_percent", "met"});
    t.key = "api_unbalance_margins";
    t.title = "API 617 unbalance cases: separation margins (AF on the case's response; required: API 617 2.6.2.10)";
    const auto or_dash = [](const std::string& x) { return x.empty() ? std::string("-") : x; };
    for (std::size_t i = 0; i < s.cases.size(); ++i)
        for (const ApiCritical& k : s.cases[i].criticals) {
            const CriticalSpeed& c = k.critical;
            t.add_row({ll(static_cast<int>(i + 1)), u.factor * c.speed, to_string(c.mode.whirl), amplification_cell(c),
                       std::string(to_string(c.amplification_method)), or_dash(c.amplification_dof),
                       or_dash(c.amplification_note), std::string(to_string(k.margin.side)),
                       std::stod(fmt::format("{:.4g}", k.margin.percent)),
                       std::stod(fmt::format("{:.3g}", k.required)), k.met});
        }
    return t;
}

Table api_unbalance_amplitudes(const ApiUnbalanceStudy& s) {
    const LengthUnit& l = s.length_unit;
    Table t({"case", "location", "kind", l.column("z"), "peak_to_peak_um", s.unit.column("at"), "checked_um",
             "limit_um", "ratio"});
    t.key = "api_unbalance_amplitudes";
    t.title = "API 617 unbalance cases: the largest orbit from 0 to the trip speed (probes against Avl; close "
              "clearances, times Scc where a margin is not met, against 75 % of the clearance)";
    for (std::size_t i = 0; i < s.cases.size(); ++i)
        for (std::size_t k = 0; k < s.locations.size(); ++k) {
            const ApiLocation& loc = s.locations[k];
            const ApiAmplitude& a = s.cases[i].amplitudes[k];
            const double scale = largest_orbit(s.cases[i]);
            const bool none = a.peak_to_peak <= kAmplitudeResolution * scale;   // rounding: no speed of a peak
            t.add_row({ll(static_cast<int>(i + 1)), loc.name, std::string(loc.probe ? "probe" : "clearance"),
                       l.in_unit(loc.z), none ? Cell(0.0) : um(a.peak_to_peak, scale),
                       none ? Cell(std::string("-")) : Cell(s.unit.factor * a.speed),
                       none ? Cell(0.0) : um(a.scaled, scale), um(a.limit), none ? Cell(0.0) : ratio_cell(a.ratio)});
        }
    return t;
}

std::vector<Table> api_unbalance_tables(const ApiUnbalanceStudy& s) {
    std::vector<Table> out{api_unbalance_summary(s)};
    if (s.cases.empty()) return out;
    out.push_back(api_unbalance_cases(s));
    out.push_back(api_unbalance_loads(s));
    out.push_back(api_unbalance_margins(s));
    out.push_back(api_unbalance_amplitudes(s));
    return out;
}

Figure api_unbalance_figure(const ApiUnbalanceStudy& s, const std::string& title) {
    Figure f;
    f.title = (title.empty() ? std::string() : title + ": ") + "API 617 unbalance response";
    const SpeedUnit& u = s.unit;
    for (std::size_t i = 0; i < s.cases.size(); ++i) {
        const ApiUnbalanceCase& c = s.cases[i];
        Panel p;
        p.title = fmt::format("case {}: {} ; {}", i + 1, to_string(c.placement.layout), to_string(c.verdict));
        p.xlabel = detail::speed_label(u);
        p.ylabel = "peak-to-peak orbit [um]";
        double hi = 0.0;
        for (std::size_t k = 0; k < s.locations.size(); ++k) {
            Series line;
            line.label = i == 0 ? s.locations[k].name : std::string();   // one legend, on the first panel
            line.style = s.locations[k].probe ? "lines" : "dashed";
            for (std::size_t j = 0; j < s.response_speeds.size(); ++j) {
                line.x.push_back(u.factor * s.response_speeds[j]);
                line.y.push_back(c.curves(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) * kMicro);
                if (std::isfinite(line.y.back())) hi = std::max(hi, line.y.back());
            }
            p.series.push_back(line);
        }
        const auto vertical = [&](double w, const std::string& label, const char* color) {
            Series v;
            v.label = i == 0 ? label : std::string();
            v.style = "dotted";
            v.color = color;
            v.x = {u.factor * w, u.factor * w};
            v.y = {0.0, hi};
            p.series.push_back(v);
        };
        if (s.min_speed < s.mcs) vertical(s.min_speed, "minimum operating speed", "#2ca02c");
        vertical(s.mcs, "mcs", "#d62728");
        vertical(s.trip_speed, "trip speed", "#7f7f7f");
        f.panels.push_back(p);
    }
    if (f.panels.empty()) {
        Panel p;
        p.title = "no critical speed in range: no case";
        f.panels.push_back(p);
    }
    return f;
}

}  // namespace gyrokit
