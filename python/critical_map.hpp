// The undamped critical speed map of an FE rotor against bearing stiffness.
#pragma once

#include <pybind11/pybind11.h>

void bind_critical_map(pybind11::module_& m);
