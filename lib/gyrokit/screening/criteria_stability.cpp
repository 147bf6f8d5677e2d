// The stability criterion: the onset of instability and the least log decrement.
#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/solve/continuation.hpp>
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/analysis/energy_bound.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/analysis/probe.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/screening/detail/probes.hpp>
#include <gyrokit/screening/detail/row.hpp>
#include <gyrokit/screening/screening.hpp>
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/response_study.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <memory>
#include <stdexcept>

namespace gyrokit::screening_detail {

// The least damped oscillating mode in range of a diagram: the smallest logarithmic
// decrement -2 pi Re(lambda)/Im(lambda) over its branches and speeds (0 for a neutral
// mode, negative for an unstable one) where the frequency lies within `band` (the
// excitation band of the scan). Real eigenvalues (overdamped, divergent) have no
// decrement and rigid-body eigenvalues are no branches. None: no such mode.
struct LeastLogDecrement {
    const Branch* branch = nullptr;
    double log_dec = inf, speed = 0;
};

LeastLogDecrement least_log_decrement(const CampbellDiagram& cd, double band) {
    LeastLogDecrement out;
    for (const auto* list : {&cd.branches, &cd.untracked})   // the shown modes and the others judged
        for (const Branch& b : *list)
        for (const BranchPoint& p : b.points) {
            if (p.mode.whirl == Whirl::Real || !(p.mode.lambda.imag() > 0.0) || p.mode.lambda.imag() > band) continue;
            const double d = p.mode.log_decrement();
            if (d < out.log_dec) out.log_dec = d, out.speed = p.speed, out.branch = &b;
        }
    return out;
}

// min_log_dec: the least log decrement and its speed into the columns after the
// onset; below the limit, stability fails (an unstable mode's reason gains it).
void check_log_dec(const Sweep& s, const CampbellDiagram& cd, const StudyOptions& so, const StabilityCriterion& c,
                   bool unstable, Row& row) {
    // The modes in range: what the speeds and harmonics can excite (a mesh's highest
    // modes, barely damped by the bearings, are no stability margin to keep).
    const LeastLogDecrement ld = least_log_decrement(cd, judged_band(so.f_cut, so.speeds, so.harmonics));
    if (!ld.branch) return;   // no oscillating mode in range: nothing rings
    row.set("min_log_dec", ld.log_dec);
    row.set(s.unit.column("min_log_dec_speed"), ld.speed * s.unit.factor);
    if (!(ld.log_dec < *c.min_log_dec)) return;
    const std::string what = fmt::format("log decrement {:.4g} (mode {} at {:.6g} {}), required {:.4g}", ld.log_dec,
                                         ld.branch->id, ld.speed * s.unit.factor, s.unit.name, *c.min_log_dec);
    if (unstable) {
        row.result.reason += ", least " + what;
        return;
    }
    row.fail("stability", fmt::format("{}, short by {:.3g} (checked up to {:.6g} {})",
                                      what, *c.min_log_dec - ld.log_dec, c.up_to * s.unit.factor, s.unit.name));
}

// A mode above the band that grows: the first speed of `speeds` below `before` at which
// one does (Re lambda beyond its bound), refined by bisection to 1e-9 of the speed.
struct GrowingAbove {
    double speed = inf;
    double frequency = 0;
};

// The modes above the band need no tracking for a verdict: the full spectrum at a speed
// says whether any of them grows, whatever their order (tracking them through their
// crossings would insert thousands of speeds on a mesh's highest modes).
GrowingAbove growing_above_band(const GyroscopicSystem& sys, const EigenOptions& eig,
                                const std::vector<double>& speeds, double band, double before) {
    SpectrumSolver solve = dense_solver(sys, eig)();
    GrowingAbove out;
    const auto grows = [&](double w) {
        const QuadraticSpectrum sp = solve(w);
        for (const Mode& m : sp.modes)
            if (!within_band(m, band, sp.real_tol) && m.stability() == Stability::Unstable) {
                out.frequency = std::abs(m.lambda.imag()) > sp.real_tol ? m.lambda.imag() : 0.0;   // 0: diverges
                return true;
            }
        return false;
    };
    for (std::size_t k = 0; k < speeds.size() && speeds[k] < before; ++k) {
        throw_if_interrupted();
        if (!grows(speeds[k])) continue;
        double a = k > 0 ? speeds[k - 1] : speeds[k], b = speeds[k];
        while (b - a > 1e-9 * b) {
            const double m = 0.5 * (a + b);
            (grows(m) ? b : a) = m;
        }
        grows(b);   // the frequency at the refined onset
        out.speed = b;
        return out;
    }
    return out;
}

void check_stability(const Sweep& s, const Scene& sc, const StabilityCriterion& c, Row& row) {
    // The stability study of the CLI and Python, but a design is judged on every mode
    // unless the scene names a number: the modes in range are tracked, and those above
    // the band are covered by the energy bound where it shows that none of them can grow
    // (symmetric stiffness, damping that dissipates); else a dense model's full spectrum
    // at each speed judges them (growing_above_band), a sparse model's window every mode.
    StudyOptions so = study_options(sc);
    so.workers = 1;   // the designs run in parallel, each on one worker
    so.speeds = SpeedRange{0.0, c.up_to, c.count}.points();
    const double band = judged_band(so.f_cut, so.speeds, so.harmonics);
    bool scan_above = false;
    if (so.solver.modes == kModesInRange && !modes_above_band_decay(sc.system, so.speeds, band)) {
        if (resolve_solver_kind(sc.dofs(), so.solver.kind, so.solver.modes) == SolverKind::Dense)
            scan_above = true;
        else
            so.solver.modes = 0;
    }
    const StabilityStudy st = stability_study(sc.system, so);
    const CampbellDiagram& cd = st.tracked.diagram;
    // The earliest onset of any judged mode, as the study refined it.
    double onset = inf;
    const UnstableRange* which = nullptr;
    for (const UnstableRange& r : st.tracked.unstable)
        if (r.from < onset) onset = r.from, which = &r;
    const GrowingAbove above = scan_above ? growing_above_band(sc.system, so.solver.eig, so.speeds, band, onset) : GrowingAbove{};
    if (above.speed < onset) {
        row.set(s.unit.column("instability_onset"), above.speed * s.unit.factor);
        const std::string what = above.frequency > 0.0
                                     ? fmt::format("a mode above the range ({:.6g} {} at the onset)",
                                                   above.frequency * s.unit.factor, s.unit.name)
                                     : std::string("a real eigenvalue above the range (divergence)");
        row.fail("stability", fmt::format("{} is unstable from {:.6g} {} (checked up to {:.6g} {})", what,
                                          above.speed * s.unit.factor, s.unit.name, c.up_to * s.unit.factor,
                                          s.unit.name));
    } else if (which) {
        row.set(s.unit.column("instability_onset"), onset * s.unit.factor);
        row.fail("stability", fmt::format("mode {} is unstable from {:.6g} {} (checked up to {:.6g} {})", which->branch,
                                          onset * s.unit.factor, s.unit.name, c.up_to * s.unit.factor, s.unit.name));
    }
    if (c.min_log_dec) check_log_dec(s, cd, so, c, which != nullptr || above.speed < inf, row);
}

}  // namespace gyrokit::screening_detail
