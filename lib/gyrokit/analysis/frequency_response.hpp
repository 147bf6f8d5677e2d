// Frequency response functions of a rotor spinning at a fixed speed: the steady
// response of every (or the chosen) DOF to a harmonic force or moment of unit
// amplitude at one DOF, over excitation frequency (docs/frf.md).
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>

#include <vector>

namespace gyrokit {

struct FrequencyResponse {
    double spin = 0.0;                 // rad/s
    std::vector<double> frequencies;   // rad/s
    int input = 0;                     // the DOF the force (moment) acts on
    std::vector<int> outputs;          // the DOF of each column of H
    // H(w): [K(spin) + spin N - w^2 M + i w (D(spin) + spin G)] h = e_input, in the
    // output's unit per the input's (m/N, rad/N, m/(N m), rad/(N m)).
    Eigen::MatrixXcd H;                // frequencies x outputs
};

// InputError for an input or output DOF out of range, a negative or non-finite spin or
// frequency; SolverError where the dynamic stiffness is singular (an undamped resonance
// on the grid).
FrequencyResponse frequency_response(const GyroscopicSystem& sys, double spin, const std::vector<double>& frequencies,
                                     int input, const std::vector<int>& outputs = {},
                                     SolverKind kind = SolverKind::Auto);

}  // namespace gyrokit
