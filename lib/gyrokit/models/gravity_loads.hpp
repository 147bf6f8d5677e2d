#pragma once
// The rotor's weight on its bearings: what a fluid-film bearing given load = "auto" carries.

#include <gyrokit/models/fe_rotor.hpp>

#include <vector>

namespace gyrokit {

// Standard gravity (m/s^2), the static load unless asked otherwise.
constexpr double kStandardGravity = 9.80665;

// Static bearing loads from the rotor's weight: the vertical reactions (N, > 0 upwards)
// at `nodes` when the rotor rests there on rigid supports (y held) besides its other
// bearings and supports, under gravity g along -y. The vertical plane alone (y,
// theta_x and the pedestals' py; constant bearings' kyy, no cross-coupling), with
// consistent loads (the mass matrix times the rigid lift), so a statically determinate
// rotor gets its exact reactions. InputError if the rotor is not held in that plane.
std::vector<double> fe_gravity_reactions(const FeRotor& r, const std::vector<int>& nodes, double g = kStandardGravity);

}  // namespace gyrokit
