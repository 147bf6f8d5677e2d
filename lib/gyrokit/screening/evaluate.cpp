// Criteria evaluation of one design.
#include <gyrokit/analysis/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/continuation.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/energy_bound.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/analysis/scalar_search.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/screening/detail/probes.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

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
void check_amplification(const Sweep& s, const SeparationCriterion& c, const std::vector<CriticalSpeed>& cs,
                         std::size_t& q, DesignResult& r) {
    const CriticalSpeed* top = nullptr;
    for (const auto& x : cs) {
        if (c.forward_only && x.mode.whirl != Whirl::Forward) continue;
        if (!top || x.amplification > top->amplification) top = &x;
    }
    if (top) {
        r.quantities[q] = top->amplification;
        r.quantities[q + 1] = top->speed * s.unit.factor;
        if (top->amplification > *c.max_amplification) {
            r.failed.push_back("amplification");
            r.reason += fmt::format("{}amplification: critical speed {:.6g} {} ({}x, {} whirl, branch {}) has AF {:.3g} "
                                    "({}), allowed at most {:.3g}",
                                    r.reason.empty() ? "" : "; ", top->speed * s.unit.factor, s.unit.name, top->harmonic,
                                    to_string(top->mode.whirl), top->branch, top->amplification,
                                    to_string(top->amplification_method),
                                    *c.max_amplification);
        }
    }
    q += 2;
}

void check_separation(const Sweep& s, const Scene& sc, const SeparationCriterion& c, std::size_t& q,
                      DesignResult& r) {
    const double w_scan = s.op_to * (1.0 + c.margin_percent / 100.0) * 1.05;
    // The study the CLI and Python run on the design's scene (its solver and
    // modes), over the scan range with the criterion's harmonics.
    StudyOptions so = study_options(sc);
    so.workers = 1;   // the designs run in parallel, each on one worker
    so.speeds = SpeedRange{0.0, w_scan, c.count}.points();
    so.harmonics = c.harmonics;
    // The factors tell the heavily damped crossings apart (the `critical` command's verdict).
    so.amplification_factors = !c.count_heavily_damped || c.api684 || c.max_amplification.has_value();
    const std::vector<CriticalSpeed> cs = critical_speed_study(sc.system, so).critical;
    // The critical speed with the least margin to spare (its margin less the one it needs).
    const CriticalSpeed* worst = nullptr;
    double worst_sm = inf, worst_required = 0.0, spare = inf;
    for (const auto& x : cs) {
        if (c.forward_only && x.mode.whirl != Whirl::Forward) continue;
        if (!c.count_heavily_damped && !x.api684_critical()) continue;   // heavily damped: no margin required
        const double sm = separation_margin(x.speed, s.op_from, s.op_to);
        const double required = c.api684 ? api684_required_margin(x.amplification, x.speed > s.op_to) : c.margin_percent;
        if (sm - required < spare) spare = sm - required, worst = &x, worst_sm = sm, worst_required = required;
    }
    if (worst) {
        r.quantities[q] = worst->speed * s.unit.factor;
        r.quantities[q + 1] = worst_sm;
        if (c.api684) r.quantities[q + 2] = worst_required, r.quantities[q + 3] = worst->amplification;
        if (spare < 0.0) {
            r.failed.push_back("separation");
            r.reason += fmt::format("{}separation: critical speed {:.6g} {} ({}x, {} whirl, branch {}{}) {}, required "
                                    "{:.3g}%",
                                    r.reason.empty() ? "" : "; ", worst->speed * s.unit.factor, s.unit.name,
                                    worst->harmonic, to_string(worst->mode.whirl), worst->branch,
                                    c.api684 ? fmt::format(", AF {:.3g}", worst->amplification) : "",
                                    position_text(worst_sm, worst->speed, s), worst_required);
        }
    }
    q += c.api684 ? 4 : 2;
    if (c.max_amplification) check_amplification(s, c, cs, q, r);
}

// The least damped oscillating mode in range of a diagram: the smallest logarithmic
// decrement -2 pi Re(lambda)/Im(lambda) over its branches and speeds (0 for a neutral
// mode, negative for an unstable one) where the frequency lies within `band` (the
// excitation band of the scan). Real eigenvalues (overdamped, divergent) have no
// decrement and rigid-body eigenvalues are no branches. None: no such mode.
struct LeastLogDecrement {
    const Branch* branch = nullptr;
    double log_dec = inf, speed = 0;
};

