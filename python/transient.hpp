// Transient response by time integration (transient_response) as NumPy arrays.
#pragma once

#include <pybind11/pybind11.h>

void bind_transient(pybind11::module_& m);
