// gyrokit-bench-tradeoffs: the FE rotor models the sections are measured on.
#pragma once

#include <gyrokit/models/fe_rotor.hpp>

namespace tradeoffs {

// Steel (Young's modulus, Poisson's ratio, density) of fe_machine and of the beam of mesh_rows.
constexpr double kE = 2.1e11, kNu = 0.3, kRho = 7850.0;

// Stepped steel shaft of 1.5 m (diameter 60..80 mm) in `elements` equal
// elements, two disks, two anisotropic bearings inboard of the ends
// (overhangs), with or without bearing damping.
gyrokit::FeRotor fe_machine(int elements, bool damped);

// The family of data/fe_rotor_100k.toml at any size: a hollow shaft (80/30 mm)
// of dofs/4 nodes in 20 mm elements, a bearing (5e8 N/m, 2e3 N s/m) every 50
// elements and at both ends, a disk in the middle of each span; the second and
// fourth spans have longer elements (1.5 m and 1.3 m spans), so that their
// modes are the lowest, apart from the cluster of the equal 1 m spans.
gyrokit::FeRotor fe_train(int dofs);

}  // namespace tradeoffs