LeastLogDecrement least_log_decrement(const CampbellDiagram& cd, double band) {
    LeastLogDecrement out;
    for (const auto* list : {&cd.branches, &cd.untracked})   // the shown modes and the others judged
        for (const Branch& b : *list)
        for (const BranchPoint& p : b.points) {
            if (p.mode.whirl == Whirl::Real || !(p.mode.lambda.imag() > 0.0) || p.mode.lambda.imag() > band) continue;
            const double d = p.mode.log_decrement();
            if (d < out.log_dec) out.log_dec = d, out.speed = p.speed, out.branch = &b;
        }
    return out;
}

// min_log_dec: the least log decrement and its speed into the columns after the
// onset; below the limit, stability fails (an unstable mode's reason gains it).
void check_log_dec(const Sweep& s, const CampbellDiagram& cd, const StudyOptions& so, const StabilityCriterion& c,
                   bool unstable, std::size_t q, DesignResult& r) {
    // The modes in range: what the speeds and harmonics can excite (a mesh's highest
    // modes, barely damped by the bearings, are no stability margin to keep).
    const LeastLogDecrement ld = least_log_decrement(cd, judged_band(so.f_cut, so.speeds, so.harmonics));
    if (!ld.branch) return;   // no oscillating mode in range: nothing rings
    r.quantities[q] = ld.log_dec;
    r.quantities[q + 1] = ld.speed * s.unit.factor;
    if (!(ld.log_dec < *c.min_log_dec)) return;
    const std::string what = fmt::format("log decrement {:.4g} (mode {} at {:.6g} {}), required {:.4g}", ld.log_dec,
                                         ld.branch->id, ld.speed * s.unit.factor, s.unit.name, *c.min_log_dec);
    if (unstable) {
        r.reason += ", least " + what;
        return;
    }
    r.failed.push_back("stability");
    r.reason += fmt::format("{}stability: {}, short by {:.3g} (checked up to {:.6g} {})", r.reason.empty() ? "" : "; ",
                            what, *c.min_log_dec - ld.log_dec, c.up_to * s.unit.factor, s.unit.name);
}

// A mode above the band that grows: the first speed of `speeds` below `before` at which
// one does (Re lambda beyond its bound), refined by bisection to 1e-9 of the speed.
struct GrowingAbove {
    double speed = inf;
    double frequency = 0;
};

// The modes above the band need no tracking for a verdict: the full spectrum at a speed
// says whether any of them grows, whatever their order (tracking them through their
// crossings would insert thousands of speeds on a mesh's highest modes).
GrowingAbove growing_above_band(const GyroscopicSystem& sys, const EigenOptions& eig,
                                const std::vector<double>& speeds, double band, double before) {
    SpectrumSolver solve = dense_solver(sys, eig)();
    GrowingAbove out;
    const auto grows = [&](double w) {
        const QuadraticSpectrum sp = solve(w);
        for (const Mode& m : sp.modes)
            if (!within_band(m, band, sp.real_tol) && m.stability() == Stability::Unstable) {
                out.frequency = std::abs(m.lambda.imag()) > sp.real_tol ? m.lambda.imag() : 0.0;   // 0: diverges
                return true;
            }
        return false;
    };
    for (std::size_t k = 0; k < speeds.size() && speeds[k] < before; ++k) {
        throw_if_interrupted();
        if (!grows(speeds[k])) continue;
        double a = k > 0 ? speeds[k - 1] : speeds[k], b = speeds[k];
        while (b - a > 1e-9 * b) {
            const double m = 0.5 * (a + b);
            (grows(m) ? b : a) = m;
        }
        grows(b);   // the frequency at the refined onset
        out.speed = b;
        return out;
    }
    return out;
}

