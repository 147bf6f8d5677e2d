#include <gyrokit/study/rotor_study.hpp>

#include <gyrokit/analysis/energy_bound.hpp>
#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/campbell_reports.hpp>
#include <gyrokit/reports/spectrum_reports.hpp>
#include <gyrokit/study/request.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gyrokit {

namespace {

using Level = Diagnostic::Level;
using Topic = Diagnostic::Topic;

// What the tracked diagram says besides its rows.
void diagram_diagnostics(const CampbellDiagram& cd, const std::vector<UnstableRange>& unstable, const SpeedUnit& u,
                         Diagnostics& d) {
    add_notes(d, Topic::Solver, cd.notes);
    if (cd.rigid_body > 0)
        d.push_back({Level::Note, Topic::RigidBody,
                     fmt::format("{} rigid-body eigenvalues (lambda = 0: free motion of a singular K) are not modes "
                                 "and are not tracked",
                                 cd.rigid_body)});
    if (cd.ambiguous_steps > 0)
        d.push_back({Level::Note, Topic::Ambiguity,
                     fmt::format("{} speed steps stayed ambiguous at the refinement limit; use a finer speed grid",
                                 cd.ambiguous_steps)});
    for (const auto& w : instability_warnings(unstable, u)) d.push_back({Level::Warning, Topic::Instability, w});
    if (std::isfinite(cd.band)) d.push_back({Level::Note, Topic::OutOfRange, out_of_range_note(cd, u)});
}

}  // namespace

StudyOptions study_options(const Scene& scene) {
    StudyOptions o;
    o.solver = scene.solver;
    o.harmonics = scene.analysis.harmonics;
    o.f_cut = scene.analysis.f_cut;
    o.speeds = scene.speed_points();
    o.unit = scene.speed_unit;
    return o;
}

SpectrumStudy spectrum_study(const GyroscopicSystem& sys, double speed, const SolverOptions& opt,
                             const SpeedUnit& unit) {
    if (!(std::isfinite(speed) && speed >= 0.0))
        throw InputError(fmt::format("{} {:.12g}: allowed: a finite number >= 0 ({})", option_field("speed"),
                                     speed * unit.factor, unit.name));
    SpectrumStudy s;
    add_notes(s.diagnostics, Topic::Extrapolation, extrapolation_notes(sys.bearings, speed, speed));
    s.plan = choose_solver(sys, opt);
    add_notes(s.diagnostics, Topic::Solver, s.plan.notes);
    s.spectrum = s.plan.make()(speed);
    add_notes(s.diagnostics, Topic::Solver, s.spectrum.notes);
    if (!s.spectrum.rigid_body.empty())
        s.diagnostics.push_back({Level::Note, Topic::RigidBody,
                                 rigid_body_note(s.spectrum.rigid_body, sys.dofs.names) + " (" +
                                     option_field("rigid_body") + " lists them)"});
    // The dense solver gives every mode: the K lowest by frequency where K are asked for.
    if (s.plan.kind == SolverKind::Dense)
        if (const std::size_t all = keep_lowest_modes(s.spectrum, opt.modes); all > s.spectrum.modes.size())
            s.diagnostics.push_back({Level::Note, Topic::Solver,
                                     fmt::format("the {} lowest by frequency of the dense solver's {} modes ({} 0 "
                                                 "lists all)",
                                                 opt.modes, all, option_field("modes"))});
    return s;
}

ModeShapeStudy mode_shape_study(const GyroscopicSystem& sys, double speed, const SolverOptions& opt,
                                const SpeedUnit& unit, const std::vector<int>& select) {
    if (!(std::isfinite(speed) && speed >= 0.0))
        throw InputError(fmt::format("{} {:.12g}: allowed: a finite number >= 0 ({})", option_field("speed"),
                                     speed * unit.factor, unit.name));
    ModeShapeStudy s;
    add_notes(s.diagnostics, Topic::Extrapolation, extrapolation_notes(sys.bearings, speed, speed));
    std::vector<std::string> notes;
    s.shapes = mode_shapes(sys, speed, opt, &notes);
    add_notes(s.diagnostics, Topic::Solver, notes);
    if (!select.empty()) s.shapes = select_mode_shapes(s.shapes, select);
    return s;
}

