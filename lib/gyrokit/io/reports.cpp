#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/io/reports.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

namespace gyrokit {

namespace {

long long ll(int i) { return static_cast<long long>(i); }

std::vector<Cell> mode_cells(const Mode& m, const SpeedUnit& u) {
    // A real part within its error bound is neutral and shown as 0 (Mode::real_part).
    return {m.real_part(), m.lambda.imag(), u.factor * m.frequency(), to_string(m.whirl), m.damping_ratio(),
            m.log_decrement()};
}

std::string speed_label(const SpeedUnit& u) { return "speed [" + u.name + "]"; }

}  // namespace

Table eig_table(const QuadraticSpectrum& s, double speed, const SpeedUnit& u, bool rigid_body) {
    Table t({u.column("speed"), "index", "re_1_s", "im_rad_s", u.column("frequency"), "whirl", "damping_ratio", "log_dec",
             "backward_error", "error_bound"});
    t.key = "eigenvalues";
    t.title = fmt::format("eigenvalues at {:.6g} ", u.factor * speed) + u.name +
              (s.infinite_count ? " (" + std::to_string(s.infinite_count) + " infinite eigenvalues omitted)" : "");
    int index = 0;
    const auto add = [&](const Mode& m, bool rigid) {
        std::vector<Cell> row{u.factor * speed, ll(++index)};
        for (auto& c : mode_cells(m, u)) row.push_back(c);
        if (rigid) row[5] = std::string("rigid-body");
        row.push_back(m.backward_error);
        row.push_back(m.error_bound);
        t.add_row(std::move(row));
    };
    for (const Mode& m : s.modes) add(m, false);
    if (rigid_body)
        for (const Mode& m : s.rigid_body) add(m, true);
    return t;
}

std::string rigid_body_note(const std::vector<Mode>& rigid, const std::vector<std::string>& names) {
    if (rigid.empty()) return "";
    std::vector<char> moves(names.size(), 0);
    for (const Mode& m : rigid) {
        const double top = m.right.cwiseAbs().maxCoeff();
        for (Eigen::Index i = 0; i < m.right.size() && static_cast<size_t>(i) < names.size(); ++i)
            if (std::abs(m.right(i)) >= 0.1 * top) moves[static_cast<size_t>(i)] = 1;
    }
    std::string list;
    int shown = 0, more = 0;
    for (size_t i = 0; i < names.size(); ++i) {
        if (!moves[i]) continue;
        if (shown < 12) list += (shown++ ? " " : "") + names[i];
        else ++more;
    }
    if (more) list += " and " + std::to_string(more) + " more";
    return std::to_string(rigid.size()) + " rigid-body eigenvalue" + (rigid.size() == 1 ? "" : "s") +
           " (lambda = 0: free motion of a singular K) " + (rigid.size() == 1 ? "is" : "are") +
           " not " + (rigid.size() == 1 ? "a mode" : "modes") + " and not listed; moving " + (list.empty() ? std::string("-") : list);
}

std::vector<std::string> instability_warnings(const CampbellDiagram& cd, const SpeedUnit& u) {
    std::vector<std::string> out;
    for (const UnstableRange& r : unstable_ranges(cd, true)) {
        char line[256];
        std::snprintf(line, sizeof line, "mode %d is unstable from %.6g to %.6g %s (Re lambda up to %.4g 1/s)",
                      r.branch, u.factor * r.from, u.factor * r.to, u.name.c_str(), r.max_real);
        out.emplace_back(line);
    }
    return out;
}

std::string out_of_range_note(const CampbellDiagram& cd, const SpeedUnit& u) {
    if (!std::isfinite(cd.band)) return "";
    if (cd.out_of_range.empty())   // a solver of the band alone (continuation, a sparse window) has not computed them
        return fmt::format("modes above {:.6g} {} ({} times the highest excitation) are out of range, not judged; "
                           "--modes 0 judges every mode",
                           u.factor * cd.band, u.name, kBandMargin);
    double lowest = std::numeric_limits<double>::infinity();
    for (const Branch& b : cd.out_of_range)
        for (const auto& p : b.points) lowest = std::min(lowest, p.mode.frequency());
    return fmt::format("{} modes stay above {:.6g} {} over the range ({} times the highest excitation; the lowest at "
                       "{:.6g} {}): out of range, not judged; --modes 0 judges every mode",
                       cd.out_of_range.size(), u.factor * cd.band, u.name, kBandMargin, u.factor * lowest, u.name);
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

Table campbell_summary(const CampbellDiagram& cd, const std::vector<CriticalSpeed>& critical, const SpeedUnit& u,
                       const std::string& plot_file, bool window) {
    Table t({"quantity", "value"});
    t.key = "summary";
    t.title = "Campbell diagram: summary (all rows: --rows, or --format csv|json)";
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
    // The least damped oscillating mode over the range, untracked ones included.
    const BranchPoint* least = nullptr;
    int least_branch = 0;
    std::vector<const Branch*> all;
    for (const auto* list : {&cd.branches, &cd.untracked})
        for (const auto& b : *list) all.push_back(&b);
    for (const Branch* bp : all)
        for (const auto& p : bp->points)
            if (p.mode.frequency() > 0 && (!least || p.mode.damping_ratio() < least->mode.damping_ratio()))
                least = &p, least_branch = bp->id;
    if (least)
        t.add_row({std::string("least damping"), fmt::format("damping ratio {:.4g}: mode {} ({}) at {}",
                                                              least->mode.damping_ratio(), least_branch,
                                                              to_string(least->mode.whirl), speed(least->speed))});
    // The verdict covers every mode: a dense diagram keeps the untracked ones by eigenvalue;
    // a sparse window covers its tracked modes only, and says so.
    const auto unstable = unstable_ranges(cd, true);
    window = window || (cd.partial && !std::isfinite(cd.band));   // the K lowest of a continuation
    const std::string which =
        window ? fmt::format("the {} tracked modes (the others are not checked)", cd.branches.size())
               : (std::isfinite(cd.band) ? "every mode in range" : "every mode");
    std::string verdict = unstable.empty() ? fmt::format("{} stable over the range (no real part beyond its error "
                                                         "bound)",
                                                         which)
                                           : "";
    // Modes are numbered by frequency at the first speed, so the lowest ones are the tracked ones.
    for (const auto& r : unstable)
        verdict += fmt::format("{}mode {} unstable from {} to {}{}", verdict.empty() ? "" : "; ", r.branch,
                               speed(r.from), speed(r.to),
                               r.branch > static_cast<int>(cd.branches.size()) ? " (not tracked: --modes 0 tracks it)"
                                                                                : "");
    if (!unstable.empty() && window)
        verdict += fmt::format("; modes beyond the {} tracked are not checked", cd.branches.size());
    t.add_row({std::string("stability"), verdict});
    if (std::isfinite(cd.band)) t.add_row({std::string("out of range"), out_of_range_note(cd, u)});
    if (cd.rigid_body > 0)
        t.add_row({std::string("rigid-body eigenvalues"), fmt::format("{} (not modes, not tracked)", cd.rigid_body)});
    t.add_row({std::string("largest backward error"), fmt::format("{:.2g}", cd.max_backward_error)});
    if (cd.ambiguous_steps > 0)
        t.add_row({std::string("ambiguous steps"), fmt::format("{} (use a finer --speeds grid)", cd.ambiguous_steps)});
    t.add_row({std::string("plot"), plot_file.empty() ? std::string("none (--plot FILE.svg draws one)") : plot_file});
    return t;
}

namespace {

// The amplification factor as printed: 3 digits (a half-power width or a damping
// ratio is not known better), "inf" for an undamped mode, "-" where not set.
Cell amplification_cell(const CriticalSpeed& c) {
    if (std::isnan(c.amplification)) return std::string("-");
    if (std::isinf(c.amplification)) return std::string("inf");
    return std::stod(fmt::format("{:.3g}", c.amplification));
}

Table critical_rows(const std::vector<const CriticalSpeed*>& cs, const SpeedUnit& u) {
    Table t({u.column("speed"), "mode", "whirl", "harmonic", u.column("frequency"), "damping_ratio", "amplification",
             "af_method", "api684"});
    for (const CriticalSpeed* c : cs)
        t.add_row({u.factor * c->speed, ll(c->branch), to_string(c->mode.whirl), ll(c->harmonic),
                   u.factor * c->mode.frequency(), c->mode.damping_ratio(), amplification_cell(*c),
                   std::isnan(c->amplification) ? std::string("-") : to_string(c->amplification_method),
                   std::isnan(c->amplification) ? std::string("-")
                   : c->api684_critical()       ? std::string("critical")
                                                : std::string("not critical")});
    return t;
}

}  // namespace

Table critical_table(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u) {
    std::vector<const CriticalSpeed*> all;
    for (const auto& c : cs) all.push_back(&c);
    Table t = critical_rows(all, u);
    t.key = "critical_speeds";
    t.title = "critical speeds";
    return t;
}

std::vector<Table> critical_tables(const std::vector<CriticalSpeed>& cs, const SpeedUnit& u) {
    std::vector<const CriticalSpeed*> critical, damped;
    for (const auto& c : cs) (c.api684_critical() ? critical : damped).push_back(&c);
    Table a = critical_rows(critical, u);
    a.key = "critical_speeds";
    a.title = fmt::format("critical speeds (API 684: amplification factor >= {})", kApi684CriticalAmplification);
    if (damped.empty()) return {a};
    Table b = critical_rows(damped, u);
    b.key = "heavily_damped_crossings";
    b.title = fmt::format("heavily damped crossings (amplification factor < {}: not critical by API 684)",
                          kApi684CriticalAmplification);
    return {a, b};
}

double round_to_bound(double x, double bound) {
    if (!(bound > 0.0) || !std::isfinite(bound) || !std::isfinite(x)) return x;
    const double q = std::pow(10.0, std::floor(std::log10(bound)));
    return std::round(x / q) * q;
}

Table stability_table(const std::vector<StabilityChange>& sc, const SpeedUnit& u) {
    Table t({u.column("speed"), u.column("bound"), "mode", "change", u.column("frequency")});
    t.key = "stability_changes";
    t.title = "stability changes (a mode's real part passes its error bound; the speed within the bound)";
    for (const auto& c : sc)
        t.add_row({round_to_bound(u.factor * c.speed, u.factor * c.bound), u.factor * c.bound, ll(c.branch),
                   std::string(c.becomes_unstable ? "unstable" : "stable"), u.factor * c.mode.frequency()});
    return t;
}

Table pervasive_table(const PervasiveReport& r, const SpeedUnit& u) {
    Table t({"damping", u.column("speed"), "mode", u.column("frequency"), "whirl", "residual"});
    std::string checked;
    for (const auto& c : r.checked) checked += (checked.empty() ? "" : ", ") + c;
    t.key = "pervasive_damping";
    t.title = "speeds where damping does not pervade (checked: " + (checked.empty() ? "no damping" : checked) + ")";
    for (const auto& l : r.losses)
        t.add_row({l.damping, u.factor * l.speed, ll(l.mode), u.factor * l.lost.frequency(), to_string(l.lost.whirl),
                   l.residual});
    return t;
}

namespace {

std::string unit_of(const std::vector<std::string>& units, int dof) {
    return units.empty() ? std::string() : units[static_cast<size_t>(dof)];
}

// The units of the DOFs: metres first (displacements are what one reads first), then in first-seen order.
std::vector<std::string> units_in(const std::vector<std::string>& units, const std::vector<int>& dofs) {
    std::vector<std::string> out;
    for (const int k : dofs)
        if (std::find(out.begin(), out.end(), unit_of(units, k)) == out.end()) out.push_back(unit_of(units, k));
    std::stable_partition(out.begin(), out.end(), [](const std::string& u) { return u == "m"; });
    return out;
}

}  // namespace

Table response_table(const std::vector<std::string>& names, const std::vector<std::string>& units,
                     const ResponseCurve& c, const SpeedUnit& u) {
    Table t({u.column("speed"), "dof", "unit", "amplitude", "phase_deg"});
    t.key = "response";
    t.title = "unbalance response z = Re(Z e^{i w t}); amplitude |Z| in the DOF's unit, phase arg Z in degrees";
    for (size_t i = 0; i < c.speeds.size(); ++i)
        for (size_t k = 0; k < c.dofs.size(); ++k) {
            const auto z = c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
            t.add_row({u.factor * c.speeds[i], names[static_cast<size_t>(c.dofs[k])], unit_of(units, c.dofs[k]),
                       std::abs(z), std::abs(z) == 0.0 ? 0.0 : std::arg(z) * 180.0 / M_PI});
        }
    return t;
}

namespace {

// Maxima by unit (first-seen order), then by amplitude, largest first.
std::vector<ResponseMaximum> by_unit_and_size(const std::vector<std::string>& units,
                                              std::vector<ResponseMaximum> m) {
    std::vector<int> dofs;
    for (const auto& x : m) dofs.push_back(x.dof);
    const std::vector<std::string> order = units_in(units, dofs);
    const auto rank = [&](int dof) {
        return std::find(order.begin(), order.end(), unit_of(units, dof)) - order.begin();
    };
    // Amplitudes equal to 9 digits (x and y of an isotropic rotor) keep the model's DOF order, whatever rounding says.
    const auto size = [](double a) { return std::stod(fmt::format("{:.9g}", a)); };
    std::stable_sort(m.begin(), m.end(), [&](const ResponseMaximum& a, const ResponseMaximum& b) {
        if (rank(a.dof) != rank(b.dof)) return rank(a.dof) < rank(b.dof);
        return size(a.amplitude) != size(b.amplitude) ? size(a.amplitude) > size(b.amplitude) : a.dof < b.dof;
    });
    return m;
}

}  // namespace

Table response_summary(const std::vector<std::string>& names, const std::vector<std::string>& units,
                       const std::vector<ResponseMaximum>& maxima, const SpeedUnit& u, std::size_t limit) {
    Table t({"dof", "unit", "max_amplitude", u.column("speed"), "where"});
    t.key = "response_maxima";
    std::size_t left_out = 0, in_unit = 0;
    std::string unit;
    for (const auto& m : by_unit_and_size(units, maxima)) {
        if (unit_of(units, m.dof) != unit) unit = unit_of(units, m.dof), in_unit = 0;
        if (limit > 0 && in_unit++ >= limit) {
            ++left_out;
            continue;
        }
        t.add_row({names[static_cast<size_t>(m.dof)], unit_of(units, m.dof), m.amplitude, u.factor * m.speed,
                   std::string(!m.bounded ? "undamped resonance (unbounded)"
                               : m.refined ? "peak (refined)"
                                           : "range end")});
    }
    const auto unbounded = std::count_if(maxima.begin(), maxima.end(), [](const ResponseMaximum& m) { return !m.bounded; });
    t.title = "largest unbalance response per DOF (peaks refined between grid speeds)" +
              (left_out ? fmt::format("; {} smaller ones left out", left_out) : std::string()) +
              (unbounded ? fmt::format("; {} DOF(s) pass an undamped resonance (damping ratio below 6e-7): "
                                       "unbounded there, add damping to the model",
                                       unbounded)
                         : std::string());
    return t;
}

std::vector<int> largest_responses(const std::vector<std::string>& units, const std::vector<ResponseMaximum>& maxima,
                                   std::size_t per_unit) {
    std::vector<int> out;
    std::size_t in_unit = 0;
    std::string unit;
    for (const auto& m : by_unit_and_size(units, maxima)) {
        if (unit_of(units, m.dof) != unit) unit = unit_of(units, m.dof), in_unit = 0;
        if (in_unit++ < per_unit) out.push_back(m.dof);
    }
    return out;
}

Table extrema_table(const std::vector<std::string>& names, const std::vector<std::string>& units,
                    const std::vector<ResponseExtremum>& e, const SpeedUnit& u) {
    Table t({"dof", "unit", "kind", u.column("speed"), "amplitude"});
    t.key = "response_peaks";
    t.title = "response peaks and antiresonances";
    for (const auto& x : e)
        t.add_row({names[static_cast<size_t>(x.dof)], unit_of(units, x.dof),
                   std::string(!x.bounded ? "unbounded peak" : x.peak ? "peak" : "antiresonance"),
                   u.factor * x.speed, x.amplitude});
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

namespace {

// Columns of the curve to draw: `shown` (model DOFs), or all.
std::vector<size_t> columns_shown(const ResponseCurve& c, const std::vector<int>& shown) {
    std::vector<size_t> cols;
    for (size_t k = 0; k < c.dofs.size(); ++k)
        if (shown.empty() || std::find(shown.begin(), shown.end(), c.dofs[k]) != shown.end()) cols.push_back(k);
    return cols;
}

std::string amplitude_label(const std::string& unit, const char* what) {
    return unit.empty() ? std::string(what) : std::string(what) + " [" + unit + "]";
}

}  // namespace

Figure response_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                       const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                       const std::vector<int>& shown) {
    Figure f;
    f.title = title.empty() ? "Unbalance response" : title;
    const std::vector<size_t> cols = columns_shown(c, shown);
    std::vector<int> dofs;
    for (const size_t k : cols) dofs.push_back(c.dofs[k]);
    Panel ph{speed_label(u), "phase [deg]", "", false, {}, -180.0, 180.0, {}, {}};
    for (const std::string& unit : units_in(units, dofs)) {
        Panel amp{speed_label(u), amplitude_label(unit, "amplitude |Z|"), "", true, {}, {}, {}, {}, {}};
        for (const size_t k : cols) {
            if (unit_of(units, c.dofs[k]) != unit) continue;
            Series a, p;
            a.label = p.label = names[static_cast<size_t>(c.dofs[k])];
            for (size_t i = 0; i < c.speeds.size(); ++i) {
                const auto z = c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
                a.x.push_back(u.factor * c.speeds[i]);
                a.y.push_back(std::abs(z));
                p.x.push_back(a.x.back());
                p.y.push_back(std::abs(z) == 0.0 ? 0.0 : std::arg(z) * 180.0 / M_PI);
            }
            amp.series.push_back(std::move(a));
            ph.series.push_back(std::move(p));
        }
        f.panels.push_back(std::move(amp));
    }
    f.panels.push_back(std::move(ph));
    return f;
}

Figure response_polar_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                             const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                             const std::vector<int>& shown) {
    Figure f;
    f.title = (title.empty() ? std::string("Unbalance response") : title) +
              fmt::format(" (polar, {:.6g} to {:.6g} {})", u.factor * c.speeds.front(), u.factor * c.speeds.back(),
                          u.name);
    const std::vector<size_t> cols = columns_shown(c, shown);
    std::vector<int> dofs;
    for (const size_t k : cols) dofs.push_back(c.dofs[k]);
    for (const std::string& unit : units_in(units, dofs)) {
        Panel p{amplitude_label(unit, "Re Z"), amplitude_label(unit, "Im Z"), "", false, {}, {}, {}, {}, {}};
        p.equal_axes = true;
        for (const size_t k : cols) {
            if (unit_of(units, c.dofs[k]) != unit) continue;
            Series s;
            s.label = names[static_cast<size_t>(c.dofs[k])];
            for (size_t i = 0; i < c.speeds.size(); ++i) {
                const auto z = c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
                s.x.push_back(z.real());
                s.y.push_back(z.imag());
            }
            p.series.push_back(std::move(s));
        }
        f.panels.push_back(std::move(p));
    }
    return f;
}

namespace {

constexpr double kDegrees = 180.0 / M_PI;

std::string mode_title(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u) {
    return fmt::format("mode shapes at {:.6g} {} ({} mode{})", u.factor * speed, u.name, shapes.size(),
                       shapes.size() == 1 ? "" : "s");
}

// Pairs a shape plot shows: those in metres, or all if none is.
std::vector<const PairOrbit*> shown_pairs(const ModeShape& s) {
    std::vector<const PairOrbit*> out;
    for (const auto& p : s.orbits)
        if (p.unit == "m") out.push_back(&p);
    if (out.empty())
        for (const auto& p : s.orbits) out.push_back(&p);
    return out;
}

}  // namespace

Table mode_list_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& names, double speed,
                      const SpeedUnit& u) {
    Table t({u.column("speed"), "mode", u.column("frequency"), "whirl", "damping_ratio", "largest", "error_bound"});
    t.key = "modes";
    t.title = mode_title(shapes, speed, u);
    for (const auto& s : shapes)
        t.add_row({u.factor * speed, ll(s.number), u.factor * s.mode.frequency(), to_string(s.mode.whirl),
                   s.mode.damping_ratio(), names[static_cast<size_t>(s.reference)], s.mode.error_bound});
    return t;
}