void check_stability(const Sweep& s, const Scene& sc, const StabilityCriterion& c, std::size_t& q,
                     DesignResult& r) {
    // The stability study of the CLI and Python, but a design is judged on every mode
    // unless the scene names a number: the modes in range are tracked, and those above
    // the band are covered by the energy bound where it shows that none of them can grow
    // (symmetric stiffness, damping that dissipates); else a dense model's full spectrum
    // at each speed judges them (growing_above_band), a sparse model's window every mode.
    StudyOptions so = study_options(sc);
    so.workers = 1;   // the designs run in parallel, each on one worker
    so.speeds = SpeedRange{0.0, c.up_to, c.count}.points();
    const double band = judged_band(so.f_cut, so.speeds, so.harmonics);
    bool scan_above = false;
    if (so.solver.modes == kModesInRange && !modes_above_band_decay(sc.system, so.speeds, band)) {
        if (resolve_solver_kind(sc.dofs(), so.solver.kind, so.solver.modes) == SolverKind::Dense)
            scan_above = true;
        else
            so.solver.modes = 0;
    }
    const StabilityStudy st = stability_study(sc.system, so);
    const CampbellDiagram& cd = st.tracked.diagram;
    const std::vector<StabilityChange>& changes = st.changes;
    double onset = inf;
    const Branch* which = nullptr;
    for (const auto* list : {&cd.branches, &cd.untracked})   // the shown modes and the others judged
        for (const Branch& b : *list) {
        for (std::size_t k = 0; k < b.points.size(); ++k) {
            const Mode& m = b.points[k].mode;
            // The library's rule: Re lambda beyond its error bound (rounding is neutral).
            if (m.stability() != Stability::Unstable) continue;
            double w = b.points[k].speed;
            if (k > 0)
                for (const auto& ch : changes)
                    if (ch.branch == b.id && ch.becomes_unstable && ch.speed <= b.points[k].speed) w = ch.speed;
            if (w < onset) onset = w, which = &b;
            break;
        }
    }
    const GrowingAbove above = scan_above ? growing_above_band(sc.system, so.solver.eig, so.speeds, band, onset) : GrowingAbove{};
    if (above.speed < onset) {
        r.quantities[q] = above.speed * s.unit.factor;
        r.failed.push_back("stability");
        const std::string what = above.frequency > 0.0
                                     ? fmt::format("a mode above the range ({:.6g} {} at the onset)",
                                                   above.frequency * s.unit.factor, s.unit.name)
                                     : std::string("a real eigenvalue above the range (divergence)");
        r.reason += fmt::format("{}stability: {} is unstable from {:.6g} {} (checked up to {:.6g} {})",
                                r.reason.empty() ? "" : "; ", what, above.speed * s.unit.factor, s.unit.name,
                                c.up_to * s.unit.factor, s.unit.name);
    } else if (which) {
        r.quantities[q] = onset * s.unit.factor;
        r.failed.push_back("stability");
        r.reason += fmt::format("{}stability: mode {} is unstable from {:.6g} {} (checked up to {:.6g} {})",
                                r.reason.empty() ? "" : "; ", which->id, onset * s.unit.factor, s.unit.name,
                                c.up_to * s.unit.factor, s.unit.name);
    }
    if (c.min_log_dec) check_log_dec(s, cd, so, c, which != nullptr || above.speed < inf, q + 1, r);
    q += c.min_log_dec ? 3 : 1;
}

void check_pervasive(const Sweep& s, const Scene& sc, const PervasiveCriterion& c, std::size_t& q,
                     DesignResult& r) {
    const GyroscopicSystem& sys = sc.system;
    double first = inf;
    std::string lost_set;
    int lost_mode = 0;
    for (const auto& name : c.damping) {
        GyroscopicSystem one;
        if (name == "total") {
            if (!sys.has_damping()) {
                first = std::min(first, s.op_from);
                lost_set = "total (no damping in this design)";
                continue;
            }
            one = sys;
            // Constant damping: one component holding the total, so that the
            // Hautus test is not also run for every component.
            const bool constant = sys.bearings.empty() &&
                                  std::none_of(sys.damping.begin(), sys.damping.end(),
                                               [](const DampingComponent& d) { return bool(d.of_speed); });
            if (constant) {
                DampingComponent total;
                total.name = "total";
                total.D = sys.damping_matrix();
                one.damping = {total};
            }
        } else {
            const std::vector<std::string> names = sys.damping_names();
            const bool present = std::find(names.begin(), names.end(), name) != names.end();
            if (!present) {
                if (s.op_from < first) first = s.op_from, lost_set = name + " (zero in this design)";
                continue;
            }
            one = sys.with_damping_only({name});
        }
        PervasiveOptions po;
        po.tolerance = c.tolerance;
        po.modes = sc.modes;
        po.solver = sc.solver_options();   // the scene's choice, as for the other criteria
        const PervasiveReport rep = pervasive_damping(one, s.operating_speeds(), po);
        for (const auto& l : rep.losses)
            if (l.damping == "total" && l.speed < first) first = l.speed, lost_set = name, lost_mode = l.mode;
    }
    if (first < inf) {
        r.quantities[q] = first * s.unit.factor;
        r.failed.push_back("pervasive");
        r.reason += lost_mode > 0 ? fmt::format("{}pervasive: damping {} does not reach mode {} at {:.6g} {}",
                                                r.reason.empty() ? "" : "; ", lost_set, lost_mode,
                                                first * s.unit.factor, s.unit.name)
                                  : fmt::format("{}pervasive: damping {} is missing", r.reason.empty() ? "" : "; ",
                                                lost_set);
    }
    q += 1;
}

