// Criteria evaluation of one design.
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

namespace gyrokit {

namespace {

using namespace screening_detail;

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
