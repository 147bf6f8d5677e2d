// FE rotors built in Python (Rotor, Section, Disk, Bearing, Support, Pedestal,
// rotor_scene) and scenes written back (Scene.to_toml, write, pickle).
#pragma once

#include <gyrokit/scene/scene.hpp>

#include <pybind11/pybind11.h>

void bind_models(pybind11::module_& m, pybind11::class_<gyrokit::Scene>& scene);
