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
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/response_study.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <stdexcept>

namespace gyrokit {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// A criterion filling a column it did not declare: the code's error, never a design's.
struct UndeclaredColumn : std::logic_error {
    using std::logic_error::logic_error;
};

// One design's row as its criteria fill it: each value by the name of a column the
// criterion declared (a name it did not declare is a bug, not a design's failure).
class Row {
public:
    Row(DesignResult& r, const std::vector<std::string>& quantities, const std::vector<std::string>& labels)
        : result(r), quantities_(quantities), labels_(labels) {}
    void set(const std::string& column, double value) { result.quantities.at(index(quantities_, column)) = value; }
    void label(const std::string& column, std::string text) { result.labels.at(index(labels_, column)) = std::move(text); }
    // A criterion not met: its name in `failed`, "name: text" in the reason.
    void fail(const std::string& criterion, const std::string& text) {
        result.failed.push_back(criterion);
        result.reason += (result.reason.empty() ? "" : "; ") + criterion + ": " + text;
    }
    DesignResult& result;

private:
    static std::size_t index(const std::vector<std::string>& columns, const std::string& name) {
        const auto it = std::find(columns.begin(), columns.end(), name);
        if (it == columns.end()) throw UndeclaredColumn("screening: column " + name + " is not declared");
        return static_cast<std::size_t>(it - columns.begin());
    }
    const std::vector<std::string>& quantities_;
    const std::vector<std::string>& labels_;
};

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
                   bool unstable, Row& row) {
    // The modes in range: what the speeds and harmonics can excite (a mesh's highest
    // modes, barely damped by the bearings, are no stability margin to keep).
    const LeastLogDecrement ld = least_log_decrement(cd, judged_band(so.f_cut, so.speeds, so.harmonics));
    if (!ld.branch) return;   // no oscillating mode in range: nothing rings
    row.set("min_log_dec", ld.log_dec);
    row.set(s.unit.column("min_log_dec_speed"), ld.speed * s.unit.factor);
    if (!(ld.log_dec < *c.min_log_dec)) return;
    const std::string what = fmt::format("log decrement {:.4g} (mode {} at {:.6g} {}), required {:.4g}", ld.log_dec,
                                         ld.branch->id, ld.speed * s.unit.factor, s.unit.name, *c.min_log_dec);
    if (unstable) {
        row.result.reason += ", least " + what;
        return;
    }
    row.fail("stability", fmt::format("{}, short by {:.3g} (checked up to {:.6g} {})",
                                      what, *c.min_log_dec - ld.log_dec, c.up_to * s.unit.factor, s.unit.name));
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

void check_stability(const Sweep& s, const Scene& sc, const StabilityCriterion& c, Row& row) {
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
        row.set(s.unit.column("instability_onset"), above.speed * s.unit.factor);
        const std::string what = above.frequency > 0.0
                                     ? fmt::format("a mode above the range ({:.6g} {} at the onset)",
                                                   above.frequency * s.unit.factor, s.unit.name)
                                     : std::string("a real eigenvalue above the range (divergence)");
        row.fail("stability", fmt::format("{} is unstable from {:.6g} {} (checked up to {:.6g} {})", what,
                                          above.speed * s.unit.factor, s.unit.name, c.up_to * s.unit.factor,
                                          s.unit.name));
    } else if (which) {
        row.set(s.unit.column("instability_onset"), onset * s.unit.factor);
        row.fail("stability", fmt::format("mode {} is unstable from {:.6g} {} (checked up to {:.6g} {})", which->id,
                                          onset * s.unit.factor, s.unit.name, c.up_to * s.unit.factor, s.unit.name));
    }
    if (c.min_log_dec) check_log_dec(s, cd, so, c, which != nullptr || above.speed < inf, row);
}

void check_pervasive(const Sweep& s, const Scene& sc, const PervasiveCriterion& c, Row& row) {
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
        po.solver = solver_options(sc);   // the scene's choice, as for the other criteria
        const PervasiveReport rep = pervasive_damping(one, s.operating_speeds(), po);
        for (const auto& l : rep.losses)
            if (l.damping == "total" && l.speed < first) first = l.speed, lost_set = name, lost_mode = l.mode;
    }
    if (first < inf) {
        row.set(s.unit.column("pervasive_loss"), first * s.unit.factor);
        row.fail("pervasive", lost_mode > 0 ? fmt::format("damping {} does not reach mode {} at {:.6g} {}", lost_set,
                                                          lost_mode, first * s.unit.factor, s.unit.name)
                                            : fmt::format("damping {} is missing", lost_set));
    }
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

void check_response(const Sweep& s, const Scene& sc, const ResponseCriterion& c, Row& row) {
    const GyroscopicSystem& sys = sc.system;
    const ResponseOutputs out = response_outputs(sys, c);
    // The largest amplitude of the chosen DOFs or probes, in SI, peaks refined between
    // grid speeds: the study of `gyrokit response` over the operating speeds (without its
    // stability warning, the stability criterion's concern); an undamped resonance is
    // unbounded (+inf) and fails. A probe's peak is refined on its own reading.
    StudyOptions so = study_options(sc);
    so.workers = 1;   // the designs run in parallel, each on one worker
    so.speeds = s.operating_speeds();
    ResponseRequest rq;
    rq.outputs = out.dofs;
    rq.probes = out.probes;
    rq.stability_check = false;
    const ResponseStudy st = response_study(sys, so, rq);
    double amax = -1, wmax = 0;
    int kmax = 0;
    for (const auto& m : st.maxima)
        if (m.amplitude > amax) amax = m.amplitude, wmax = m.speed, kmax = m.dof;
    row.set("max_amplitude", amax);
    row.set(s.unit.column("max_amplitude_speed"), wmax * s.unit.factor);
    if (!out.probes.empty()) row.label("max_amplitude_probe", out.probes.at(static_cast<std::size_t>(kmax)).name);
    if (amax > c.max_amplitude)
        row.fail("response", std::isinf(amax)
                                 ? fmt::format("{} is unbounded at {:.6g} {} (an undamped resonance)", out.name(sys, kmax),
                                               wmax * s.unit.factor, s.unit.name)
                                 : fmt::format("{} = {:.4g} at {:.6g} {} exceeds {:.4g}", out.name(sys, kmax), amax,
                                               wmax * s.unit.factor, s.unit.name, c.max_amplitude));
}

