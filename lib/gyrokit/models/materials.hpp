// Named shaft and disk materials: a small table of common rotor materials
// (room temperature, handbook values; docs/fe_rotor.md lists the sources) and
// the solid of revolution a disk given by its geometry is.
#pragma once

#include <string>
#include <vector>

namespace gyrokit {

struct Material {
    std::string name;
    double youngs_modulus = 0.0;   // E, Pa
    double poisson_ratio = 0.0;    // nu
    double density = 0.0;          // kg/m^3
    std::string source;            // where the values come from
};

// steel, stainless, aluminium, titanium.
const std::vector<Material>& standard_materials();
// The material named `name` among `extra` (a scene's own) and the standard ones;
// InputError naming `origin` and the names there are otherwise.
Material find_material(const std::string& name, const std::vector<Material>& extra, const std::string& origin);

// A disk as a hollow cylinder: outer and inner diameter, width (m) and density.
struct DiskInertia {
    double mass = 0.0;               // m = rho pi (Do^2 - Di^2) w / 4
    double diametral_inertia = 0.0;  // Id = m (3 (Do^2 + Di^2) / 4 + w^2) / 12, about a diameter through the centre
    double polar_inertia = 0.0;      // Ip = m (Do^2 + Di^2) / 8
};
DiskInertia disk_inertia(double outer_diameter, double inner_diameter, double width, double density);

}  // namespace gyrokit
