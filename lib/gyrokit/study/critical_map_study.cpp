#include <gyrokit/study/critical_map_study.hpp>

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

namespace gyrokit {

CriticalSpeedMap critical_map_study(const Scene& scene, const CriticalSpeedMapOptions& options) {
    if (!scene.rotor_model())
        throw InputError(fmt::format("{}: a critical speed map of a [model] of type {}; allowed: an fe_rotor model",
                                     scene.path, scene.model_type()));
    return critical_speed_map(*scene.rotor_model(), options);
}

}  // namespace gyrokit
