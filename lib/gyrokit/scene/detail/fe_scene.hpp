// Reader of [model] type = "fe_rotor" scene tables: a finite-element rotor
// described by its geometry and material (see docs/scene_format.md).
#pragma once

#include <gyrokit/models/rotor_model.hpp>

#include "gyrokit/scene/toml_keys.hpp"

#include <string>

namespace gyrokit {

// The rotor's description: every key checked (the error names the table entry, key,
// value and allowed range); bearing tables are read relative to `dir`. Positions are
// checked against the mesh when it is built (build(RotorModel)).
RotorModel rotor_model_from(const TomlKeys& k, const std::string& dir);

}  // namespace gyrokit
