#include <gyrokit/study/frf_study.hpp>

#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/response_reports.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gyrokit {

FrfStudy frf_study(const Scene& scene, const RotorRequest& common, const FrfRequest& rq) {
    const GyroscopicSystem& sys = scene.system;
    const StudyOptions so = resolve_request(scene, common, SpeedsNeeded::No);
    FrfStudy st;
    st.unit = so.unit;
    const std::vector<std::string>& names = sys.dofs.names;
    const auto in = std::find(names.begin(), names.end(), rq.input);
    if (in == names.end())
        throw InputError(fmt::format("{} '{}': not a DOF of the model; allowed: names such as {}",
                                     option_field("input"), rq.input, names.empty() ? std::string("-") : names.front()));
    const int input = static_cast<int>(in - names.begin());
    if (!rq.dofs.empty() && !rq.probes.empty())
        throw InputError(option_field("dofs") + " and " + option_field("probes") + ": allowed: one of them");
    std::vector<int> outputs = rq.probes.empty() ? dofs_by_name(rq.dofs, names, option_field("dofs")) : probe_dofs(rq.probes);
    if (outputs.empty()) outputs.push_back(input);   // the driving point
    const double spin = to_rad_s(rq.speed.value_or(0.0), "speed", "number", so.unit);
    std::vector<double> w;
    if (rq.frequencies) {
        if (rq.frequencies->empty())
            throw InputError(fmt::format("{} (none): allowed: one or more frequencies >= 0 ({})",
                                         option_field("frequencies"), so.unit.name));
        for (const double f : *rq.frequencies) w.push_back(to_rad_s(f, "frequencies", "number", so.unit));
    } else {
        w = so.speeds;   // the scene's [speeds] grid
        if (w.empty())
            throw InputError(fmt::format("{}no frequencies; give {} ({}) or a [speeds] table in the scene",
                                         scene.path.empty() ? "" : scene.path + ": ", option_field("frequencies"),
                                         so.unit.name));
    }
    add_notes(st.diagnostics, Diagnostic::Topic::Extrapolation, extrapolation_notes(sys.bearings, spin, spin));
    FrequencyResponse r = frequency_response(sys, spin, w, input, outputs, so.solver.kind);
    // Probes: their readings are the outputs, named as given.
    st.named = ProbeOutputs{sys.dofs.names, sys.dofs.units, {}};
    if (!rq.probes.empty()) {
        st.named = probe_outputs(sys, rq.probes);
        r.H = probe_readings(rq.probes, r.outputs, r.H);
        r.outputs = st.named.outputs;
    }
    st.si = r.H;
    to_length_unit(r.outputs, r.H, st.named.units, scene.length_unit());   // mm in an mm scene
    st.response = std::move(r);
    return st;
}

}  // namespace gyrokit
