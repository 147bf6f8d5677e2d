// The rotor analyses as every front end runs them: the CLI, Python and the
// screening call these, so that the same study gives the same results and the
// same notes everywhere. Options are merged once (the scene's [analysis] and
// [speeds], then the caller's), the solver is chosen by the library's rule, the
// modes in range are tracked by default, and what the run has to say comes back
// as typed diagnostics.
#pragma once

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/mode_shapes.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/solve/workers.hpp>
#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/defaults.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace gyrokit {

// Unset fields are the table's defaults (study/defaults.hpp).
struct StudyOptions {
    SolverOptions solver = in_range();   // modes: the modes in range unless asked
    std::vector<double> speeds;      // rad/s
    std::vector<int> harmonics{defaults::harmonic};
    std::optional<double> f_cut;     // rad/s: the modes judged (judged_band: default 1.5 x the highest excitation)
    // Every core (defaults::jobs), as threads: a library caller's process is not forked.
    Workers workers{worker_count(defaults::jobs), WorkerKind::Threads};
    SpeedUnit unit;                  // the unit the diagnostics name speeds in
    std::function<void(std::size_t, std::size_t)> progress;   // speeds solved, of all
    bool amplification_factors = true;   // critical speeds: API 684 AF (half-power: some hundred solves each)

private:
    static SolverOptions in_range() {
        SolverOptions s;
        s.modes = defaults::modes;
        return s;
    }
};

// The scene's defaults: [analysis] solver options, modes and harmonics, [speeds] and
// their units. A caller's own values on top: resolve_request (study/request.hpp).
StudyOptions study_options(const Scene& scene);

// The eigenvalues at one speed (eig), by the library's solver choice. A mode count
// K > 0: the K lowest by frequency of the dense solver's spectrum (keep_lowest_modes,
// as a Campbell diagram's K lowest), the sparse window of the K nearest the target;
// 0 (and the modes in range, which one speed does not define) every mode (dense) or
// the sparse default window. InputError for a speed that is not finite and >= 0.
struct SpectrumStudy {
    SolverChoice plan;
    QuadraticSpectrum spectrum;
    Diagnostics diagnostics;   // bearings beyond their tables at the speed, the solver's notes, rigid-body eigenvalues
};
SpectrumStudy spectrum_study(const GyroscopicSystem& sys, double speed, const SolverOptions& opt,
                             const SpeedUnit& unit = {});   // the unit messages name the speed in

// The mode shapes at one speed (modes, mode_shapes): the opt.modes lowest (0: every
// mode computed); `select` (numbers from 1 of those computed) keeps only these, in
// that order. InputError naming the field (speed, mode) and its range; speeds in
// messages in `unit`.
struct ModeShapeStudy {
    std::vector<ModeShape> shapes;
    Diagnostics diagnostics;   // bearings beyond their tables at the speed, the solver's notes
};
ModeShapeStudy mode_shape_study(const GyroscopicSystem& sys, double speed, const SolverOptions& opt,
                                const SpeedUnit& unit = {}, const std::vector<int>& select = {});
// The shapes numbered `select` (ModeShape::number), in that order; InputError naming
// the mode field and the numbers computed.
std::vector<ModeShape> select_mode_shapes(const std::vector<ModeShape>& shapes, const std::vector<int>& select);

// The Hautus check of each damping component and of the total damping over the
// study's speeds, the modes the study names (opt.solver.modes), its workers.
struct PervasiveStudy {
    PervasiveReport report;
    Diagnostics diagnostics;   // what the check covers where the sparse solver's window limits it
};
PervasiveStudy pervasive_study(const GyroscopicSystem& sys, const StudyOptions& opt,
                               double tolerance = defaults::pervasive_tolerance);

// A tracked Campbell diagram and what it stood on.
struct CampbellStudy {
    SolverChoice plan;       // the solver choice (its notes are in diagnostics)
    SolverFactory solver;    // the tracking solver (the continuation where it is used)
    CampbellDiagram diagram;
    // Where a mode is unstable: its stability changes refined on the tracking solver
    // and every unstable range (every mode judged) with those edges. Both empty where
    // every mode is stable, so a stable rotor costs no refinement.
    std::vector<StabilityChange> changes;
    std::vector<UnstableRange> unstable;
    Diagnostics diagnostics; // solver, extrapolation, rigid-body, ambiguity, instability, out of range
};
CampbellStudy campbell_study(const GyroscopicSystem& sys, const StudyOptions& opt);
// The Campbell summary of a study: its sparse window judges its own modes only.
Table campbell_summary(const CampbellStudy& st, const std::vector<CriticalSpeed>& critical, const SpeedUnit& u,
                       const std::string& plot_file);

// The critical speeds of the tracked modes, with API 684 amplification factors.
struct CriticalSpeedStudy {
    CampbellStudy tracked;
    std::vector<CriticalSpeed> critical;
};
CriticalSpeedStudy critical_speed_study(const GyroscopicSystem& sys, const StudyOptions& opt);
// The same on a tracked diagram (the Campbell summary lists them too).
std::vector<CriticalSpeed> critical_speeds_of(const GyroscopicSystem& sys, const CampbellStudy& tracked,
                                              const StudyOptions& opt);

// The speeds where a tracked mode changes stability; a Verdict note where none does.
// Its table is the verdict on stability: the diagram's rigid-body, ambiguity and
// instability lines are left out of its diagnostics.
struct StabilityStudy {
    CampbellStudy tracked;
    std::vector<StabilityChange> changes;
};
StabilityStudy stability_study(const GyroscopicSystem& sys, const StudyOptions& opt);
// The same on a diagram already tracked with `opt` (the report's Campbell diagram).
StabilityStudy stability_of(const GyroscopicSystem& sys, const CampbellStudy& tracked, const StudyOptions& opt);

// The steady unbalance response is no state the rotor reaches where a mode is
// unstable: the modes are tracked over the range (at most 21 speeds of it, a
// bounded cost next to the response itself: sorted, repeated speeds once) and every
// unstable range is a warning, after the solver choice's notes (how many modes it checks).
Diagnostics response_stability_warnings(const GyroscopicSystem& sys, const StudyOptions& opt);

}  // namespace gyrokit
