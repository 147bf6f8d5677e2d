#include <gyrokit/core/bearing_table.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

namespace gyrokit {

std::string BearingTable::label() const {
    const std::string file = std::filesystem::path(name).filename().string();
    return file.empty() ? name : file;
}

BearingCoefficients BearingTable::at(double w) const {
    if (model) return model(std::max(w, speeds.front()));
    if (w <= speeds.front()) return rows.front();
    if (w >= speeds.back()) return rows.back();
    const size_t j = static_cast<size_t>(std::upper_bound(speeds.begin(), speeds.end(), w) - speeds.begin());
    const double t = (w - speeds[j - 1]) / (speeds[j] - speeds[j - 1]);
    BearingCoefficients c;
    c.K = (1.0 - t) * rows[j - 1].K + t * rows[j].K;
    c.C = (1.0 - t) * rows[j - 1].C + t * rows[j].C;
    return c;
}

bool BearingTable::covers(double w) const { return w >= speeds.front() && (model || w <= speeds.back()); }

bool BearingTable::has_damping() const {
    if (model) return model(speeds.front()).C.cwiseAbs().maxCoeff() > 0.0;
    for (const auto& r : rows)
        if (r.C.cwiseAbs().maxCoeff() > 0.0) return true;
    return false;
}

void BearingTable::validate_rows() const {
    if (speeds.size() < 2)
        throw InputError(fmt::format("bearing table {}: {} speed row(s); allowed: at least 2 rows to interpolate "
                                     "between",
                                     name, speeds.size()));
    if (rows.size() != speeds.size())
        throw InputError(fmt::format("bearing table {}: {} coefficient rows for {} speeds", name, rows.size(),
                                     speeds.size()));
    for (size_t i = 0; i < speeds.size(); ++i) {
        if (!std::isfinite(speeds[i]) || speeds[i] < 0.0)
            throw InputError(fmt::format("bearing table {}: speed {} in row {}; allowed: finite and >= 0", name,
                                         speeds[i], i + 1));
        if (i > 0 && !(speeds[i] > speeds[i - 1]))
            throw InputError(fmt::format("bearing table {}: speed {} in row {} does not exceed {} in row {}; "
                                         "allowed: strictly increasing speeds",
                                         name, speeds[i], i + 1, speeds[i - 1], i));
        if (!rows[i].K.allFinite() || !rows[i].C.allFinite())
            throw InputError(fmt::format("bearing table {}: row {} has a NaN or infinite coefficient; allowed: "
                                         "finite numbers",
                                         name, i + 1));
    }
}

void BearingTable::validate(int dofs) const {
    if (model) {
        if (speeds.size() != 1 || !(speeds.front() > 0.0) || !std::isfinite(speeds.front()))
            throw InputError(fmt::format("bearing {}: the model holds its values below {} rad/s; allowed: one "
                                         "finite speed > 0",
                                         name, speeds.empty() ? NAN : speeds.front()));
        const BearingCoefficients c = model(speeds.front());
        if (!c.K.allFinite() || !c.C.allFinite())
            throw InputError(fmt::format("bearing {}: a NaN or infinite coefficient at {} rad/s", name,
                                         speeds.front()));
    } else {
        validate_rows();
    }
    for (const auto& [key, v] : {std::pair{"dof_x", dof_x}, std::pair{"dof_y", dof_y}})
        if (v < 0 || v >= dofs)
            throw InputError(fmt::format("bearing table {}: {} = {} is out of range; allowed: 0 to {} (0-based DOF "
                                         "index)",
                                         name, key, v, dofs - 1));
    if (dof_x == dof_y)
        throw InputError(fmt::format("bearing table {}: dof_x = dof_y = {}; allowed: two distinct DOFs", name,
                                     dof_x));
    if (pedestal_x >= 0 || pedestal_y >= 0) {
        for (const auto& [key, v] : {std::pair{"pedestal_x", pedestal_x}, std::pair{"pedestal_y", pedestal_y}})
            if (v < 0 || v >= dofs || v == dof_x || v == dof_y)
                throw InputError(fmt::format("bearing table {}: {} = {} is out of range; allowed: 0 to {} (0-based "
                                             "DOF index), not dof_x or dof_y",
                                             name, key, v, dofs - 1));
        if (pedestal_x == pedestal_y)
            throw InputError(fmt::format("bearing table {}: pedestal_x = pedestal_y = {}; allowed: two distinct DOFs",
                                         name, pedestal_x));
    }
}

std::vector<std::string> extrapolation_notes(const std::vector<BearingTable>& tables, double from, double to) {
    std::vector<std::string> notes;
    for (const auto& t : tables)
        if (t.model && !t.covers(from))
            notes.push_back(fmt::format("bearing {}: below {:g} rad/s its coefficients at {:g} rad/s hold (the film "
                                        "would be thinner than max_eccentricity allows; {} {:g} rad/s requested)",
                                        t.name, t.speeds.front(), t.speeds.front(), from == to ? "at" : "from", from));
        else if (!t.model && (!t.covers(from) || !t.covers(to)))
            notes.push_back(from == to ? fmt::format("bearing table {} covers {:g} to {:g} rad/s; the speed {:g} rad/s "
                                                     "outside it uses its end row (held constant)",
                                                     t.name, t.speeds.front(), t.speeds.back(), from)
                                       : fmt::format("bearing table {} covers {:g} to {:g} rad/s; the speeds {:g} to "
                                                     "{:g} rad/s outside it use its end rows (held constant)",
                                                     t.name, t.speeds.front(), t.speeds.back(), from, to));
    return notes;
}

}  // namespace gyrokit