Table mode_orbit_table(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u) {
    // Node and axial position only for a model whose pairs sit on an axis.
    const bool nodes = !shapes.empty() && !shapes.front().orbits.empty() && shapes.front().orbits.front().node >= 0;
    std::vector<std::string> columns{u.column("speed"), "mode", u.column("frequency"), "pair"};
    if (nodes) columns.insert(columns.end(), {"node", "z_m"});
    columns.insert(columns.end(), {"unit", "major", "minor", "angle_deg", "phase_deg", "whirl"});
    Table t(columns);
    t.key = "mode_orbits";
    t.title = mode_title(shapes, speed, u) + ": orbits, scaled to 1 at the largest entry";
    for (const auto& s : shapes) {
        for (const auto& p : s.orbits) {
            std::vector<Cell> row{u.factor * speed, ll(s.number), u.factor * s.mode.frequency(), p.name};
            if (nodes) row.insert(row.end(), {ll(p.node), p.z});
            row.insert(row.end(), {p.unit, p.orbit.major, p.orbit.minor, p.orbit.angle * kDegrees,
                                   p.orbit.phase * kDegrees, to_string(p.orbit.whirl)});
            t.add_row(std::move(row));
        }
    }
    return t;
}

Table mode_dof_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& names,
                     const std::vector<std::string>& units, double speed, const SpeedUnit& u) {
    Table t({u.column("speed"), "mode", u.column("frequency"), "dof", "unit", "re", "im", "amplitude", "phase_deg"});
    t.key = "mode_entries";
    t.title = mode_title(shapes, speed, u) + ": eigenvector entries, scaled to 1 at the largest";
    for (const auto& s : shapes) {
        for (Eigen::Index i = 0; i < s.shape.size(); ++i) {
            const auto x = s.shape(i);
            t.add_row({u.factor * speed, ll(s.number), u.factor * s.mode.frequency(), names[static_cast<size_t>(i)],
                       units.empty() ? std::string() : units[static_cast<size_t>(i)], x.real(), x.imag(),
                       std::abs(x), std::abs(x) == 0.0 ? 0.0 : std::arg(x) * kDegrees});
        }
    }
    return t;
}

