// System and Scene, load_scene and parse_scene; returns the Scene class for bind_models.
#pragma once

#include <gyrokit/scene/scene.hpp>

#include <pybind11/pybind11.h>

pybind11::class_<gyrokit::Scene> bind_system(pybind11::module_& m);
