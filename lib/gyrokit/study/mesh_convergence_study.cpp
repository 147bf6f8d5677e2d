#include <gyrokit/study/mesh_convergence_study.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The critical speeds and the frequencies at the top speed of one mesh.
MeshLevel solve_level(const RotorModel& base, int factor, const StudyOptions& opt, Diagnostics& diagnostics,
                      int& dofs_seen) {
    RotorModel m = base;
    MeshLevel level;
    level.factor = factor;
    for (RotorSection& s : m.sections) {
        if (!s.shape.coupling) s.elements *= factor;   // a coupling stays one element
        level.elements += s.elements;
    }
    const BuiltRotor built = build(m);
    level.dofs = built.system.size();
    dofs_seen = level.dofs;
    if (level.dofs > kMeshMaxDofs) return level;
    const CriticalSpeedStudy cs = critical_speed_study(built.system, opt);
    if (factor == 1)
        for (const Diagnostic& d : cs.tracked.diagnostics) diagnostics.push_back(d);
    for (const CriticalSpeed& c : cs.critical)
        if (c.harmonic == 1 && c.speed > 0) level.critical.push_back(c.speed);
    std::sort(level.critical.begin(), level.critical.end());
    const CampbellDiagram& cd = cs.tracked.diagram;
    const double top = opt.speeds.back();
    const auto take = [&](const std::vector<Branch>& branches) {
        for (const Branch& b : branches) {
            if (b.points.empty() || b.points.back().speed != top) continue;
            const double f = b.points.back().mode.frequency();
            if (f > 0 && f <= cd.band) level.frequencies.push_back(f);
        }
    };
    take(cd.branches);
    take(cd.untracked);
    std::sort(level.frequencies.begin(), level.frequencies.end());
    return level;
}

// The k-th value of each level (NaN where a level has fewer), its changes and where it converges.
MeshQuantity quantity(const std::string& name, const std::vector<MeshLevel>& levels, std::size_t k, bool critical,
                      double tol) {
    MeshQuantity q;
    q.name = name;
    for (const MeshLevel& l : levels) {
        const std::vector<double>& v = critical ? l.critical : l.frequencies;
        q.values.push_back(k < v.size() ? v[k] : kNaN);
    }
    for (std::size_t i = 0; i + 1 < q.values.size(); ++i)
        q.change.push_back(std::fabs(q.values[i + 1] - q.values[i]) / std::fabs(q.values[i + 1]));
    // The coarsest level from which every further change is below the tolerance.
    for (int i = static_cast<int>(q.change.size()) - 1; i >= 0 && q.change[i] < tol; --i) q.converged = i;
    return q;
}

// The quantities every mesh has: a mode that crosses f_cut, or a crossing that enters
// the speed range, as the mesh is refined is at the edge of what is judged, not a value
// that fails to converge (a note names them).
std::vector<MeshQuantity> quantities(const MeshConvergenceStudy& s) {
    std::size_t nc = s.levels.front().critical.size(), nf = s.levels.front().frequencies.size();
    for (const MeshLevel& l : s.levels) nc = std::min(nc, l.critical.size()), nf = std::min(nf, l.frequencies.size());
    std::vector<MeshQuantity> out;
    for (std::size_t k = 0; k < nc; ++k)
        out.push_back(quantity(fmt::format("critical speed {}", k + 1), s.levels, k, true, s.tolerance));
    for (std::size_t k = 0; k < nf; ++k)
        out.push_back(quantity(fmt::format("frequency {} at {:.6g} {}", k + 1, s.unit.factor * s.top_speed, s.unit.name),
                               s.levels, k, false, s.tolerance));
    return out;
}

}  // namespace

