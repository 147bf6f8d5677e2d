// Frequency response functions as every front end runs them: the request's input,
// outputs (DOFs by name, or displacement probes), spin and frequencies, each in the
// study's unit (the scene's [speeds] units unless the call names one), the
// frequencies by default the scene's [speeds] grid; the outputs in the scene's
// length unit for the tables and figures, and in SI beside them.
#pragma once

#include <gyrokit/analysis/frequency_response.hpp>
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/study/request.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct FrfRequest {
    std::string input;                                 // the DOF the unit force (moment) acts on, by name
    std::optional<double> speed;                       // spin, in the study's unit; unset: 0
    std::optional<std::vector<double>> frequencies;    // in the study's unit; unset: the scene's [speeds]
    std::vector<std::string> dofs;                     // outputs by name; none (and no probes): the input
    std::vector<Probe> probes;                         // displacement probes read instead of DOFs
};

struct FrfStudy {
    SpeedUnit unit;
    FrequencyResponse response;   // H in the outputs' units of the scene's length unit (m or mm per N ...)
    Eigen::MatrixXcd si;          // the same H in SI units (m/N, rad/N, ...)
    ProbeOutputs named;           // the outputs' names and units (the model's DOFs, then the probes)
    Diagnostics diagnostics;      // bearings beyond their tables at the spin
};

// InputError naming the field (input, dofs, probes, speed, frequencies) and its allowed
// range; `common` as resolve_request takes it (unit, solver; speeds are not used).
FrfStudy frf_study(const Scene& scene, const RotorRequest& common, const FrfRequest& request);

}  // namespace gyrokit