std::vector<ModeShape> select_mode_shapes(const std::vector<ModeShape>& shapes, const std::vector<int>& select) {
    std::vector<ModeShape> chosen;
    for (const int k : select) {
        const auto it = std::find_if(shapes.begin(), shapes.end(), [&](const ModeShape& m) { return m.number == k; });
        if (it == shapes.end()) {
            if (shapes.empty())
                throw InputError(fmt::format("{} {}: no mode was computed at this speed", option_field("mode"), k));
            std::string numbers;
            for (const ModeShape& m : shapes) numbers += (numbers.empty() ? "" : ", ") + std::to_string(m.number);
            const bool run = shapes.back().number - shapes.front().number + 1 == static_cast<int>(shapes.size());
            throw InputError(fmt::format("{} {}: allowed: {} (the modes computed)", option_field("mode"), k,
                                         run ? fmt::format("{} to {}", shapes.front().number, shapes.back().number)
                                             : numbers));
        }
        chosen.push_back(*it);
    }
    return chosen;
}

PervasiveStudy pervasive_study(const GyroscopicSystem& sys, const StudyOptions& opt, double tolerance) {
    if (opt.speeds.empty())
        throw InputError(option_field("speeds") + " (none): allowed: at least one speed in rad/s");
    PervasiveStudy s;
    PervasiveOptions po;
    po.tolerance = tolerance;
    po.modes = opt.solver.modes;
    po.solver = opt.solver;
    po.threads = opt.workers;
    po.f_cut = opt.f_cut;
    if (po.modes == 0 && resolve_solver_kind(sys.size(), opt.solver.kind) == SolverKind::Sparse)
        s.diagnostics.push_back({Level::Note, Topic::Solver,
                                 fmt::format("the sparse solver checks the {} modes nearest the target; set {} K for "
                                             "another number",
                                             kDefaultSparseModes, option_field("modes"))});
    s.report = pervasive_damping(sys, opt.speeds, po);
    add_notes(s.diagnostics, Topic::Solver, s.report.notes);   // the tracking's (a window that may miss modes)
    return s;
}

CampbellStudy campbell_study(const GyroscopicSystem& sys, const StudyOptions& opt) {
    if (opt.speeds.empty())
        throw InputError(option_field("speeds") + " (none): allowed: at least one speed in rad/s");
    CampbellStudy s;
    s.plan = choose_solver(sys, opt.solver);
    add_notes(s.diagnostics, Topic::Solver, s.plan.notes);
    if (s.plan.make.walks() && opt.speeds.size() > 1)
        s.diagnostics.push_back({Level::Note, Topic::Solver,
                                 "the sparse window holds the modes nearest the target at the first speed, followed "
                                 "along their branches; a mode that comes nearer the target later joins it only where a "
                                 "step falls back to a window solve (target_order moves the window with the speed)"});
    add_notes(s.diagnostics, Topic::Extrapolation,
              extrapolation_notes(sys.bearings, opt.speeds.front(), opt.speeds.back()));
    CampbellOptions co = tracking_options(s.plan, opt.solver.modes, opt.speeds, opt.harmonics, opt.workers, opt.f_cut);
    co.progress = opt.progress;
    Tracking t = track(s.plan.make, co, opt.speeds);
    s.solver = std::move(t.solver);
    s.diagram = std::move(t.diagram);
    s.unstable = unstable_ranges(s.diagram, true);
    if (!s.unstable.empty()) {
        s.changes = stability_changes(s.solver, s.diagram, opt.workers);
        s.unstable = refine_edges(std::move(s.unstable), s.diagram, s.changes);
    }
    diagram_diagnostics(s.diagram, s.unstable, opt.unit, s.diagnostics);
    return s;
}

