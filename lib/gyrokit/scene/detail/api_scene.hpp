// The scene's [api] table: the machine data of the API 617 analyses.
#pragma once

#include <gyrokit/models/machine_stages.hpp>
#include <gyrokit/scene/scene.hpp>

#include "gyrokit/scene/toml_keys.hpp"

namespace gyrokit {

// [api]: speeds in the scene's [speeds] units, lengths in its length_unit; `sc` the
// scene read so far (its model, units). InputError naming the key, value and range.
ApiMachine api_machine_from(const TomlKeys& k, const toml::table& t, const Scene& sc);

}  // namespace gyrokit
