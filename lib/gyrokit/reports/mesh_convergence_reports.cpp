#include <gyrokit/reports/mesh_convergence_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

using detail::ll;

Table mesh_summary(const MeshConvergenceStudy& s) {
    Table t({"quantity", "value"});
    t.key = "mesh_summary";
    t.title = "mesh convergence: summary";
    const auto row = [&](const char* q, const std::string& v) { t.add_row({std::string(q), v}); };
    const auto level_text = [&](const MeshLevel& l) {
        return fmt::format("x{}: {} elements, {} DOFs", l.factor, l.elements, l.dofs);
    };
    row("verdict", s.chosen >= 0 ? "converged" : "not converged");
    row("tolerance", fmt::format("{:g} % change on doubling", 100 * s.tolerance));
    for (const MeshLevel& l : s.levels) row("mesh", level_text(l));
    if (s.chosen >= 0) row("chosen", level_text(s.levels[static_cast<std::size_t>(s.chosen)]));
    std::string counts;
    for (const int n : s.section_elements) counts += (counts.empty() ? "" : ", ") + std::to_string(n);
    row(s.chosen >= 0 ? "section elements (chosen)" : "section elements (finest)", counts);
    row("quantities", fmt::format("{} (critical speeds over the scene's speeds, frequencies up to f_cut at {:.6g} {})",
                                  s.quantities.size(), s.unit.factor * s.top_speed, s.unit.name));
    return t;
}

Table mesh_quantities(const MeshConvergenceStudy& s) {
    Table t({"quantity", "factor", "elements", "dofs", s.unit.column("value"), "change_percent", "converged"});
    t.key = "mesh_quantities";
    t.title = "mesh convergence: each quantity at each mesh (change: to the next doubling)";
    for (const MeshQuantity& q : s.quantities)
        for (std::size_t i = 0; i < s.levels.size(); ++i) {
            const MeshLevel& l = s.levels[i];
            const double v = q.values[i];
            const bool has_change = i < q.change.size() && std::isfinite(q.change[i]);
            t.add_row({q.name, ll(l.factor), ll(l.elements), ll(l.dofs),
                       std::isfinite(v) ? Cell(s.unit.factor * v) : Cell(std::string("-")),
                       has_change ? Cell(std::stod(fmt::format("{:.3g}", 100 * q.change[i]))) : Cell(std::string("-")),
                       q.converged >= 0 && static_cast<int>(i) >= q.converged});
        }
    return t;
}

std::vector<Table> mesh_tables(const MeshConvergenceStudy& s) { return {mesh_summary(s), mesh_quantities(s)}; }

}  // namespace gyrokit