Table campbell_summary(const CampbellStudy& st, const std::vector<CriticalSpeed>& critical, const SpeedUnit& u,
                       const std::string& plot_file) {
    return campbell_summary(st.diagram, critical, st.unstable, u, plot_file, st.plan.kind == SolverKind::Sparse);
}

std::vector<CriticalSpeed> critical_speeds_of(const GyroscopicSystem& sys, const CampbellStudy& tracked,
                                              const StudyOptions& opt) {
    std::vector<CriticalSpeed> cs = critical_speeds(tracked.solver, tracked.diagram, opt.harmonics, opt.workers);
    if (opt.amplification_factors) set_amplification_factors(cs, sys);
    return cs;
}

CriticalSpeedStudy critical_speed_study(const GyroscopicSystem& sys, const StudyOptions& opt) {
    CriticalSpeedStudy s;
    s.tracked = campbell_study(sys, opt);
    s.critical = critical_speeds_of(sys, s.tracked, opt);
    return s;
}

StabilityStudy stability_study(const GyroscopicSystem& sys, const StudyOptions& opt) {
    return stability_of(sys, campbell_study(sys, opt), opt);
}

StabilityStudy stability_of(const GyroscopicSystem& sys, const CampbellStudy& tracked, const StudyOptions& opt) {
    StabilityStudy s;
    s.tracked = tracked;
    s.changes = s.tracked.changes;   // refined where a mode is unstable; none changes otherwise
    Diagnostics& d = s.tracked.diagnostics;
    d.erase(std::remove_if(d.begin(), d.end(),
                           [](const Diagnostic& x) {
                               return x.topic == Topic::RigidBody || x.topic == Topic::Ambiguity ||
                                      x.topic == Topic::Instability;
                           }),
            d.end());
    if (s.changes.empty())
        s.tracked.diagnostics.push_back(
            {Level::Note, Topic::Verdict,
             std::string("no mode changes stability in the range; ") +
                 (s.tracked.unstable.empty()
                      ? "none is unstable (neutral modes: Re lambda within its error bound)"
                      : "some are unstable throughout")});
    // The modes above the band are not tracked; where the energy bound shows that none
    // of them grows, the verdict covers them too.
    if (std::isfinite(s.tracked.diagram.band))
        if (const auto b = modes_above_band_decay(sys, opt.speeds, s.tracked.diagram.band))
            d.push_back({Level::Note, Topic::Verdict,
                         fmt::format("the modes above {:.6g} {}, not tracked, grow nowhere: the energy bound (symmetric "
                                     "stiffness, damping that dissipates) gives Re lambda <= {:.2g} 1/s for every "
                                     "mode at every speed, a log decrement of at least {:.2g} up there",
                                     opt.unit.factor * s.tracked.diagram.band, opt.unit.name, b->rate,
                                     0.0 - 2.0 * kPi * b->rate / s.tracked.diagram.band)});   // 0, not -0
    return s;
}

Diagnostics response_stability_warnings(const GyroscopicSystem& sys, const StudyOptions& opt) {
    StudyOptions o = opt;
    std::sort(o.speeds.begin(), o.speeds.end());
    o.speeds.erase(std::unique(o.speeds.begin(), o.speeds.end()), o.speeds.end());
    if (o.speeds.size() < 2) return {};   // no range to track over
    if (o.speeds.size() > 21) {
        const double from = o.speeds.front(), to = o.speeds.back();
        o.speeds.clear();
        for (int k = 0; k <= 20; ++k) o.speeds.push_back(from + (to - from) * k / 20.0);
    }
    o.progress = {};
    Diagnostics out;
    const CampbellStudy st = campbell_study(sys, o);
    add_notes(out, Topic::Solver, st.plan.notes);
    for (const Diagnostic& d : st.diagnostics)
        if (d.topic == Topic::Instability)
            out.push_back({Level::Warning, Topic::Instability,
                           d.text + "; the unbalance response there is not a steady state"});
    return out;
}

}  // namespace gyrokit
