// Scene files (TOML): a model and the analysis settings. See docs/scene_format.md.
#pragma once

#include "core/gyroscopic_system.hpp"
#include "core/speed_range.hpp"
#include "models/fluid_rotor.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct Scene {
    std::string path;                  // the file it was read from
    std::string title;
    std::string model_type;            // "gyrostat" | "matrices" | "fluid_rotor"
    GyroscopicSystem system;
    std::optional<SpeedRange> speeds;  // [speeds] from, to, count
    int modes = 0;                     // [analysis] modes (0 = all)
    std::vector<int> harmonics{1};     // [analysis] harmonics
    std::optional<FluidRotorParameters> fluid;   // set for [model] type = "fluid_rotor"
};

// Reads and validates a scene. Every error is an InputError of one line naming
// the file, the key, the value and the allowed range. `overrides` replace
// numeric keys before validation, named TABLE.KEY (e.g. "model.c_G"): how a
// design study varies a base scene.
Scene load_scene(const std::string& path, const std::map<std::string, double>& overrides = {});

}  // namespace gyrokit
