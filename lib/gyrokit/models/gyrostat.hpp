// Gyrostat with elastic shaft (Magnus): elastically suspended cage, rotor on a
// massless elastic shaft. Coordinates z = [alpha, beta, x, y, psi, theta]:
// cage tilts, rotor translation relative to the cage, rotor tilt relative to
// the cage. Equations (9) of the paper with the corrections of docs/gyrostat.md.
#pragma once
#include <string>

#include <gyrokit/core/gyroscopic_system.hpp>

namespace gyrokit {

struct GyrostatParameters {
    double A_G = 0, B_G = 0;   // cage moments of inertia about the suspension point, kg m^2
    double A_R = 0, C_R = 0;   // rotor diametral and polar moments of inertia, kg m^2
    double m = 0;              // rotor mass, kg
    double s = 0;              // distance suspension point - rotor centre, m (may be negative)
    double eps = 0;            // rotor eccentricity (static unbalance), m
    double c_G = 0;            // cage tilt stiffness, N m/rad
    double c_T = 0;            // shaft translation stiffness, N/m
    double c_R = 0;            // shaft tilt stiffness, N m/rad
    double d_G = 0, d_T = 0, d_R = 0;   // cage, translation and rotation damping
    bool rigid_shaft = false;           // c_T, c_R -> infinity: only alpha, beta (eq. 12)
    bool rigid_housing = false;         // c_G -> infinity: only x, y, psi, theta
};

// Throws InputError naming `origin`, the key (the scene's [model] key), the value and
// the allowed range; the keys a rigid shaft (c_T, c_R) or housing (A_G, B_G, c_G)
// makes irrelevant are not checked.
void validate(const GyrostatParameters& p, const std::string& origin);

// Builds M, D (components "d_G", "d_T", "d_R"), G, K and the unbalance load
// (make_system: the verb every model shares).
// With a rigid shaft or housing only the remaining DOFs are built.
GyroscopicSystem make_system(const GyrostatParameters& p);

}  // namespace gyrokit
