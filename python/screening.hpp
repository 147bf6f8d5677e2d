// Design screening: screen, screen_design, screen_plan, screen_error_row.
#pragma once

#include <pybind11/pybind11.h>

void bind_screening(pybind11::module_& m);
