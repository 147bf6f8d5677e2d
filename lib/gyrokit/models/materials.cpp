#include <gyrokit/models/materials.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/constants.hpp>

#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

const std::vector<Material>& standard_materials() {
    // Steel as ROSS and Friswell et al. use it (E = 211 GPa, G = 81.2 GPa: nu = E/2G - 1).
    static const std::vector<Material> table = {
        {"steel", 211e9, 211e9 / (2 * 81.2e9) - 1, 7810.0,
         "Friswell et al., Dynamics of Rotating Machines (2010), ch. 5 examples; ROSS's steel"},
        {"stainless", 193e9, 0.29, 8000.0, "AISI 304 annealed, ASM Handbook vol. 1"},
        {"aluminium", 68.9e9, 0.33, 2700.0, "6061-T6, ASM Handbook vol. 2"},
        {"titanium", 113.8e9, 0.342, 4430.0, "Ti-6Al-4V annealed, ASM Handbook vol. 2"},
    };
    return table;
}

Material find_material(const std::string& name, const std::vector<Material>& extra, const std::string& origin) {
    std::string names;
    for (const auto* list : {&extra, &standard_materials()})
        for (const Material& m : *list) {
            if (m.name == name) return m;
            names += (names.empty() ? "" : ", ") + m.name;
        }
    throw InputError(fmt::format("{} = '{}' is unknown; allowed: {}", origin, name, names));
}

DiskInertia disk_inertia(double Do, double Di, double w, double rho) {
    DiskInertia d;
    const double s = Do * Do + Di * Di;
    d.mass = rho * kPi * (Do * Do - Di * Di) * w / 4.0;
    d.polar_inertia = d.mass * s / 8.0;
    d.diametral_inertia = d.mass * (3.0 * s / 4.0 + w * w) / 12.0;
    return d;
}

}  // namespace gyrokit
