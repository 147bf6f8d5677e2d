#include <gyrokit/study/response_study.hpp>

#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/reports/response_reports.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace gyrokit {

ResponseStudy response_study(const GyroscopicSystem& sys, const StudyOptions& opt, const ResponseRequest& r) {
    using Topic = Diagnostic::Topic;
    if (opt.speeds.empty())
        throw InputError(option_field("speeds") + " (none): allowed: at least one speed in rad/s");
    if (!r.probes.empty() && !r.outputs.empty())
        throw InputError("probes and DOFs: allowed: one of them (probes alone, or the DOFs reported)");
    for (const int k : r.outputs)
        if (k < 0 || k >= sys.size())
            throw InputError(fmt::format("output DOF {}: allowed: 0 to {} (the model's DOFs)", k, sys.size() - 1));
    sys.validate("response: the system");
    ResponseStudy s;
    // The sparse LU of the dynamic stiffness where the solver choice is sparse.
    const SolverKind kind = resolve_solver_kind(sys.size(), opt.solver.kind);
    // Output space: the model's DOFs (names, units), or the probes' readings (in m).
    const bool probed = !r.probes.empty();
    std::vector<std::string> si_units;
    if (probed) {
        for (const Probe& p : r.probes) s.names.push_back(p.name), si_units.push_back("m");
    } else {
        s.names = sys.dofs.names;
        si_units = sys.dofs.units;
    }
    const int count = probed ? static_cast<int>(r.probes.size()) : sys.size();
    // Lengths as the scene states them (an mm scene prints mm); models without DOF units as they are.
    Eigen::VectorXd shown_per_si = Eigen::VectorXd::Ones(count);
    for (std::size_t k = 0; k < si_units.size() && static_cast<int>(k) < count; ++k)
        shown_per_si(static_cast<Eigen::Index>(k)) = r.length.display_factor(si_units[k]);
    s.units = si_units.empty() ? std::vector<std::string>(static_cast<std::size_t>(count), "")
                               : r.length.display_units(si_units);
    const ResponseSolver in_si = [&](double w) -> Eigen::VectorXcd {
        const Eigen::VectorXcd Z = unbalance_response(sys, w, kind);
        if (!probed) return Z;
        Eigen::VectorXcd reading(count);
        for (int k = 0; k < count; ++k) reading(k) = probe_response(r.probes[static_cast<std::size_t>(k)], Z);
        return reading;
    };
    const ResponseSolver shown = [&](double w) -> Eigen::VectorXcd {
        return in_si(w).cwiseProduct(shown_per_si.cast<std::complex<double>>());
    };
    const auto [lowest, highest] = std::minmax_element(opt.speeds.begin(), opt.speeds.end());   // in any order
    add_notes(s.diagnostics, Topic::Extrapolation, extrapolation_notes(sys.bearings, *lowest, *highest));
    const ResponseCurve si = unbalance_response(in_si, count, opt.speeds, r.outputs);
    s.si = si.Z;
    s.curve = si;
    for (std::size_t j = 0; j < si.dofs.size(); ++j)
        s.curve.Z.col(static_cast<Eigen::Index>(j)) *= shown_per_si(si.dofs[j]);
    if (r.stability_check)
        for (Diagnostic& d : response_stability_warnings(sys, opt)) s.diagnostics.push_back(std::move(d));
    // Peaks refined between grid speeds (a grid maximum can lie far below a sharp
    // resonance's); without them the maxima are the grid's.
    if (r.peaks) s.extrema = response_extrema(shown, s.curve, !r.antiresonances);
    s.maxima = response_maxima(s.curve, s.extrema);
    if (r.outputs.empty() && s.curve.dofs.size() > 6) s.plotted = largest_responses(s.units, s.maxima, 6);
    return s;
}

}  // namespace gyrokit
