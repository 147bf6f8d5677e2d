#include <gyrokit/reports/critical_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

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

Table critical_rows(const std::vector<const CriticalSpeed*>& cs, const SpeedUnit& u) {
    // af_dof: the DOF whose response gave the half-power AF; af_note: why 1/(2 zeta) instead.
    Table t({u.column("speed"), "mode", "whirl", "harmonic", u.column("frequency"), "damping_ratio", "amplification",
             "af_method", "api684", "af_dof", "af_note"});
    const auto or_dash = [](const std::string& s) { return s.empty() ? std::string("-") : s; };
    for (const CriticalSpeed* c : cs)
        t.add_row({u.factor * c->speed, ll(c->branch), to_string(c->mode.whirl), ll(c->harmonic),
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

}  // namespace gyrokit
