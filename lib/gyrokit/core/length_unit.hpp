// How a scene states lengths ([model] length_unit = "m" | "mm"). Every value inside
// gyrokit is in metres; what a person types (an axial position) is read in the scene's
// unit, and tables and figures print lengths in it.
#pragma once

#include <string>
#include <vector>

namespace gyrokit {

struct LengthUnit {
    std::string name = "m";
    double metres = 1.0;   // metres per unit
    // "m" or "mm"; InputError naming the value and the allowed ones.
    static LengthUnit parse(const std::string& name);
    double in_unit(double metres_value) const { return metres_value / metres; }
    double to_metres(double value) const { return value * metres; }
    // A column name that records the unit: "z" -> z_m, z_mm.
    std::string column(const std::string& base) const { return base + "_" + name; }
    // A DOF's value as printed: a length ("m") in this unit, any other unit (rad) as it is.
    double display_factor(const std::string& dof_unit) const { return dof_unit == "m" ? 1.0 / metres : 1.0; }
    std::string display_unit(const std::string& dof_unit) const { return dof_unit == "m" ? name : dof_unit; }
    std::vector<std::string> display_units(const std::vector<std::string>& dof_units) const {
        std::vector<std::string> out;
        for (const std::string& u : dof_units) out.push_back(display_unit(u));
        return out;
    }
};

}  // namespace gyrokit
