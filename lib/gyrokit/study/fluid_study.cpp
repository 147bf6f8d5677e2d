#include <gyrokit/study/fluid_study.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/study/request.hpp>

#include <fmt/format.h>

#include <cmath>

namespace gyrokit {

FluidStudy fluid_study(const Scene& scene, const FluidRequest& rq) {
    if (!scene.fluid())
        throw InputError(fmt::format("{}: [model] type = '{}'; the fluid analysis needs type = \"fluid_rotor\"",
                                     scene.path, scene.model_type()));
    FluidStudy st;
    st.unit = resolve_unit(scene, rq.unit);
    const FluidRotorParameters& p = *scene.fluid();
    st.rotor = build_fluid_rotor(p);
    if (!rq.fill) {
        st.critical = fluid_critical_speeds(st.rotor);
        return st;
    }
    if (rq.fill->empty())
        throw InputError(fmt::format("{} (none): allowed: one or more radii 0 < R0 < R = {} (m)", option_field("fill"),
                                     p.R));
    for (const double r0 : *rq.fill)
        if (!(std::isfinite(r0) && r0 > 0.0 && r0 < p.R))
            throw InputError(fmt::format("{} R0 = {}: allowed: 0 < R0 < R = {} (m)", option_field("fill"), r0, p.R));
    st.sweep = fill_sweep(p, *rq.fill);
    if (st.sweep->skipped)
        st.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Solver,
                                  fmt::format("{} fill levels lie exactly at a sloshing resonance", st.sweep->skipped)});
    return st;
}

}  // namespace gyrokit
