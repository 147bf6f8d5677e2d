// Writes the system matrices at one speed as Matrix Market files.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// The dense state matrix is written only up to this many DOFs.
constexpr int kExportStateLimit = 1000;

struct ExportReport {
    std::vector<std::string> files;   // names written, in order
    std::vector<std::string> notes;   // what was not written and why
};

// Into `dir` (created if missing), in sparse coordinate form: M, K, G (per unit
// speed), N and K2 (if any), D (total) and D_<component> at speed w, each bearing
// table's K_bearing<i>, D_bearing<i>, the assembled C = D + wG and Kw = K + wN +
// w^2 K2, the first companion pencil A - lambda B (A = [-C -Kw; I 0], B = [M 0;
// 0 I]) and, up to kExportStateLimit DOFs and if M is invertible, the state
// matrix S = [0 I; -M^-1 Kw  -M^-1 C].
ExportReport export_matrices(const GyroscopicSystem& sys, double w, const std::string& dir);

}  // namespace gyrokit
