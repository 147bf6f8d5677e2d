// A displacement probe: a proximity probe reads the lateral motion of a shaft
// section along one direction, x cos(angle) + y sin(angle), angle from +x towards
// +y (API 684 places two probes per bearing, e.g. at +-45 degrees from vertical).
// Of a complex response Z (z(t) = Re(Z e^{i w t})) it reads the amplitude
// |Z_x cos(angle) + Z_y sin(angle)|: on an elliptical orbit it depends on the
// direction, on a circular orbit it does not.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>

#include <Eigen/Dense>
#include <complex>
#include <string>
#include <vector>

namespace gyrokit {

struct Probe {
    std::string name;
    int dof_x = 0, dof_y = 1;      // model DOF indices of the x and y displacement
    double angle_degrees = 0.0;    // from +x towards +y
};

// Z_x cos(angle) + Z_y sin(angle): the probe's complex reading (its phase as
// well as its amplitude). Multiples of 90 degrees are exact (0 degrees reads
// Z_x, 90 degrees Z_y, with no rounding of cos and sin). Throws InputError if a
// DOF index lies outside Z.
std::complex<double> probe_response(const Probe& p, const Eigen::VectorXcd& Z);
// |probe_response|: the amplitude the probe reads.
double probe_amplitude(const Probe& p, const Eigen::VectorXcd& Z);

// The probe at a node of a model with nodes on an axis (a finite-element rotor):
// its x and y translations, the whirl pair of the node in m. InputError naming
// the node and the allowed range if the node does not exist, and the reason if it
// has no free pair of translations (a support holds x or y, or the model has no
// lateral motion).
Probe probe_at_node(const GyroscopicSystem& sys, const std::string& name, int node, double angle_degrees);

// The model DOFs the probes read, each once, in order of first use.
std::vector<int> probe_dofs(const std::vector<Probe>& probes);
// The probes' readings of a response known at the model DOFs `dofs` (the columns of Z,
// one row per speed or frequency): one column per probe. InputError if a probe's DOF
// is not among `dofs`.
Eigen::MatrixXcd probe_readings(const std::vector<Probe>& probes, const std::vector<int>& dofs,
                                const Eigen::MatrixXcd& Z);
// Output names for the report functions, which name an output by its index: the model's
// DOF names and units followed by one entry per probe (its name, "m"); `outputs` the
// probes' indices in them (the model's size on).
struct ProbeOutputs {
    std::vector<std::string> names, units;
    std::vector<int> outputs;
};
ProbeOutputs probe_outputs(const GyroscopicSystem& sys, const std::vector<Probe>& probes);

}  // namespace gyrokit
