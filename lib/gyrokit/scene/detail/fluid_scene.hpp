// Reader of [model] type = "fluid_rotor" (liquid-filled rotor) scene tables.
#pragma once

#include "gyrokit/scene/toml_keys.hpp"
#include <gyrokit/models/fluid_rotor.hpp>

namespace gyrokit {

// Every key range-checked, unknown keys rejected, R0 >= R rejected naming both.
FluidRotorParameters fluid_rotor_from(const TomlKeys& k);

}  // namespace gyrokit
