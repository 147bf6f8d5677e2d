// Scene files (TOML): a model and the analysis settings. See docs/scene_format.md.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/core/sparse_system.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/models/fluid_rotor.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// Models up to this many DOFs are also held densely (for the dense solver and
// the analyses only it offers); larger ones only in sparse form.
constexpr int kDenseLimit = 3000;

struct Scene {
    std::string path;                  // the file it was read from
    std::string title;
    std::string model_type;            // "gyrostat" | "matrices" | "fluid_rotor" | "fe_rotor"
    GyroscopicSystem system;           // the dense model; empty (size 0) when only `sparse` exists
    // The sparse model of "matrices" and "fe_rotor" scenes (other models: none;
    // the sparse solver then works on their pencils converted per speed).
    std::optional<SparseGyroscopicSystem> sparse;
    std::string solver = "auto";       // [analysis] solver: auto | dense | sparse
    std::optional<double> target;      // [analysis] target: frequency (rad/s) the sparse search centres on
    double target_order = 0.0;         // [analysis] target_order: the centre moves as target + order * speed
    std::optional<SpeedRange> speeds;  // [speeds] from, to, count
    int modes = 0;                     // [analysis] modes (0 = all)
    std::vector<int> harmonics{1};     // [analysis] harmonics
    std::optional<FluidRotorParameters> fluid;   // set for [model] type = "fluid_rotor"

    int dofs() const { return sparse ? sparse->size() : system.size(); }
    const std::vector<std::string>& dof_names() const { return sparse ? sparse->dof_names : system.dof_names; }
    bool has_dense() const { return system.size() > 0; }
};

// Reads and validates a scene. Every error is an InputError of one line naming
// the file, the key, the value and the allowed range. `overrides` replace
// numeric keys before validation, named TABLE.KEY (e.g. "model.c_G"): how a
// design study varies a base scene.
Scene load_scene(const std::string& path, const std::map<std::string, double>& overrides = {});

}  // namespace gyrokit
