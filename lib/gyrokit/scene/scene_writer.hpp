// Scenes from models built in code, and scenes written back as TOML: a study handed
// to the CLI, a cluster or a colleague. See docs/scene_format.md, "Writing scenes".
#pragma once

#include <gyrokit/scene/scene.hpp>
#include <gyrokit/models/rotor_model.hpp>

#include <string>

namespace gyrokit {

// A scene of an FE rotor built in code: the model built and validated (InputError
// as build() gives it), the analysis settings at their defaults (set them on the
// result). `title` names the scene in messages ("fe_rotor" if empty).
Scene rotor_scene(const RotorModel& model, const std::string& title = "");

// Scenes of a gyrostat or a liquid-filled rotor from its parameters (validate, then
// make_system; InputError naming the key as the scene reader does). `title` names
// the scene in messages ("gyrostat" or "fluid_rotor" if empty).
Scene model_scene(const GyrostatParameters& parameters, const std::string& title = "");
Scene model_scene(const FluidRotorParameters& parameters, const std::string& title = "");

// The scene as TOML that load_scene and parse_scene read back to the same model and
// settings: every number in its shortest round-trip form, lengths in m, speeds in
// rad/s, so the matrices are equal bit for bit; angles (unbalance phase, load angle)
// are written in degrees, as the format has them, and come back within 1 ulp. A
// bearing table read from a file is referred to by its absolute path.
// A gyrostat or liquid-filled rotor built from its parameters is written from them.
// Any other model read from a document (a file, a text) is written as read: its
// document with overrides applied and file names absolute. InputError for what the
// format cannot say: a matrices model assembled in code, a support holding another
// set of DOFs than pinned or clamped.
std::string scene_text(const Scene& scene);

// scene_text written to `path` through an OutputFile (replaced whole). InputError if
// it cannot be written or `path` is a matrix or table the scene reads (its own file
// may be written back: an edit).
void write_scene(const Scene& scene, const std::string& path);

}  // namespace gyrokit
