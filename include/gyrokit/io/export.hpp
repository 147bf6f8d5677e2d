// Writes the system matrices at one speed as Matrix Market files.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>

#include <string>

namespace gyrokit {

// Into `dir` (created if missing): M, K, G (per unit speed), N and K2 (if any),
// D (total) and D_<component> at speed w, the assembled C = D + wG and Kw = K + wN + w^2 K2, the first companion
// pencil A - lambda B (A = [-C -Kw; I 0], B = [M 0; 0 I]) and, if M is
// invertible, the state matrix S = [0 I; -M^-1 Kw  -M^-1 C].
void export_matrices(const GyroscopicSystem& sys, double w, const std::string& dir);

}  // namespace gyrokit
