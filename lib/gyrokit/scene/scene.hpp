// Scene files (TOML): a model and the analysis settings. See docs/scene_format.md.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/core/solver_kind.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/rotor_model.hpp>
#include <gyrokit/models/fluid_rotor.hpp>
#include <gyrokit/models/machine_stages.hpp>
#include <gyrokit/models/gyrostat.hpp>

#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace gyrokit {

// The model a scene describes, as described (its assembled matrices are Scene::system). The
// models without a writer of their own keep their document: the [model] as read, overrides
// applied and relative file names made absolute, so that scene_text writes it back from anywhere.
struct MatricesScene {
    std::string document;
};
struct GyrostatScene {
    GyrostatParameters parameters;
    std::string document;   // empty: built in code (written from the parameters)
};
struct FluidRotorScene {
    FluidRotorParameters parameters;
    std::string document;   // empty: built in code (written from the parameters)
};
struct FeRotorScene {
    RotorModel model;   // the rotor as described (written back by scene_text)
    FeRotor mesh;       // and its mesh (speed-dependent bearings in Scene::system)
};
// A system built in code is a MatricesScene (the default).
using SceneModel = std::variant<MatricesScene, GyrostatScene, FluidRotorScene, FeRotorScene>;

// What a scene's analyses excite and judge ([analysis]).
struct AnalysisSettings {
    std::vector<int> harmonics{1};     // the excitation orders (1 = synchronous)
    std::optional<double> f_cut;       // rad/s: the modes judged (default: excitation_band)
};

// A scene's solver where it names none: auto, the modes in range.
inline SolverOptions scene_solver() {
    SolverOptions o;
    o.modes = kModesInRange;
    return o;
}

struct Scene {
    std::string path;                  // the file it was read from
    std::string title;
    SceneModel model;                  // what the [model] describes
    GyroscopicSystem system;           // the model's matrices, validated
    // [analysis] solver, target (rad/s: the frequency the sparse search centres on),
    // target_order (the centre moves as target + order * speed) and modes (0 = all;
    // absent: those in range): the solver the scene asks for, as every study starts it.
    SolverOptions solver = scene_solver();
    AnalysisSettings analysis;         // [analysis] harmonics, f_cut
    std::optional<SpeedRange> speeds;  // [speeds] from, to, count as written, in speed_unit
    // [speeds] units (rad/s where the scene names none): the unit a study gives and
    // takes speeds and frequencies in unless the call names another (resolve_request).
    SpeedUnit speed_unit;
    // [api]: the machine data of the API 617 / API 684 analyses (FE rotors; speeds in
    // rad/s, lengths in m).
    std::optional<ApiMachine> api;
    // Every file read to build it (absolute paths: the scene file, the matrices and
    // tables it names): what no output of a run on it may overwrite.
    std::vector<std::string> inputs;

    int dofs() const { return system.size(); }
    // The [model] type: "matrices" | "gyrostat" | "fluid_rotor" | "fe_rotor".
    std::string model_type() const;
    // The model's description where it is of that type, else nullptr.
    const RotorModel* rotor_model() const;
    const FeRotor* fe_rotor() const;
    const FluidRotorParameters* fluid() const;
    const GyrostatParameters* gyrostat() const;
    // The unit the scene states lengths in (an FE rotor's length_unit; else metres).
    LengthUnit length_unit() const { return rotor_model() ? LengthUnit::parse(rotor_model()->length_unit) : LengthUnit{}; }
    // The [speeds] grid in rad/s (empty without [speeds]): the points in the scene's
    // unit, each converted (speed_unit), so that a range written in rpm is the same
    // grid however it reaches a study.
    std::vector<double> speed_points() const;
    const std::vector<std::string>& dof_names() const { return system.dofs.names; }
};

// Reads and validates a scene. Every error is an InputError of one line naming
// the file, the key, the value and the allowed range. `overrides` replace
// numeric keys before validation, named TABLE.KEY (e.g. "model.c_G"): how a
// design study varies a base scene. `fe_motion` (lateral, all, axial or torsional), if
// given, replaces the DOF set of an fe_rotor model (its motion and dofs_per_node): a
// torsional or axial analysis of a rotor described once.
Scene load_scene(const std::string& path, const std::map<std::string, double>& overrides = {},
                 const std::string& fe_motion = "");

// The same from the text of a scene: `origin` names it in messages, `dir`
// resolves the files it refers to (Matrix Market, bearing tables).
// `overrides` as load_scene's.
Scene parse_scene(const std::string& text, const std::string& origin, const std::string& dir = ".",
                  const std::map<std::string, double>& overrides = {});

// Checks the analysis settings of a scene assembled in code (speeds, modes, harmonics,
// target, target_order, f_cut) as the reader checks [speeds] and [analysis]: InputError
// naming the field, the value and the allowed range.
void validate_settings(const Scene& scene);

}  // namespace gyrokit
