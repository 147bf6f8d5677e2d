// The rotor analyses of a System: eig, mode_shapes, campbell, critical_speeds, stability,
// pervasive, response.
#pragma once

#include <pybind11/pybind11.h>

void bind_analyses(pybind11::module_& m);
