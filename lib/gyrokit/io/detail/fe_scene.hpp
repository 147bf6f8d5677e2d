// Reader of [model] type = "fe_rotor" scene tables: a finite-element rotor
// described by its geometry and material (see docs/scene_format.md).
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include "gyrokit/io/detail/toml_keys.hpp"

#include <string>

namespace gyrokit {

// Builds and assembles the rotor. Positions (z, m) of disks, bearings and
// supports must fall on a node (section ends and their subdivisions); bearing
// tables are read relative to `dir`. Every error names the table entry, key,
// value and allowed range.
// The rotor's description goes to `rotor` if given.
GyroscopicSystem fe_rotor_from(const TomlKeys& k, const std::string& dir, FeRotor* rotor = nullptr);

}  // namespace gyrokit
