// The steady unbalance response as every front end runs it (the CLI's `response`,
// Python's gyrokit.response): the dynamic stiffness solved at each speed, the
// outputs (DOFs or probe readings) in the scene's length unit, the peaks refined
// between grid speeds, the curves a plot of many shows, and the warnings: bearings
// used beyond their tables, and (unless the request skips it) every unstable range of
// the modes tracked over the speeds, where the response is no steady state.
#pragma once

#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <string>
#include <vector>

namespace gyrokit {

struct ResponseRequest {
    std::vector<int> outputs;        // DOFs reported; empty: every DOF (or the probes)
    std::vector<Probe> probes;       // displacement probes instead of DOFs (named as given, lengths)
    LengthUnit length;               // lengths shown (the scene's length_unit)
    bool peaks = true;               // refine the peaks between grid speeds (extrema, maxima, plotted)
    bool antiresonances = false;     // with peaks: the local minima too
    bool stability_check = true;     // track the modes over the speeds for the unstable-range warning
};

struct ResponseStudy {
    std::vector<std::string> names, units;   // of every output index (DOFs, or the probes), units as shown
    ResponseCurve curve;                     // speeds x outputs, in `units`
    Eigen::MatrixXcd si;                     // the same columns in SI units (m, rad)
    std::vector<ResponseExtremum> extrema;   // refined peaks (and antiresonances), in `units`
    std::vector<ResponseMaximum> maxima;     // the largest amplitude of each output (refined where peaks)
    std::vector<int> plotted;                // a plot of many curves: the six largest of each unit; empty: all
    Diagnostics diagnostics;                 // extrapolation notes, solver notes, instability warnings
};

// InputError for no speeds, probes together with outputs, or an output that is no DOF.
ResponseStudy response_study(const GyroscopicSystem& sys, const StudyOptions& opt, const ResponseRequest& request);

}  // namespace gyrokit
