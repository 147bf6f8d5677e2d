// The auto-balancer and the Sommerfeld effect: balancer, sommerfeld.
#pragma once

#include <pybind11/pybind11.h>

void bind_balancing(pybind11::module_& m);