Figure mode_shape_figure(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u,
                         const std::string& title) {
    static const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                                   "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
    Figure f;
    f.title = (title.empty() ? std::string("Mode shapes") : title) +
              fmt::format(" at {:.6g} {}", u.factor * speed, u.name);
    const bool along_axis = !shapes.empty() && !shapes.front().orbits.empty() &&
                            std::all_of(shapes.front().orbits.begin(), shapes.front().orbits.end(),
                                        [](const PairOrbit& p) { return p.node >= 0; });
    const auto label = [&](size_t k) {
        const ModeShape& s = shapes[k];
        return fmt::format("mode {}: {:.5g} {} {}", s.number, u.factor * s.mode.frequency(), u.name,
                           to_string(s.mode.whirl));
    };
    if (along_axis) {
        Panel shape{"z [m]", "deflection at t = 0, plane of the largest entry", "", false, {}, {}, {}, {}, {}};
        Panel envelope{"z [m]", "orbit major semi-axis", "", false, {}, 0.0, {}, {}, {}};
        for (size_t k = 0; k < shapes.size(); ++k) {
            Series d, e;
            d.label = label(k);
            d.style = e.style = "linespoints";
            d.color = e.color = colors[k % 10];
            // The plane (u or v) in which the reference entry lies: there the shape is real at t = 0.
            const auto pairs = shown_pairs(shapes[k]);
            const bool v_plane = std::any_of(pairs.begin(), pairs.end(),
                                             [&](const PairOrbit* p) { return p->v == shapes[k].reference; });
            for (const PairOrbit* p : pairs) {
                d.x.push_back(p->z);
                d.y.push_back(shapes[k].shape(v_plane ? p->v : p->u).real());
                e.x.push_back(p->z);
                e.y.push_back(p->orbit.major);
            }
            shape.series.push_back(std::move(d));
            envelope.series.push_back(std::move(e));
        }
        f.panels = {std::move(shape), std::move(envelope)};
        return f;
    }
    // No axis: each mode's orbits, u(t) against v(t) over one period.
    for (size_t k = 0; k < shapes.size(); ++k) {
        Panel orbits{"u", "v", label(k), false, {}, {}, {}, {}, {}};
        orbits.equal_axes = true;
        int c = 0;
        for (const PairOrbit* p : shown_pairs(shapes[k])) {
            // The orbit, and its first eighth thicker as points: the sense of the whirl.
            Series e, start;
            e.label = p->name;
            e.color = start.color = colors[c++ % 10];
            start.style = "points";
            for (int i = 0; i <= 72; ++i) {
                const std::complex<double> phase = std::polar(1.0, 2.0 * M_PI * i / 72.0);
                e.x.push_back((shapes[k].shape(p->u) * phase).real());
                e.y.push_back((shapes[k].shape(p->v) * phase).real());
                if (i <= 9) start.x.push_back(e.x.back()), start.y.push_back(e.y.back());
            }
            orbits.series.push_back(std::move(e));
            orbits.series.push_back(std::move(start));
        }
        f.panels.push_back(std::move(orbits));
    }
    return f;
}

