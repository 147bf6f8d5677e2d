// The separation criterion: margins of the critical speeds from the operating range.
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/solve/continuation.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/energy_bound.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/screening/detail/probes.hpp>
#include <gyrokit/screening/detail/row.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/response_study.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <stdexcept>

namespace gyrokit::screening_detail {

std::string position_text(double sm, double wc, const Sweep& s) {
    if (sm >= 0 && wc <= s.op_from) return fmt::format("is {:.3g}% below the operating range", sm);
    if (sm >= 0) return fmt::format("is {:.3g}% above the operating range", sm);
    return "lies inside the operating range";
}

// API 684 style margin of one critical speed from [from, to], in percent.
double separation_margin(double wc, double from, double to) {
    if (wc <= from) return 100.0 * (from - wc) / from;
    if (wc >= to) return 100.0 * (wc - to) / to;
    return -100.0 * std::min((wc - from) / from, (to - wc) / to);
}

// max_amplification_factor: the largest amplification factor among the critical speeds
// of the scan (those the separation criterion counts: its whirl), and its speed.
void check_amplification(const Sweep& s, const SeparationCriterion& c, const std::vector<CriticalSpeed>& cs, Row& row) {
    const CriticalSpeed* top = nullptr;
    for (const auto& x : cs) {
        if (c.forward_only && x.mode.whirl != Whirl::Forward) continue;
        if (!top || x.amplification > top->amplification) top = &x;
    }
    if (top) {
        row.set("max_amplification_factor", top->amplification);
        row.set(s.unit.column("max_amplification_speed"), top->speed * s.unit.factor);
        if (top->amplification > *c.max_amplification) {
            row.fail("amplification",
                     fmt::format("critical speed {:.6g} {} ({}x, {} whirl, branch {}) has AF {:.3g} "
                                    "({}), allowed at most {:.3g}",
                                    top->speed * s.unit.factor, s.unit.name, top->harmonic,
                                    to_string(top->mode.whirl), top->branch, top->amplification,
                                    to_string(top->amplification_method),
                                    *c.max_amplification));
        }
    }
}

void check_separation(const Sweep& s, const Scene& sc, const SeparationCriterion& c, Row& row) {
    const double w_scan = s.op_to * (1.0 + c.margin_percent / 100.0) * 1.05;
    // The study the CLI and Python run on the design's scene (its solver and
    // modes), over the scan range with the criterion's harmonics.
    StudyOptions so = study_options(sc);
    so.workers = 1;   // the designs run in parallel, each on one worker
    so.speeds = SpeedRange{0.0, w_scan, c.count}.points();
    so.harmonics = c.harmonics;
    so.amplification_factors = c.api684 || c.max_amplification.has_value();   // these read every factor
    std::vector<CriticalSpeed> cs = critical_speed_study(sc.system, so).critical;
    // Else the factors only tell the heavily damped crossings apart (the `critical` command's
    // verdict): those of the crossings nearest the operating range, in order of their margins,
    // until one is critical (a half-power factor costs some hundred solves).
    if (!so.amplification_factors && !c.count_heavily_damped) {
        std::vector<std::size_t> order;
        for (std::size_t i = 0; i < cs.size(); ++i)
            if (!c.forward_only || cs[i].mode.whirl == Whirl::Forward) order.push_back(i);
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return separation_margin(cs[a].speed, s.op_from, s.op_to) < separation_margin(cs[b].speed, s.op_from, s.op_to);
        });
        for (const std::size_t i : order) {
            set_amplification_factors(cs, sc.system, i);
            if (cs[i].api684_critical()) break;   // the least margin among the critical ones
        }
    }
    // The critical speed with the least margin to spare (its margin less the one it needs).
    const CriticalSpeed* worst = nullptr;
    double worst_sm = inf, worst_required = 0.0, spare = inf;
    for (const auto& x : cs) {
        if (c.forward_only && x.mode.whirl != Whirl::Forward) continue;
        // Heavily damped: no margin required (a factor left unset, NaN, is a crossing beyond the
        // first critical one found above: not the worst either way).
        if (!c.count_heavily_damped && !x.api684_critical()) continue;
        const double sm = separation_margin(x.speed, s.op_from, s.op_to);
        const double required = c.api684 ? api684_required_margin(x.amplification, x.speed > s.op_to) : c.margin_percent;
        if (sm - required < spare) spare = sm - required, worst = &x, worst_sm = sm, worst_required = required;
    }
    if (worst) {
        row.set(s.unit.column("critical_speed"), worst->speed * s.unit.factor);
        row.set("separation_percent", worst_sm);
        if (c.api684) row.set("required_separation_percent", worst_required), row.set("amplification_factor", worst->amplification);
        if (spare < 0.0) {
            row.fail("separation",
                     fmt::format("critical speed {:.6g} {} ({}x, {} whirl, branch {}{}) {}, required "
                                    "{:.3g}%",
                                    worst->speed * s.unit.factor, s.unit.name,
                                    worst->harmonic, to_string(worst->mode.whirl), worst->branch,
                                    c.api684 ? fmt::format(", AF {:.3g}", worst->amplification) : "",
                                    position_text(worst_sm, worst->speed, s), worst_required));
        }
    }
    if (c.max_amplification) check_amplification(s, c, cs, row);
}

}  // namespace gyrokit::screening_detail
