#include "gyrokit/scene/detail/fluid_scene.hpp"

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

namespace gyrokit {

FluidRotorParameters fluid_rotor_from(const TomlKeys& k) {
    k.only({"type", "R", "R0", "a", "l", "rho", "nu", "c1", "c2", "c11", "m0", "I0", "J0", "e", "modes", "tolerance",
            "jstar_terms"});
    FluidRotorParameters p;
    p.R = k.number("R", std::nullopt, 0, true, "m");
    p.R0 = k.number("R0", std::nullopt, 0, true, "m");
    if (!(p.R0 < p.R))
        throw InputError(fmt::format("{} = {} is not below R = {}; allowed: 0 < R0 < R (m)", k.where("R0"), p.R0, p.R));
    p.a = k.number("a", std::nullopt, 0, true, "m");
    p.l = k.number("l", std::nullopt, 0, true, "m");
    p.rho = k.number("rho", std::nullopt, 0, false, "kg/m^3");
    p.nu = k.number("nu", 0.0, 0, false, "m^2/s");
    p.c1 = k.number("c1", std::nullopt, 0, true, "N/m");
    p.c2 = k.number("c2", std::nullopt, 0, true, "N/m");
    p.c11 = k.number("c11", std::nullopt, 0, true, "N/m");
    p.m0 = k.number("m0", std::nullopt, 0, true, "kg");
    p.I0 = k.number("I0", std::nullopt, 0, false, "kg m^2");
    p.J0 = k.number("J0", std::nullopt, 0, true, "kg m^2");
    p.e = k.number("e", 0.0, 0, false, "m");
    p.modes = static_cast<int>(k.integer("modes", 0, 1, 100000));
    if (p.modes == 0) {
        p.tolerance = k.number("tolerance", 1e-10, 0, true, "relative contribution to the equivalent inertia");
        if (p.tolerance >= 1)
            throw InputError(fmt::format("{} = {}: out of range; allowed: 0 < tolerance < 1", k.where("tolerance"),
                                         p.tolerance));
    } else if (k.has("tolerance")) {
        throw InputError(k.where("tolerance") + " given together with modes; allowed: one of modes, tolerance");
    }
    p.jstar_terms = static_cast<int>(k.integer("jstar_terms", 0, 1, 10000000));
    return p;
}

}  // namespace gyrokit
