// Probes given from Python, for the frequency and unbalance responses.
#pragma once

#include <gyrokit/analysis/probe.hpp>

#include <utility>
#include <vector>

namespace gyrokit_python {
// Probes at nodes from Python's (node, angle in degrees) pairs, named "NODE@ANGLE"; InputError
// naming the entry.
std::vector<gyrokit::Probe> probes_of(const gyrokit::GyroscopicSystem& s,
                                      const std::vector<std::pair<int, double>>& list);
}  // namespace gyrokit_python
