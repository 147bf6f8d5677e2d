// The probes of [criteria.response]: read from the sweep file, checked against the
// base scene, and found in each design's model. Not installed.
#pragma once

#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/screening/sweep.hpp>

#include <string>
#include <vector>

namespace gyrokit {

class TomlKeys;

// [criteria.response] probes = [{ name = "NDE", dof_x = "x3", dof_y = "y3", angle = 45.0 }, ...]
// (or node = 3 instead of dof_x and dof_y). One-line InputError naming the entry,
// the key, the value and what is allowed.
std::vector<ResponseProbe> read_probes(const TomlKeys& response);

// The probes against the base scene of the sweep `sweep`: DOFs that exist and share a
// unit, nodes that exist and have free x and y.
void check_probes(const std::string& sweep, const std::string& scene, const std::vector<ResponseProbe>& probes,
                  const GyroscopicSystem& base);

// The probe in one design's model; InputError where it names nothing there.
Probe resolve_probe(const ResponseProbe& p, const GyroscopicSystem& sys);

}  // namespace gyrokit
