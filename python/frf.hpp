// Frequency response functions at a fixed spin speed.
#pragma once

#include <pybind11/pybind11.h>

void bind_frf(pybind11::module_& m);
