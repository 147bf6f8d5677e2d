// Cells and labels every report family shares.
#pragma once

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/eig/mode.hpp>
#include <gyrokit/io/table.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace gyrokit::detail {

inline long long ll(int i) { return static_cast<long long>(i); }

inline double degrees(double rad) { return rad * 180.0 / kPi; }

inline std::vector<Cell> mode_cells(const Mode& m, const SpeedUnit& u) {
    // A real part within its error bound is neutral and shown as 0 (Mode::real_part).
    return {m.real_part(), m.lambda.imag(), u.factor * m.frequency(), to_string(m.whirl), m.damping_ratio(),
            m.log_decrement()};
}

inline std::string speed_label(const SpeedUnit& u) { return "speed [" + u.name + "]"; }

inline std::string unit_of(const std::vector<std::string>& units, int dof) {
    return units.empty() ? std::string() : units[static_cast<size_t>(dof)];
}

// The units of the DOFs: metres first (displacements are what one reads first), then in first-seen order.
inline std::vector<std::string> units_in(const std::vector<std::string>& units, const std::vector<int>& dofs) {
    std::vector<std::string> out;
    for (const int k : dofs)
        if (std::find(out.begin(), out.end(), unit_of(units, k)) == out.end()) out.push_back(unit_of(units, k));
    std::stable_partition(out.begin(), out.end(), [](const std::string& u) { return u == "m"; });
    return out;
}

}  // namespace gyrokit::detail
