#include <gyrokit/reports/critical_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>

namespace gyrokit {

using detail::ll;

// The amplification factor as printed: 3 digits (a half-power width or a damping
// ratio is not known better), "inf" for an undamped mode, "-" where not set.
Cell amplification_cell(const CriticalSpeed& c) {
    if (std::isnan(c.amplification)) return std::string("-");
    if (std::isinf(c.amplification)) return std::string("inf");
    return std::stod(fmt::format("{:.3g}", c.amplification));
}

namespace {

double bound_digit(double bound);

Table critical_rows(const std::vector<const CriticalSpeed*>& cs, const SpeedUnit& u) {
    // af_dof: the DOF whose response gave the half-power AF; af_note: why 1/(2 zeta) instead.
    Table t({u.column("speed"), u.column("bound"), "mode", "whirl", "harmonic", u.column("frequency"), "damping_ratio",
             "amplification", "af_method", "api684", "af_dof", "af_note"});
    const auto or_dash = [](const std::string& s) { return s.empty() ? std::string("-") : s; };
    for (const CriticalSpeed* c : cs)
        t.add_row({round_to_bound(u.factor * c->speed, u.factor * c->bound), bound_digit(u.factor * c->bound),
                   ll(c->branch), to_string(c->mode.whirl), ll(c->harmonic),
                   u.factor * c->mode.frequency(), c->mode.damping_ratio(), amplification_cell(*c),
                   std::isnan(c->amplification) ? std::string("-") : to_string(c->amplification_method),
                   std::isnan(c->amplification) ? std::string("-")
                   : c->api684_critical()       ? std::string("critical")
                                                : std::string("not critical"),
                   or_dash(c->amplification_dof), or_dash(c->amplification_note)});
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

namespace {

// A bound is vouched for by its order of magnitude: one digit, rounded up.
double bound_digit(double bound) {
    if (!(bound > 0.0) || !std::isfinite(bound)) return bound;
    const double q = std::pow(10.0, std::floor(std::log10(bound)));
    return std::ceil(bound / q * (1.0 - 1e-12)) * q;
}

}  // namespace

Table stability_table(const std::vector<StabilityChange>& sc, const SpeedUnit& u) {
    Table t({u.column("speed"), u.column("bound"), "mode", "change", u.column("frequency")});
    t.key = "stability_changes";
    t.title = "stability changes (a mode's real part passes its error bound; the speed within the bound)";
    for (const auto& c : sc)
        t.add_row({round_to_bound(u.factor * c.speed, u.factor * c.bound), bound_digit(u.factor * c.bound), ll(c.branch),
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

Table pervasive_summary(const PervasiveReport& r, const SpeedUnit& u) {
    Table t({"quantity", "value"});
    t.key = "pervasive_summary";
    t.title = "pervasive damping: what was checked, and the verdict";
    const auto speed = [&](double w) { return fmt::format("{:.6g} {}", u.factor * w, u.name); };
    std::string sets;
    for (size_t i = 0; i < r.checked.size(); ++i)
        sets += (i == 0 ? "" : i + 1 == r.checked.size() ? " and " : ", ") + r.checked[i];
    t.add_row({std::string("damping checked"),
               r.checked.empty() ? std::string("none: the model has no damping")
                                 : sets + " (each component alone, then all together)"});
    t.add_row({std::string("speeds"),
               fmt::format("{} from {} to {}", r.speeds, speed(r.from), speed(r.to))});
    t.add_row({std::string("modes checked"),
               fmt::format("{} of the undamped system: {}{}", r.modes,
                           std::isfinite(r.band) ? "every mode up to f_cut = " + speed(r.band) : std::string("every mode"),
                           r.partial ? " (a sparse window: modes up to f_cut may be missed, see the notes)" : "")});
    std::string verdict;
    if (r.checked.empty()) {
        verdict = "nothing to check";
    } else {
        std::map<std::string, int> count;
        for (const DampingLoss& l : r.losses) ++count[l.damping];
        std::string lost, pervade;
        for (const std::string& c : r.checked) {
            const auto it = count.find(c);
            if (it == count.end()) pervade += (pervade.empty() ? "" : ", ") + c;
            else
                lost += fmt::format("{}{} leaves {} (speed, mode) point{} unreached", lost.empty() ? "" : "; ", c,
                                    it->second, it->second == 1 ? "" : "s");
        }
        verdict = lost.empty() ? "damping pervades: every set reaches every checked mode at every checked speed"
                               : "not pervasive: " + lost + " (table below)" +
                                     (pervade.empty() ? "" : "; " + pervade + " pervade");
    }
    t.add_row({std::string("verdict"), verdict});
    return t;
}

}  // namespace gyrokit