// The outputs the response criterion reads: the chosen DOFs (dofs: their indices),
// or the probes, each a column of its own (probes: resolved in this design's model).
struct ResponseOutputs {
    std::vector<int> dofs;
    std::vector<Probe> probes;
    std::string name(const GyroscopicSystem& sys, int k) const {
        return probes.empty() ? "|" + sys.dof_names.at(static_cast<std::size_t>(k)) + "|"
                              : "probe " + probes.at(static_cast<std::size_t>(k)).name;
    }
};

ResponseOutputs response_outputs(const GyroscopicSystem& sys, const ResponseCriterion& c) {
    ResponseOutputs o;
    for (const ResponseProbe& p : c.probes) {
        try {
            o.probes.push_back(resolve_probe(p, sys));
        } catch (const InputError& e) {
            throw InputError(fmt::format("[criteria.response] probe '{}' in this design: {}", p.name, e.what()));
        }
    }
    if (!o.probes.empty()) return o;
    for (int k = 0; k < sys.size(); ++k)
        if (c.dofs.empty() || std::find(c.dofs.begin(), c.dofs.end(), sys.dof_names.at(k)) != c.dofs.end())
            o.dofs.push_back(k);
    if (o.dofs.empty()) throw InputError("[criteria.response] dofs: none of them is a DOF of this design");
    return o;
}

void check_response(const Sweep& s, const Scene& sc, const ResponseCriterion& c, std::size_t& q,
                    DesignResult& r) {
    const GyroscopicSystem& sys = sc.system;
    const ResponseOutputs out = response_outputs(sys, c);
    // The largest amplitude of the chosen DOFs or probes, peaks refined between grid
    // speeds (as `gyrokit response`); an undamped resonance is unbounded (+inf) and fails.
    // A probe's reading is one more output: its peak is refined on its own amplitude.
    const ResponseSolver solve = [&](double w) -> Eigen::VectorXcd {
        const Eigen::VectorXcd Z = unbalance_response(sys, w);
        if (out.probes.empty()) return Z;
        Eigen::VectorXcd reading(static_cast<Eigen::Index>(out.probes.size()));
        for (std::size_t k = 0; k < out.probes.size(); ++k)
            reading(static_cast<Eigen::Index>(k)) = probe_response(out.probes[k], Z);
        return reading;
    };
    const int size = out.probes.empty() ? sys.size() : static_cast<int>(out.probes.size());
    const ResponseCurve rc = unbalance_response(solve, size, s.operating_speeds(), out.dofs);
    double amax = -1, wmax = 0;
    int kmax = 0;
    for (const auto& m : response_maxima(rc, response_extrema(solve, rc, true)))
        if (m.amplitude > amax) amax = m.amplitude, wmax = m.speed, kmax = m.dof;
    r.quantities[q] = amax;
    r.quantities[q + 1] = wmax * s.unit.factor;
    if (!out.probes.empty()) {
        const std::vector<std::string> lc = label_columns(s);
        const auto l = std::find(lc.begin(), lc.end(), "max_amplitude_probe") - lc.begin();
        r.labels.at(static_cast<std::size_t>(l)) = out.probes.at(static_cast<std::size_t>(kmax)).name;
    }
    if (amax > c.max_amplitude) {
        r.failed.push_back("response");
        r.reason += std::isinf(amax)
                        ? fmt::format("{}response: {} is unbounded at {:.6g} {} (an undamped resonance)",
                                      r.reason.empty() ? "" : "; ", out.name(sys, kmax), wmax * s.unit.factor,
                                      s.unit.name)
                        : fmt::format("{}response: {} = {:.4g} at {:.6g} {} exceeds {:.4g}", r.reason.empty() ? "" : "; ",
                                      out.name(sys, kmax), amax, wmax * s.unit.factor, s.unit.name, c.max_amplitude);
    }
    q += 2;
}

