// The static analysis of an FE rotor (deflection, internal forces, reactions).
#pragma once

#include <pybind11/pybind11.h>

void bind_statics(pybind11::module_& m);