MeshConvergenceStudy mesh_convergence_study(const Scene& sc, const MeshConvergenceRequest& r) {
    const RotorModel* base = sc.rotor_model();
    if (!base)
        throw InputError(fmt::format("{}: mesh convergence refines an FE rotor's sections; this [model] is of type {}; "
                                     "allowed: fe_rotor",
                                     sc.path, sc.model_type()));
    MeshConvergenceStudy s;
    s.unit = resolve_unit(sc, r.unit);
    s.tolerance = r.tolerance.value_or(kMeshTolerance);
    if (!(s.tolerance > 0 && s.tolerance < 0.5))
        throw InputError(fmt::format("{} {}: allowed: (0, 0.5) (a relative change on doubling)",
                                     option_field("tolerance"), s.tolerance));
    const int levels = r.levels.value_or(kMeshLevels);
    if (levels < 2 || levels > 8)
        throw InputError(fmt::format("{} {}: allowed: [2, 8] (meshes x1 to x2^(levels - 1))", option_field("levels"),
                                     levels));
    StudyOptions opt = study_options(sc);
    if (opt.speeds.empty())
        throw InputError(fmt::format("{}: mesh convergence follows the critical speeds over the scene's [speeds]; "
                                     "required: a [speeds] table",
                                     sc.path));
    opt.unit = s.unit;
    opt.harmonics = {1};
    opt.amplification_factors = false;
    s.top_speed = opt.speeds.back();
    for (int l = 0; l < levels; ++l) {
        throw_if_interrupted();
        int dofs = 0;
        MeshLevel level = solve_level(*base, 1 << l, opt, s.diagnostics, dofs);
        if (dofs > kMeshMaxDofs) {
            s.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict,
                                     fmt::format("the mesh x{} has {} DOFs, above {}: not solved", 1 << l, dofs,
                                                 kMeshMaxDofs)});
            break;
        }
        s.levels.push_back(level);
        if (s.levels.size() < 2) continue;
        s.quantities = quantities(s);
        // Every quantity changed by less than the tolerance on this doubling: the previous mesh is chosen.
        const double tol = s.tolerance;
        const bool settled = std::all_of(s.quantities.begin(), s.quantities.end(),
                                         [tol](const MeshQuantity& q) { return q.change.back() < tol; });
        if (settled) break;
    }
    if (s.levels.size() < 2)
        throw InputError(fmt::format("{}: the {} mesh has more than {} DOFs; mesh convergence needs two meshes at "
                                     "most that large: fewer elements in the scene",
                                     sc.path, s.levels.empty() ? "scene's" : "scene's doubled", kMeshMaxDofs));
    s.quantities = quantities(s);
    // What some meshes have and others not (at the edges of the range and of f_cut).
    std::size_t most_c = 0, most_f = 0, least_c = s.levels.front().critical.size(),
                least_f = s.levels.front().frequencies.size();
    for (const MeshLevel& l : s.levels) {
        most_c = std::max(most_c, l.critical.size()), least_c = std::min(least_c, l.critical.size());
        most_f = std::max(most_f, l.frequencies.size()), least_f = std::min(least_f, l.frequencies.size());
    }
    if (most_c > least_c || most_f > least_f)
        s.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict,
                                 fmt::format("the meshes differ in number at the edges (critical speeds {} to {}, "
                                             "frequencies up to f_cut {} to {}): the quantities every mesh has are "
                                             "judged",
                                             least_c, most_c, least_f, most_f)});
    s.chosen = 0;
    for (const MeshQuantity& q : s.quantities) {
        if (q.converged < 0) {
            s.chosen = -1;
            break;
        }
        s.chosen = std::max(s.chosen, q.converged);
    }
    const int at = s.chosen >= 0 ? s.chosen : static_cast<int>(s.levels.size()) - 1;
    for (const RotorSection& sec : base->sections)
        s.section_elements.push_back(sec.shape.coupling ? sec.elements : sec.elements * s.levels[at].factor);
    if (s.chosen < 0)
        s.diagnostics.push_back({Diagnostic::Level::Warning, Diagnostic::Topic::Verdict,
                                 fmt::format("not converged: a quantity still changes by {:g} % or more on the last "
                                             "doubling (x{} to x{}); ask for more levels or a looser tolerance",
                                             100 * s.tolerance, s.levels[s.levels.size() - 2].factor,
                                             s.levels.back().factor)});
    if (s.quantities.empty())
        s.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict,
                                 "no critical speed in the range and no mode up to f_cut at the top speed: nothing "
                                 "to converge"});
    return s;
}

}  // namespace gyrokit