// A criterion of the sweep: the columns it declares, in order, and its check, which
// fills them by name (Row).
class Criterion {
public:
    virtual ~Criterion() = default;
    virtual std::vector<std::string> quantities() const = 0;
    virtual std::vector<std::string> labels() const { return {}; }
    virtual void check(const Scene& sc, Row& row) const = 0;
};

class Separation final : public Criterion {
public:
    Separation(const Sweep& s, const SeparationCriterion& c) : s_(s), c_(c) {}
    std::vector<std::string> quantities() const override {
        // Speeds in the sweep's unit, named with it (critical_speed_rad_s, ..._hz, ..._rpm).
        std::vector<std::string> q{s_.unit.column("critical_speed"), "separation_percent"};
        if (c_.api684) q.insert(q.end(), {"required_separation_percent", "amplification_factor"});
        if (c_.max_amplification)
            q.insert(q.end(), {"max_amplification_factor", s_.unit.column("max_amplification_speed")});
        return q;
    }
    void check(const Scene& sc, Row& row) const override { check_separation(s_, sc, c_, row); }

private:
    const Sweep& s_;
    const SeparationCriterion& c_;
};

class Stability final : public Criterion {
public:
    Stability(const Sweep& s, const StabilityCriterion& c) : s_(s), c_(c) {}
    std::vector<std::string> quantities() const override {
        std::vector<std::string> q{s_.unit.column("instability_onset")};
        if (c_.min_log_dec) q.insert(q.end(), {"min_log_dec", s_.unit.column("min_log_dec_speed")});
        return q;
    }
    void check(const Scene& sc, Row& row) const override { check_stability(s_, sc, c_, row); }

private:
    const Sweep& s_;
    const StabilityCriterion& c_;
};

class Pervasive final : public Criterion {
public:
    Pervasive(const Sweep& s, const PervasiveCriterion& c) : s_(s), c_(c) {}
    std::vector<std::string> quantities() const override { return {s_.unit.column("pervasive_loss")}; }
    void check(const Scene& sc, Row& row) const override { check_pervasive(s_, sc, c_, row); }

private:
    const Sweep& s_;
    const PervasiveCriterion& c_;
};

class Response final : public Criterion {
public:
    Response(const Sweep& s, const ResponseCriterion& c) : s_(s), c_(c) {}
    std::vector<std::string> quantities() const override {
        return {"max_amplitude", s_.unit.column("max_amplitude_speed")};
    }
    // With probes: the probe that read the largest amplitude.
    std::vector<std::string> labels() const override {
        return c_.probes.empty() ? std::vector<std::string>{} : std::vector<std::string>{"max_amplitude_probe"};
    }
    void check(const Scene& sc, Row& row) const override { check_response(s_, sc, c_, row); }

private:
    const Sweep& s_;
    const ResponseCriterion& c_;
};

// The sweep's criteria in the order of their columns.
std::vector<std::unique_ptr<Criterion>> criteria_of(const Sweep& s) {
    std::vector<std::unique_ptr<Criterion>> out;
    const Criteria& c = s.criteria;
    if (c.separation) out.push_back(std::make_unique<Separation>(s, *c.separation));
    if (c.stability) out.push_back(std::make_unique<Stability>(s, *c.stability));
    if (c.pervasive) out.push_back(std::make_unique<Pervasive>(s, *c.pervasive));
    if (c.response) out.push_back(std::make_unique<Response>(s, *c.response));
    return out;
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
    for (const auto& k : criteria_of(s))
        for (std::string& q : k->quantities()) c.push_back(std::move(q));
    return c;
}

std::vector<std::string> label_columns(const Sweep& s) {
    std::vector<std::string> c;
    for (const auto& k : criteria_of(s))
        for (std::string& l : k->labels()) c.push_back(std::move(l));
    return c;
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
    const std::vector<std::string> qc = quantity_columns(s), lc = label_columns(s);
    r.quantities.assign(qc.size(), std::nullopt);
    r.labels.assign(lc.size(), std::string());
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
        Row row(r, qc, lc);
        for (const auto& k : criteria_of(s)) k->check(sc, row);
        // +inf only as the amplitude at an undamped resonance or the amplification factor of an
        // undamped mode; anything else non-finite is a failure.
        for (std::size_t k = 0; k < qc.size(); ++k)
            if (r.quantities[k] && !std::isfinite(*r.quantities[k]) &&
                !((qc[k] == "max_amplitude" || qc[k] == "amplification_factor" || qc[k] == "max_amplification_factor") &&
                  *r.quantities[k] > 0.0))
                throw SolverError(qc[k] + " is not finite");
    } catch (const Interrupted&) {
        throw;
    } catch (const UndeclaredColumn&) {
        throw;   // the code's error, not the design's
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
