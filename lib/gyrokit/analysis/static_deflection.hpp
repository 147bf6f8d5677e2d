// Static analysis of an FE rotor at standstill: deflection and slope at every node,
// shear force and bending moment along the shaft, and the reactions of bearings,
// supports and pedestals, under gravity and given point loads (docs/static.md).
//
// K u = f on the lateral DOFs of the rotor (constant bearings as their springs,
// cross-coupling included; supports and the rigid holds held in x and y),
// with the consistent weight f = -g M r (r = 1 on every vertical translation: a rigid
// lift), so a statically determinate rotor gets its exact reactions.
#pragma once

#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/gravity_loads.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The largest gravity (m/s^2) and point load component (N, N m) a static analysis takes.
constexpr double kMaxGravity = 1e6;
constexpr double kMaxStaticLoad = 1e15;

// A point load at a node: forces (N) along x and y, moments (N m) about x and y.
struct StaticLoad {
    int node = 0;
    double fx = 0.0, fy = 0.0, mx = 0.0, my = 0.0;
};

// A node held in x and y besides the supports (a speed-dependent bearing at standstill).
struct RigidHold {
    int node = 0;
    std::string name;                 // its reaction's name ("" : "rigid <index + 1>")
};

struct StaticOptions {
    double gravity = kStandardGravity;       // m/s^2 along -y (0: no weight)
    std::vector<StaticLoad> loads;
    std::vector<RigidHold> rigid;
    std::vector<std::string> bearing_names;  // of the rotor's bearings in order; empty: "bearing <i + 1>"
};

// Deflection of a node; slopes are the shaft's dx/dz = theta_y and dy/dz = -theta_x.
struct StaticNode {
    int node = 0;
    double z = 0.0;                   // m
    double x = 0.0, y = 0.0;          // m
    double slope_x = 0.0, slope_y = 0.0;   // rad
};

// Internal forces at one end of an element (just inside it), in each plane: the shear
// force V = dM/dz (N) and the bending moment M (N m) with M = E I y'' in the vertical
// plane (y, z) and M = E I x'' in the horizontal one (x, z): positive where the shaft
// sags towards -y (or -x) with its ends held.
struct StaticSection {
    int element = 0;
    double z = 0.0;                   // m: the element's start or end
    double shear_x = 0.0, moment_x = 0.0;   // horizontal plane (x, z)
    double shear_y = 0.0, moment_y = 0.0;   // vertical plane (y, z)
};

// The force (N) and moment (N m) a bearing, support or pedestal spring exerts on the rotor.
struct StaticReaction {
    std::string what;                 // "bearing 1", "support 1", "pedestal 1" (from 1), a rigid hold's name
    int node = 0;
    double z = 0.0;
    double fx = 0.0, fy = 0.0, mx = 0.0, my = 0.0;
};

struct StaticResult {
    std::vector<StaticNode> nodes;
    std::vector<StaticSection> sections;   // two per element: its start and its end
    std::vector<StaticReaction> reactions;
    double weight = 0.0;              // N, the rotor's (and pedestals') total weight
    // Checks: the relative backward error of the solve, ||K u - f|| / (||K|| ||u|| + ||f||),
    // and the force balance |sum of reactions + loads| / (sum of |loads| + weight).
    double backward_error = 0.0;
    double balance_error = 0.0;
    // The condition number of the held stiffness (estimated; Frobenius norm) and the bound
    // on the deflections' relative error, condition * backward_error. Above 1e-4 the
    // rotor counts as not held (a free rigid motion).
    double condition = 0.0;
    double error_bound = 0.0;
};

// InputError if the rotor is not held in both planes (free to fall or tip), if a node
// is out of range, or if its DOFs have no lateral motion.
StaticResult fe_static(const FeRotor& rotor, const StaticOptions& options);

}  // namespace gyrokit
