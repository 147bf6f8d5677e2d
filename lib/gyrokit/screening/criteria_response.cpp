// The pervasive-damping and unbalance-response criteria.
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
        po.modes = sc.solver.modes;
        po.f_cut = sc.analysis.f_cut;   // the modes judged, as by the stability criteria
        po.solver = sc.solver;   // the scene's choice, as for the other criteria
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
        return probes.empty() ? "|" + sys.dofs.names.at(static_cast<std::size_t>(k)) + "|"
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
        if (c.dofs.empty() || std::find(c.dofs.begin(), c.dofs.end(), sys.dofs.names.at(k)) != c.dofs.end())
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

}  // namespace gyrokit::screening_detail
