// Mode shapes: an eigenvector scaled for reading, and the ellipse (orbit) each
// whirl pair of DOFs traces in the mode. For a rotor with nodes on its axis the
// orbits of the translational pairs, in axial order, are the deflected shape.
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/mode.hpp>

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

namespace gyrokit {

// The ellipse traced by (Re(u e^{i t}), Re(v e^{i t})): split into a forward and a
// backward circle, u + i v -> f e^{i t} + b e^{-i t} with f = (u + i v)/2 and
// b = (conj(u) + i conj(v))/2, the semi-axes are |f| + |b| and ||f| - |b||.
struct Orbit {
    double major = 0.0;        // semi-axes, in the DOFs' unit
    double minor = 0.0;
    double angle = 0.0;        // rad, of the major axis from +u towards +v, in (-pi/2, pi/2]
    double phase = 0.0;        // rad, arg u: the phase of the u coordinate (the shape's reference entry has 0)
    Whirl whirl = Whirl::None; // Forward: turns from +u towards +v; Planar: minor <= kWhirlTolerance major;
                               // None: no motion
};
Orbit orbit_of(std::complex<double> u, std::complex<double> v);
// In a mode shape, a pair whose entries are at most this fraction of the largest
// entry of its unit is at rest (a node of the mode): its orbit is no motion, not
// the rounding's ellipse.
constexpr double kRestTolerance = 1e-9;

// One whirl pair's orbit in a mode, with where it sits.
struct PairOrbit {
    int u = 0, v = 0;          // DOF indices of the pair
    std::string name;          // "x3/y3"
    std::string unit;          // of the pair's DOFs ("" if the model does not say)
    int node = -1;             // node on the axis (-1: none)
    double z = 0.0;            // m, the node's axial position (0 without a node)
    Orbit orbit;
};

struct ModeShape {
    int number = 1;            // position in the spectrum, from 1 (by frequency)
    Mode mode;                 // eigenvalue, error bound, whirl of the whole mode
    // The right eigenvector scaled so that its reference entry is 1: the entry of
    // largest modulus among the DOFs in metres (all DOFs if the model names no
    // units, or if its metre entries stay below kWhirlTolerance of the largest).
    Eigen::VectorXcd shape;
    int reference = 0;         // index of that entry
    std::vector<PairOrbit> orbits;   // one per whirl pair, by node then pair order
};

// The shape of one mode of `sys` (its vector from the same system).
ModeShape mode_shape(const Mode& m, const GyroscopicSystem& sys);
// The shapes of every mode of a spectrum of `sys` (rigid-body eigenvalues left out).
std::vector<ModeShape> mode_shapes(const QuadraticSpectrum& s, const GyroscopicSystem& sys);
// Solves `sys` at speed `w` with the solver `options` choose (choose_solver) and
// returns the shapes of the `options.modes` lowest modes (0: every mode computed);
// the solver's notes are appended to `notes` if given.
std::vector<ModeShape> mode_shapes(const GyroscopicSystem& sys, double w, const SolverOptions& options = {},
                                   std::vector<std::string>* notes = nullptr);

}  // namespace gyrokit
