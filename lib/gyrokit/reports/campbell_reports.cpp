#include <gyrokit/reports/campbell_reports.hpp>

#include <gyrokit/reports/critical_reports.hpp>
#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

namespace gyrokit {

using detail::ll;
using detail::mode_cells;
using detail::speed_label;

std::string unstable_span(const UnstableRange& r, const SpeedUnit& u) {
    const auto edge = [&](double w, bool refined, double bound, bool at_end) {
        // A refined edge to its bound's digits; the first or last speed is the range's own edge.
        if (refined) return fmt::format("{:.6g}", round_to_bound(u.factor * w, u.factor * bound));
        return fmt::format("{:.6g}{}", u.factor * w, at_end ? "" : " (a grid speed)");
    };
    return fmt::format("from {} to {} {}", edge(r.from, r.from_refined, r.from_bound, r.first_index == 0),
                       edge(r.to, r.to_refined, r.to_bound, r.to_last), u.name);
}

std::vector<std::string> instability_warnings(const std::vector<UnstableRange>& unstable, const SpeedUnit& u) {
    std::vector<std::string> out;
    for (const UnstableRange& r : unstable)
        out.push_back(fmt::format("mode {} is unstable {} (Re lambda up to {:.4g} 1/s)", r.branch,
                                  unstable_span(r, u), r.max_real));
    return out;
}

std::string out_of_range_note(const CampbellDiagram& cd, const SpeedUnit& u) {
    if (!std::isfinite(cd.band)) return "";
    if (cd.band_of_modes)
        return fmt::format("modes above {:.6g} {} (the band holding the {} shown and their neighbours, beyond f_cut) "
                           "are not computed, not judged; {} 0 judges every mode",
                           u.factor * cd.band, u.name, cd.branches.size(), option_field("modes"));
    const std::string origin =
        cd.band_asked ? std::string("as asked") : fmt::format("{} times the highest excitation", kBandMargin);
    if (cd.out_of_range.empty())   // a solver of the band alone (continuation, a sparse window) has not computed them
        return fmt::format("modes above f_cut = {:.6g} {} ({}) are out of range, not computed, not judged; {} 0 "
                           "judges every mode",
                           u.factor * cd.band, u.name, origin, option_field("modes"));
    double lowest = std::numeric_limits<double>::infinity();
    for (const Branch& b : cd.out_of_range)
        for (const auto& p : b.points) lowest = std::min(lowest, p.mode.frequency());
    return fmt::format("{} modes stay above f_cut = {:.6g} {} over the range ({}; the lowest at {:.6g} {}): out of "
                       "range, not judged; {} 0 judges every mode",
                       cd.out_of_range.size(), u.factor * cd.band, u.name, origin, u.factor * lowest, u.name,
                       option_field("modes"));
}

Table campbell_table(const CampbellDiagram& cd, const SpeedUnit& u) {
    Table t({u.column("speed"), "mode", "re_1_s", "im_rad_s", u.column("frequency"), "whirl", "damping_ratio", "log_dec"});
    t.key = "campbell";
    t.title = "Campbell diagram";
    // Rows by speed, then mode.
    std::vector<size_t> next(cd.branches.size(), 0);
    for (double w : cd.speeds)
        for (size_t b = 0; b < cd.branches.size(); ++b) {
            const auto& pts = cd.branches[b].points;
            if (next[b] < pts.size() && pts[next[b]].speed == w) {
                std::vector<Cell> row{u.factor * w, ll(cd.branches[b].id)};
                for (auto& c : mode_cells(pts[next[b]].mode, u)) row.push_back(c);
                t.add_row(std::move(row));
                ++next[b];
            }
        }
    return t;
}

Table campbell_summary(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& critical,
                       const std::vector<UnstableRange>& unstable, const SpeedUnit& u,
                       const std::string& plot_file, bool window) {
    Table t({"quantity", "value"});
    t.key = "summary";
    t.title = "Campbell diagram: summary (all rows: " + option_field("rows") + ")";
    const auto speed = [&](double w) { return fmt::format("{:.6g} {}", u.factor * w, u.name); };
    t.add_row({std::string("modes tracked"), std::to_string(cd.branches.size())});
    if (!cd.speeds.empty())
        t.add_row({std::string("speed range"), fmt::format("{} to {} ({} speeds, {} inserted by refinement)",
                                                            speed(cd.speeds.front()), speed(cd.speeds.back()),
                                                            cd.speeds.size(), cd.inserted_speeds)});
    std::size_t forward = 0, damped = 0;
    for (const auto& c : critical) {
        if (!c.api684_critical()) ++damped;
        else forward += c.mode.whirl == Whirl::Forward;
    }
    t.add_row({std::string("critical speeds"),
               critical.empty() ? std::string("none in the range")
               : fmt::format("{} in the range (API 684: amplification factor >= {}), {} of them forward whirl{} "
                             "(tables below)",
                             critical.size() - damped, kApi684CriticalAmplification, forward,
                             damped ? fmt::format("; {} heavily damped crossings (not critical)", damped)
                                    : std::string())});
    // The least damped oscillating mode the diagram shows (the verdict below covers the others).
    if (const auto least = least_damped(cd))
        t.add_row({std::string("least damping"),
                   fmt::format("damping ratio {:.4g}: mode {} ({}) at {}, frequency {}",
                               least->point.mode.damping_ratio(), least->branch, to_string(least->point.mode.whirl),
                               speed(least->point.speed), speed(least->point.mode.frequency()))});
    // The verdict covers every mode: a dense diagram keeps the untracked ones by eigenvalue;
    // a sparse window covers its tracked modes only, and says so.
    window = window || (cd.partial && !std::isfinite(cd.band));   // the K lowest of a continuation
    if (cd.window_holds_band) window = false;   // a window widened to hold the band judges it whole
    const std::string more =
        cd.untracked.empty() ? std::string()
                             : fmt::format(" ({} shown, {} more judged)", cd.branches.size(), cd.untracked.size());
    const std::string which =
        window ? fmt::format("the {} modes of the window (the others are not checked)", cd.branches.size() + cd.untracked.size())
               : (std::isfinite(cd.band) ? fmt::format("every mode up to {}{}", speed(cd.band), more)
                                         : "every mode");
    std::string verdict = unstable.empty() ? fmt::format("{} stable over the range (no real part beyond its error "
                                                         "bound)",
                                                         which)
                                           : "";
    // Modes are numbered by frequency at the first speed, so the lowest ones are the tracked ones.
    for (const auto& r : unstable)
        verdict += fmt::format("{}mode {} unstable {}{}", verdict.empty() ? "" : "; ", r.branch, unstable_span(r, u),
                               r.branch > static_cast<int>(cd.branches.size())
                                   ? fmt::format(" (beyond the {} shown)", cd.branches.size())
                                   : "");
    if (!unstable.empty() && window)
        verdict += fmt::format("; modes beyond the {} of the window are not checked", cd.branches.size() + cd.untracked.size());
    t.add_row({std::string("stability"), verdict});
    if (std::isfinite(cd.band)) t.add_row({std::string("out of range"), out_of_range_note(cd, u)});
    if (cd.rigid_body > 0)
        t.add_row({std::string("rigid-body eigenvalues"), fmt::format("{} (not modes, not tracked)", cd.rigid_body)});
    t.add_row({std::string("largest backward error"), fmt::format("{:.2g}", cd.max_backward_error)});
    if (cd.ambiguous_steps > 0)
        t.add_row({std::string("ambiguous steps"), fmt::format("{} (use a finer {} grid)", cd.ambiguous_steps, option_field("speeds"))});
    t.add_row({std::string("plot"), plot_file.empty() ? "none (" + option_field("plot") + " draws one)" : plot_file});
    return t;
}

Figure campbell_figure(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& cs,
                       const std::vector<int>& harmonics, const SpeedUnit& u, const std::string& title) {
    Figure f;
    f.title = title.empty() ? "Campbell diagram" : title;
    Panel freq{speed_label(u), "frequency [" + u.name + "]", "", false, {}, 0.0, {}, {}, {}};
    Panel damp{speed_label(u), "damping ratio", "", false, {}, {}, {}, {}, {}};
    bool fwd_labelled = false, bwd_labelled = false;
    for (const Branch& b : cd.branches) {
        // Split the branch into runs of one whirl direction so each gets its style.
        size_t i = 0;
        while (i < b.points.size()) {
            const Whirl w = b.points[i].mode.whirl;
            Series s, d;
            for (; i < b.points.size() && b.points[i].mode.whirl == w; ++i) {
                s.x.push_back(u.factor * b.points[i].speed);
                s.y.push_back(u.factor * b.points[i].mode.frequency());
                d.x.push_back(s.x.back());
                d.y.push_back(b.points[i].mode.damping_ratio());
            }
            if (i < b.points.size()) {   // join to the next run
                s.x.push_back(u.factor * b.points[i].speed);
                s.y.push_back(u.factor * b.points[i].mode.frequency());
            }
            const bool fwd = w == Whirl::Forward, bwd = w == Whirl::Backward;
            s.color = d.color = fwd ? "#d62728" : bwd ? "#1f77b4" : "#7f7f7f";
            s.style = d.style = bwd ? "dashed" : "lines";
            if (fwd && !fwd_labelled) { s.label = "forward whirl"; fwd_labelled = true; }
            if (bwd && !bwd_labelled) { s.label = "backward whirl"; bwd_labelled = true; }
            freq.series.push_back(std::move(s));
            damp.series.push_back(std::move(d));
        }
    }
    if (!cd.speeds.empty()) {
        const double w0 = cd.speeds.front(), w1 = cd.speeds.back();
        for (int k : harmonics)
            freq.series.push_back({{u.factor * w0, u.factor * w1}, {u.factor * k * w0, u.factor * k * w1},
                                   std::to_string(k) + "x", "dashed", "#000000"});
        double fmax = 0.0;
        for (const Branch& b : cd.branches)
            for (const auto& p : b.points) fmax = std::max(fmax, u.factor * p.mode.frequency());
        // Frequencies beyond twice the highest harmonic line cross none of them: the axis stops
        // there, so that a stiff local mode (a journal on its oil film) does not flatten the rest.
        // The lowest branch stays in view when it lies above every line.
        int kmax = 1;
        for (int k : harmonics) kmax = std::max(kmax, k);
        double lowest = 0.0;
        if (!cd.branches.empty())
            for (const auto& p : cd.branches.front().points) lowest = std::max(lowest, u.factor * p.mode.frequency());
        fmax = std::min(fmax, std::max(2.0 * kmax * u.factor * w1, 1.1 * lowest));
        if (fmax > 0.0) freq.ymax = 1.05 * fmax;
    }
    Series crit{{}, {}, "critical speeds", "points", "#2ca02c"};
    for (const auto& c : cs) {
        crit.x.push_back(u.factor * c.speed);
        crit.y.push_back(u.factor * c.mode.frequency());
    }
    if (!crit.x.empty()) freq.series.push_back(std::move(crit));
    f.panels = {std::move(freq), std::move(damp)};
    return f;
}

}  // namespace gyrokit
