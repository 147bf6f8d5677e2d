// The defaults a user meets: every front end takes its default values from here
// (the CLI's options and help, the Python signatures, the screening), and
// docs/defaults.md lists the same table (tests/defaults_check.py compares all of
// them with `gyrokit defaults`). Each value is decided where the analysis that uses
// it lives (the constant named beside it); this header gathers them for the
// front ends, so that none of them decides one of its own.
#pragma once

#include <gyrokit/analysis/api_unbalance.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/analysis/level1_stability.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/models/machine_stages.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/study/mesh_convergence_study.hpp>
#include <gyrokit/study/report_study.hpp>
#include <gyrokit/analysis/transient.hpp>
#include <gyrokit/analysis/static_deflection.hpp>

#include <string>
#include <vector>

namespace gyrokit::defaults {

// Modes: unset means the modes in range (every mode up to f_cut tracked and judged).
inline constexpr int modes = kModesInRange;
// f_cut: this many times the highest excitation frequency (harmonic x top speed).
inline constexpr double f_cut_margin = kBandMargin;
// The excitation lines: 1x.
inline constexpr int harmonic = 1;
// Speeds and frequencies in and out where neither the call nor the scene's [speeds] names a unit.
inline constexpr const char* unit = "rad/s";
// The dense eigensolver: the state matrix where it is faster and verified, else scaled QZ.
inline constexpr const char* method = "auto";
// The solver: dense up to kAutoSparseDofs DOFs (kAutoDenseInRangeDofs for the modes in range), else sparse.
inline constexpr const char* solver = "auto";
// The sparse window when no mode count is given.
inline constexpr int sparse_modes = kDefaultSparseModes;
// Arnoldi vectors of the sparse solver: 0 = automatic.
inline constexpr int lanczos = 0;
// Workers (threads of a sweep, designs of a screening) under one name: 0 = every core.
inline constexpr int jobs = 0;
// The largest residual of a pervasive-damping loss.
inline constexpr double pervasive_tolerance = kPervasiveTolerance;
// Critical speed map: critical speeds of each whirl per stiffness, and the stiffness range.
inline constexpr int critical_map_modes = kCriticalMapModes;
inline constexpr double critical_map_stiffness_from = kMapStiffnessFrom;   // times 48 E I / L^3
inline constexpr double critical_map_stiffness_to = kMapStiffnessTo;
inline constexpr int critical_map_points = kMapStiffnessPoints;
// Level I stability: the curve's equal steps, and its range in multiples of QA.
inline constexpr int level1_intervals = kLevel1Intervals;
inline constexpr double level1_q_ratio = kLevel1QRatio;
// API unbalance cases: the grid speeds from 0 to the highest speed sought, and the trip
// speed in multiples of the mcs.
inline constexpr int api_speeds = kApiResponseSpeeds;
inline constexpr double api_trip_ratio = kApiTripRatio;
// Mesh convergence: the change allowed on doubling, and the meshes at most.
inline constexpr double mesh_tolerance = kMeshTolerance;
inline constexpr int mesh_levels = kMeshLevels;
// The report: the critical speeds whose mode shapes it draws.
inline constexpr int report_mode_shapes = kReportModeShapes;
// Static deflection: gravity along -y, m/s^2.
inline constexpr double gravity = kStandardGravity;
// Transient response: the largest number of time steps a run may take.
inline constexpr long long max_steps = kTransientMaxSteps;
// Transient response: the initial state, at rest (or steady: the steady response at the first speed).
inline constexpr const char* transient_start = "rest";

// One row of the table: its name, the value as written on a command line or in
// Python ("" where the default is a rule, stated in `meaning`), and where a user
// meets it: the CLI option and the Python keyword that take it, in every command
// and call that has them, or in `command` / `function` alone where those are given.
struct Entry {
    std::string name;
    std::string value;
    std::string meaning;
    std::string option;     // e.g. "--units" ("" : none)
    std::string keyword;    // e.g. "unit" ("" : none)
    std::string command;    // "" : every command with `option`
    std::string function;   // "" : every Python call with `keyword`
};
const std::vector<Entry>& table();

}  // namespace gyrokit::defaults
