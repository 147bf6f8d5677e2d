#include <gyrokit/study/static_study.hpp>

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace gyrokit {

StaticResult static_study(const Scene& scene, StaticOptions options) {
    if (!scene.fe_rotor())
        throw InputError(fmt::format("{}: static analysis of a [model] of type {}; allowed: an fe_rotor model",
                                     scene.path, scene.model_type()));
    const GyroscopicSystem& sys = scene.system;
    // Every bearing named by its number in the scene's list, whatever its kind.
    const BearingNumbers numbers = bearing_numbers(*scene.rotor_model());
    options.bearing_names.clear();
    for (const int n : numbers.constant) options.bearing_names.push_back(bearing_name(n));
    const std::size_t rigid_before = options.rigid.size();
    for (std::size_t j = 0; j < sys.bearings.size(); ++j) {
        const BearingTable& b = sys.bearings[j];
        const std::string name = bearing_name(numbers.speed_dependent.at(j));
        if (b.pedestal_x >= 0 || sys.dofs.on_pedestal(b.dof_x))
            throw InputError(fmt::format("{}: {} ({}) is speed-dependent and stands on a pedestal; allowed in a "
                                         "static analysis: constant bearings on pedestals",
                                         scene.path, name, b.label()));
        options.rigid.push_back({sys.dofs.nodes[static_cast<std::size_t>(b.dof_x)], name});
    }
    StaticResult r = fe_static(*scene.fe_rotor(), options);
    // The bearings first, in the scene's order (the speed-dependent ones are held rigid, listed
    // after the supports by fe_static), then pedestals, supports and other holds as listed.
    const std::size_t constant = numbers.constant.size();
    const std::size_t films_at = r.reactions.size() - (options.rigid.size() - rigid_before);
    std::vector<std::pair<int, StaticReaction>> bearings;
    for (std::size_t i = 0; i < constant; ++i) bearings.emplace_back(numbers.constant[i], r.reactions[i]);
    for (std::size_t j = 0; j < sys.bearings.size(); ++j)
        bearings.emplace_back(numbers.speed_dependent[j], r.reactions[films_at + j]);
    std::sort(bearings.begin(), bearings.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<StaticReaction> ordered;
    for (auto& b : bearings) ordered.push_back(std::move(b.second));
    for (std::size_t i = constant; i < films_at; ++i) ordered.push_back(r.reactions[i]);
    r.reactions = std::move(ordered);
    return r;
}

}  // namespace gyrokit
