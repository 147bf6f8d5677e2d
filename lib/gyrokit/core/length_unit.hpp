// How a scene states lengths ([model] length_unit = "m" | "mm"). Every value inside
// gyrokit is in metres; what a person types (an axial position) is read in the scene's
// unit, and tables and figures print lengths in it.
#pragma once

#include <string>

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
};

}  // namespace gyrokit
