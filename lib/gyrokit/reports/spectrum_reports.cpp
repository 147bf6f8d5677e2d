#include <gyrokit/reports/spectrum_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

namespace gyrokit {

using detail::ll;
using detail::mode_cells;

Table eig_table(const QuadraticSpectrum& s, double speed, const SpeedUnit& u, bool rigid_body) {
    Table t({u.column("speed"), "index", "re_1_s", "im_rad_s", u.column("frequency"), "whirl", "damping_ratio", "log_dec",
             "backward_error", "error_bound"});
    t.key = "eigenvalues";
    t.title = fmt::format("eigenvalues at {:.6g} ", u.factor * speed) + u.name +
              (s.infinite_count ? " (" + std::to_string(s.infinite_count) + " infinite eigenvalues omitted)" : "");
    int index = 0;
    const auto add = [&](const Mode& m, bool rigid) {
        std::vector<Cell> row{u.factor * speed, ll(++index)};
        for (auto& c : mode_cells(m, u)) row.push_back(c);
        if (rigid) row[5] = std::string("rigid-body");
        row.push_back(m.backward_error);
        row.push_back(m.error_bound);
        t.add_row(std::move(row));
    };
    for (const Mode& m : s.modes) add(m, false);
    if (rigid_body)
        for (const Mode& m : s.rigid_body) add(m, true);
    return t;
}

std::string rigid_body_note(const std::vector<Mode>& rigid, const std::vector<std::string>& names) {
    if (rigid.empty()) return "";
    std::vector<char> moves(names.size(), 0);
    for (const Mode& m : rigid) {
        const double top = m.right.cwiseAbs().maxCoeff();
        for (Eigen::Index i = 0; i < m.right.size() && static_cast<size_t>(i) < names.size(); ++i)
            if (std::abs(m.right(i)) >= 0.1 * top) moves[static_cast<size_t>(i)] = 1;
    }
    std::string list;
    int shown = 0, more = 0;
    for (size_t i = 0; i < names.size(); ++i) {
        if (!moves[i]) continue;
        if (shown < 12) list += (shown++ ? " " : "") + names[i];
        else ++more;
    }
    if (more) list += " and " + std::to_string(more) + " more";
    return std::to_string(rigid.size()) + " rigid-body eigenvalue" + (rigid.size() == 1 ? "" : "s") +
           " (lambda = 0: free motion of a singular K) " + (rigid.size() == 1 ? "is" : "are") +
           " not " + (rigid.size() == 1 ? "a mode" : "modes") + " and not listed; moving " + (list.empty() ? std::string("-") : list);
}

}  // namespace gyrokit