namespace {

// A solid cylinder of mass m with the inertias Ip = m r^2 / 2 and Id = m (3 r^2 + w^2) / 12:
// the radius and width a disk given by (m, Id, Ip) would have.
std::pair<double, double> disk_cylinder(const FeDisk& d) {
    if (d.mass <= 0.0) return {0.0, 0.0};
    const double r = std::sqrt(2.0 * d.polar_inertia / d.mass);
    const double w2 = 12.0 * d.diametral_inertia / d.mass - 3.0 * r * r;
    return {r, w2 > 0.0 ? std::sqrt(w2) : 0.0};
}

}  // namespace

namespace {

// The shaft node a speed-dependent bearing stands at (-1: none): its x DOF's node, or
// the node of the pedestal it acts on (a held shaft: px<node>).
int bearing_node(const GyroscopicSystem& s, const BearingTable& b) {
    if (s.node_of_dof.empty()) return -1;
    const int node = s.node_of_dof[static_cast<size_t>(b.dof_x)];
    const std::string& name = s.dof_names[static_cast<size_t>(b.dof_x)];
    if (node < 0 && name.rfind("px", 0) == 0) return std::stoi(name.substr(2));
    return node;
}

}  // namespace

Table model_summary(const Scene& sc) {
    Table t({"quantity", "value", "unit"});
    t.key = "model";
    t.title = "model " + sc.path + (sc.title.empty() ? std::string() : ": " + sc.title);
    const GyroscopicSystem& s = sc.system;
    const auto add = [&](const std::string& q, const Cell& v, const std::string& unit = "") {
        t.add_row({q, v, unit});
    };
    add("type", sc.model_type);
    add("dofs", ll(s.size()));
    if (!s.dof_units.empty()) {
        std::vector<std::string> seen;
        for (const auto& u : s.dof_units)
            if (std::find(seen.begin(), seen.end(), u) == seen.end()) seen.push_back(u);
        for (const auto& u : seen)
            add("dofs_in_" + u, ll(static_cast<int>(std::count(s.dof_units.begin(), s.dof_units.end(), u))));
    }
    add("whirl_pairs", ll(static_cast<int>(s.whirl_pairs.size())));
    if (!s.node_z.empty()) {
        add("nodes", ll(static_cast<int>(s.node_z.size())));
        add("length", *std::max_element(s.node_z.begin(), s.node_z.end()) -
                          *std::min_element(s.node_z.begin(), s.node_z.end()), "m");
    }
    // Mass that a unit translation along u of every free translational pair moves: r^T M r
    // (nodes a support holds are not in the system, so their share is not either).
    if (!s.dof_units.empty()) {
        Eigen::VectorXd r = Eigen::VectorXd::Zero(s.size());
        for (const auto& [u, v] : s.whirl_pairs)
            if (s.dof_units[static_cast<size_t>(u)] == "m") r(u) = 1.0;
        if (r.sum() > 0) add("translating_mass", r.dot(SparseMatrix(s.M) * r), "kg");
    }
    add("nonzeros_M_K", ll(static_cast<int>(s.M.nonZeros() + s.K.nonZeros())));
    add("gyroscopic", std::string(s.G.nonZeros() > 0 && s.G.norm() > 0 ? "yes" : "no"));
    // Circulatory forces: a speed-proportional N, or a skew part of the stiffness (cross-coupled
    // bearings, constant or speed-dependent: the usual cause of oil whip).
    {
        const bool skew_K = SparseMatrix(s.K - SparseMatrix(s.K.transpose())).norm() > 0.0;
        const bool skew_tables = std::any_of(s.bearings.begin(), s.bearings.end(), [](const BearingTable& b) {
            return std::any_of(b.speeds.begin(), b.speeds.end(), [&](double w) {
                const Eigen::Matrix2d k = b.at(w).K;
                return k(0, 1) != k(1, 0);
            });
        });
        std::vector<std::string> why;
        if (s.has_circulatory()) why.push_back("N per unit speed");
        if (skew_K || skew_tables) why.push_back("cross-coupled stiffness");
        add("circulatory", why.empty() ? std::string("no") : fmt::format("yes ({})", fmt::join(why, ", ")));
    }
    add("speed_squared_stiffness", std::string(s.has_speed_squared_stiffness() ? "yes" : "no"));
    std::string damping;
    for (const auto& n : s.damping_names()) damping += (damping.empty() ? "" : ", ") + n;
    add("damping", damping.empty() ? std::string("none") : damping);
    add("bearing_tables", ll(static_cast<int>(s.bearings.size())));
    add("unbalance", std::string(s.unbalance.size() > 0 && s.unbalance.norm() > 0 ? "yes" : "no"));
    if (s.size() <= kAutoSparseDofs) {
        const QuadraticSpectrum sp = solve_at_speed(s, 0.0);
        add("rigid_body_eigenvalues_at_rest", ll(static_cast<int>(sp.rigid_body.size())));
        if (!sp.modes.empty()) add("lowest_frequency_at_rest", sp.modes.front().frequency(), "rad/s");
    } else {
        add("rigid_body_eigenvalues_at_rest", std::string("not computed (sparse model)"));
    }
    if (sc.fe_rotor) {
        const FeRotor& r = *sc.fe_rotor;
        add("elements", ll(static_cast<int>(r.elements.size())));
        add("motion", std::string(to_string(r.motion)));
        add("dofs_per_node", ll(dofs_per_node(r.motion)));
        add("couplings", ll(static_cast<int>(std::count_if(r.elements.begin(), r.elements.end(),
                                                            [](const FeShaftElement& e) { return e.coupling.has_value(); }))));
        double shaft = 0.0, dmin = 1e300, dmax = 0.0;
        for (const auto& e : r.elements) {
            shaft += fe_element_mass(e);   // couplings: their mass
            if (e.coupling) continue;
            for (const double d : {e.outer_diameter, e.outer_diameter_end.value_or(e.outer_diameter)}) {
                dmin = std::min(dmin, d);
                dmax = std::max(dmax, d);
            }
        }
        add("shaft_mass", shaft, "kg");
        double disks = 0.0;
        for (const auto& d : r.disks) disks += d.mass;
        add("total_mass", shaft + disks, "kg");
        add("shaft_outer_diameter_min", dmin, "m");
        add("shaft_outer_diameter_max", dmax, "m");
        add("shear_deformation", std::string(r.shear_deformation ? "yes" : "no"));
        add("rotary_inertia", std::string(r.rotary_inertia ? "yes" : "no"));
        int k = 0;
        for (const auto& d : r.disks) {
            const std::string p = fmt::format("disk{}_", ++k);
            add(p + "z", s.node_z[static_cast<size_t>(d.node)], "m");
            add(p + "mass", d.mass, "kg");
            add(p + "Id", d.diametral_inertia, "kg m^2");
            add(p + "Ip", d.polar_inertia, "kg m^2");
        }
        k = 0;
        for (const auto& b : r.bearings)
            add(fmt::format("bearing{}_z", ++k), s.node_z[static_cast<size_t>(b.node)], "m");
        for (const auto& b : s.bearings)
            if (const int node = bearing_node(s, b); node >= 0)
                add(fmt::format("bearing{}_z", ++k), s.node_z[static_cast<size_t>(node)], "m");
        k = 0;
        for (const auto& sp : r.supports)
            add(fmt::format("support{}_z", ++k), s.node_z[static_cast<size_t>(sp.node)], "m");
        k = 0;
        for (const auto& p : r.pedestals) {
            const std::string key = fmt::format("pedestal{}_", ++k);
            add(key + "z", s.node_z[static_cast<size_t>(p.node)], "m");
            add(key + "mass", p.mass, "kg");
            add(key + "kxx", p.kxx, "N/m");
            add(key + "kyy", p.kyy, "N/m");
            add(key + "cxx", p.cxx, "N s/m");
            add(key + "cyy", p.cyy, "N s/m");
        }
    }
    return t;
}

