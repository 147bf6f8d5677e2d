#include <gyrokit/study/static_study.hpp>

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

namespace gyrokit {

StaticResult static_study(const Scene& scene, StaticOptions options) {
    if (!scene.fe_rotor())
        throw InputError(fmt::format("{}: static analysis of a [model] of type {}; allowed: an fe_rotor model",
                                     scene.path, scene.model_type()));
    const GyroscopicSystem& sys = scene.system;
    for (const BearingTable& b : sys.bearings) {
        if (b.pedestal_x >= 0 || sys.dofs.on_pedestal(b.dof_x))
            throw InputError(fmt::format("{}: bearing {} is speed-dependent and stands on a pedestal; allowed in a "
                                         "static analysis: constant bearings on pedestals",
                                         scene.path, b.name));
        options.rigid.push_back({sys.dofs.nodes[static_cast<std::size_t>(b.dof_x)], b.label()});
    }
    return fe_static(*scene.fe_rotor(), options);
}

}  // namespace gyrokit