std::string one_line(std::string m) {
    std::replace(m.begin(), m.end(), '\n', ' ');
    std::replace(m.begin(), m.end(), '\r', ' ');
    return m;
}

}  // namespace

std::string to_string(Verdict v) {
    switch (v) {
        case Verdict::Pass: return "pass";
        case Verdict::Fail: return "fail";
        default: return "error";
    }
}

std::vector<std::string> quantity_columns(const Sweep& s) {
    std::vector<std::string> c;
    // Speeds in the sweep's unit, named with it (critical_speed_rad_s, ..._hz, ..._rpm).
    if (s.criteria.separation) c.insert(c.end(), {s.unit.column("critical_speed"), "separation_percent"});
    if (s.criteria.separation && s.criteria.separation->api684)
        c.insert(c.end(), {"required_separation_percent", "amplification_factor"});
    if (s.criteria.separation && s.criteria.separation->max_amplification)
        c.insert(c.end(), {"max_amplification_factor", s.unit.column("max_amplification_speed")});
    if (s.criteria.stability) c.push_back(s.unit.column("instability_onset"));
    if (s.criteria.stability && s.criteria.stability->min_log_dec)
        c.insert(c.end(), {"min_log_dec", s.unit.column("min_log_dec_speed")});
    if (s.criteria.pervasive) c.push_back(s.unit.column("pervasive_loss"));
    if (s.criteria.response) c.insert(c.end(), {"max_amplitude", s.unit.column("max_amplitude_speed")});
    return c;
}

std::vector<std::string> label_columns(const Sweep& s) {
    if (s.criteria.response && !s.criteria.response->probes.empty()) return {"max_amplitude_probe"};
    return {};
}

std::vector<std::string> result_columns(const Sweep& s) {
    std::vector<std::string> c{"design"};
    for (const auto& p : s.parameters) c.push_back(p.name);
    for (const auto& q : quantity_columns(s)) c.push_back(q);
    for (const auto& l : label_columns(s)) c.push_back(l);
    c.insert(c.end(), {"verdict", "failed", "reason"});
    return c;
}

DesignResult evaluate_design(const Sweep& s, std::size_t i) {
    DesignResult r;
    r.index = i;
    r.parameters = s.design(i);
    const std::vector<std::string> qc = quantity_columns(s);
    r.quantities.assign(qc.size(), std::nullopt);
    r.labels.assign(label_columns(s).size(), std::string());
    Scene sc;
    try {
        sc = s.loader(design_overrides(s, r.parameters));
    } catch (const Interrupted&) {
        throw;   // not a property of the design
    } catch (const std::exception& e) {
        r.verdict = Verdict::Error;
        r.reason = one_line(std::string("invalid parameters: ") + e.what());
        return r;
    }
    try {
        std::size_t q = 0;
        const Criteria& c = s.criteria;
        if (c.separation) check_separation(s, sc, *c.separation, q, r);
        if (c.stability) check_stability(s, sc, *c.stability, q, r);
        if (c.pervasive) check_pervasive(s, sc, *c.pervasive, q, r);
        if (c.response) check_response(s, sc, *c.response, q, r);
        // +inf only as the amplitude at an undamped resonance or the amplification factor of an
        // undamped mode; anything else non-finite is a failure.
        for (std::size_t k = 0; k < qc.size(); ++k)
            if (r.quantities[k] && !std::isfinite(*r.quantities[k]) &&
                !((qc[k] == "max_amplitude" || qc[k] == "amplification_factor" || qc[k] == "max_amplification_factor") &&
                  *r.quantities[k] > 0.0))
                throw SolverError(qc[k] + " is not finite");
    } catch (const Interrupted&) {
        throw;
    } catch (const std::exception& e) {
        r.verdict = Verdict::Error;
        r.failed.clear();
        r.quantities.assign(qc.size(), std::nullopt);
        r.labels.assign(r.labels.size(), std::string());
        r.reason = one_line(std::string("analysis failed: ") + e.what());
        return r;
    }
    r.verdict = r.failed.empty() ? Verdict::Pass : Verdict::Fail;
    if (r.failed.empty()) r.reason = "all criteria met";
    r.reason = one_line(r.reason);
    return r;
}

}  // namespace gyrokit