Figure fe_rotor_figure(const FeRotor& r, const GyroscopicSystem& sys, const std::string& title) {
    Figure f;
    f.title = title.empty() ? std::string("Finite-element rotor") : title;
    Panel p{"z [m]", "radius [m]", "", false, {}, {}, {}, {}, {}};
    std::vector<double> z(static_cast<size_t>(r.node_count()), 0.0);
    for (size_t e = 0; e < r.elements.size(); ++e) z[e + 1] = z[e] + r.elements[e].length;
    // Shaft outline: outer radius above and below the axis, the bore dashed.
    Series top, bottom, bore_top, bore_bottom;
    top.label = "shaft";
    top.color = bottom.color = "#1f77b4";
    bore_top.color = bore_bottom.color = "#1f77b4";
    bore_top.style = bore_bottom.style = "dashed";
    for (size_t e = 0; e < r.elements.size(); ++e) {
        const FeShaftElement& el = r.elements[e];
        if (el.coupling) {   // no outline: a gap in the drawn shaft
            for (Series* s : {&top, &bottom, &bore_top, &bore_bottom}) s->x.push_back(NAN), s->y.push_back(NAN);
            continue;
        }
        // Both ends of the element: a step between uniform elements, a slope along a cone.
        const double ends[2][2] = {{el.outer_diameter / 2, el.inner_diameter / 2},
                                   {el.outer_diameter_end.value_or(el.outer_diameter) / 2,
                                    el.inner_diameter_end.value_or(el.inner_diameter) / 2}};
        for (int k = 0; k < 2; ++k) {
            const double x = z[e + k], ro = ends[k][0], ri = ends[k][1];
            top.x.push_back(x), top.y.push_back(ro);
            bottom.x.push_back(x), bottom.y.push_back(-ro);
            bore_top.x.push_back(x), bore_top.y.push_back(ri > 0 ? ri : NAN);
            bore_bottom.x.push_back(x), bore_bottom.y.push_back(ri > 0 ? -ri : NAN);
        }
    }
    p.series = {top, bottom, bore_top, bore_bottom};
    Series disks;
    disks.label = "disks (solid cylinders of their m, Id, Ip)";
    disks.color = "#d62728";
    for (const auto& d : r.disks) {
        const auto [rad, width] = disk_cylinder(d);
        const double zc = z[static_cast<size_t>(d.node)], h = std::max(width, 1e-3 * z.back()) / 2;
        for (const auto& [x, y] : std::vector<std::pair<double, double>>{
                 {zc - h, -rad}, {zc - h, rad}, {zc + h, rad}, {zc + h, -rad}, {zc - h, -rad}})
            disks.x.push_back(x), disks.y.push_back(y);
        disks.x.push_back(NAN), disks.y.push_back(NAN);
    }
    if (!r.disks.empty()) p.series.push_back(disks);
    // Bearings and supports below the shaft at their nodes.
    const auto marks = [&](const std::vector<int>& nodes, const std::string& label, const std::string& color) {
        Series m;
        m.label = label;
        m.style = "points";
        m.color = color;
        for (const int n : nodes) {
            double ro = 0.0;
            if (n > 0) {
                const FeShaftElement& left = r.elements[static_cast<size_t>(n - 1)];
                ro = std::max(ro, left.outer_diameter_end.value_or(left.outer_diameter) / 2);
            }
            if (n < static_cast<int>(r.elements.size())) ro = std::max(ro, r.elements[static_cast<size_t>(n)].outer_diameter / 2);
            m.x.push_back(z[static_cast<size_t>(n)]);
            m.y.push_back(-1.5 * ro);
        }
        if (!nodes.empty()) p.series.push_back(m);
    };
    std::vector<int> bearing_nodes, support_nodes, nodes;
    for (const auto& b : r.bearings) bearing_nodes.push_back(b.node);
    for (const auto& b : sys.bearings)
        if (const int node = bearing_node(sys, b); node >= 0) bearing_nodes.push_back(node);
    for (const auto& s : r.supports) support_nodes.push_back(s.node);
    marks(bearing_nodes, "bearings", "#2ca02c");
    marks(support_nodes, "rigid supports", "#000000");
    Series axis;
    axis.label = "nodes";
    axis.style = "points";
    axis.color = "#7f7f7f";
    for (const double x : z) axis.x.push_back(x), axis.y.push_back(0.0);
    p.series.push_back(axis);
    f.panels = {p};
    return f;
}

}  // namespace gyrokit
