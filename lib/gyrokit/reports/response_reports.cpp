#include <gyrokit/reports/response_reports.hpp>

#include <gyrokit/io/svg_figure.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

namespace gyrokit {

using detail::speed_label;
using detail::unit_of;
using detail::units_in;

void to_length_unit(const std::vector<int>& outputs, Eigen::MatrixXcd& Z, std::vector<std::string>& units,
                    const LengthUnit& length) {
    if (units.empty()) return;   // a model without DOF units: as it is
    for (std::size_t j = 0; j < outputs.size(); ++j)
        Z.col(static_cast<Eigen::Index>(j)) *= length.display_factor(units.at(static_cast<std::size_t>(outputs[j])));
    units = length.display_units(units);
}

Table response_table(const std::vector<std::string>& names, const std::vector<std::string>& units,
                     const ResponseCurve& c, const SpeedUnit& u) {
    Table t({u.column("speed"), "dof", "unit", "amplitude", "phase_deg"});
    t.key = "response";
    t.title = "unbalance response z = Re(Z e^{i w t}); amplitude |Z| in the DOF's unit, phase arg Z in degrees";
    for (size_t i = 0; i < c.speeds.size(); ++i)
        for (size_t k = 0; k < c.dofs.size(); ++k) {
            const auto z = c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
            t.add_row({u.factor * c.speeds[i], names[static_cast<size_t>(c.dofs[k])], unit_of(units, c.dofs[k]),
                       std::abs(z), std::abs(z) == 0.0 ? 0.0 : std::arg(z) * 180.0 / kPi});
        }
    return t;
}

namespace {

// Maxima by unit (first-seen order), then by amplitude, largest first.
std::vector<ResponseMaximum> by_unit_and_size(const std::vector<std::string>& units,
                                              std::vector<ResponseMaximum> m) {
    std::vector<int> dofs;
    for (const auto& x : m) dofs.push_back(x.dof);
    const std::vector<std::string> order = units_in(units, dofs);
    const auto rank = [&](int dof) {
        return std::find(order.begin(), order.end(), unit_of(units, dof)) - order.begin();
    };
    // Amplitudes equal to 9 digits (x and y of an isotropic rotor) keep the model's DOF order, whatever rounding says.
    const auto size = [](double a) { return std::stod(fmt::format("{:.9g}", a)); };
    std::stable_sort(m.begin(), m.end(), [&](const ResponseMaximum& a, const ResponseMaximum& b) {
        if (rank(a.dof) != rank(b.dof)) return rank(a.dof) < rank(b.dof);
        return size(a.amplitude) != size(b.amplitude) ? size(a.amplitude) > size(b.amplitude) : a.dof < b.dof;
    });
    return m;
}

}  // namespace

Table response_summary(const std::vector<std::string>& names, const std::vector<std::string>& units,
                       const std::vector<ResponseMaximum>& maxima, const SpeedUnit& u, std::size_t limit) {
    Table t({"dof", "unit", "max_amplitude", u.column("speed"), "where"});
    t.key = "response_maxima";
    std::size_t left_out = 0, in_unit = 0;
    std::string unit;
    for (const auto& m : by_unit_and_size(units, maxima)) {
        if (unit_of(units, m.dof) != unit) unit = unit_of(units, m.dof), in_unit = 0;
        if (limit > 0 && in_unit++ >= limit) {
            ++left_out;
            continue;
        }
        t.add_row({names[static_cast<size_t>(m.dof)], unit_of(units, m.dof), m.amplitude, u.factor * m.speed,
                   std::string(!m.bounded ? "undamped resonance (unbounded)"
                               : m.refined ? "peak (refined)"
                                           : "range end")});
    }
    const auto unbounded = std::count_if(maxima.begin(), maxima.end(), [](const ResponseMaximum& m) { return !m.bounded; });
    t.title = "largest unbalance response per DOF (peaks refined between grid speeds)" +
              (left_out ? fmt::format("; {} smaller ones left out", left_out) : std::string()) +
              (unbounded ? fmt::format("; {} DOF(s) pass an undamped resonance (damping ratio below 6e-7): "
                                       "unbounded there, add damping to the model",
                                       unbounded)
                         : std::string());
    return t;
}

std::vector<int> largest_responses(const std::vector<std::string>& units, const std::vector<ResponseMaximum>& maxima,
                                   std::size_t per_unit) {
    std::vector<int> out;
    std::size_t in_unit = 0;
    std::string unit;
    for (const auto& m : by_unit_and_size(units, maxima)) {
        if (unit_of(units, m.dof) != unit) unit = unit_of(units, m.dof), in_unit = 0;
        if (in_unit++ < per_unit) out.push_back(m.dof);
    }
    return out;
}

Table extrema_table(const std::vector<std::string>& names, const std::vector<std::string>& units,
                    const std::vector<ResponseExtremum>& e, const SpeedUnit& u) {
    Table t({"dof", "unit", "kind", u.column("speed"), "amplitude"});
    t.key = "response_peaks";
    t.title = "response peaks and antiresonances";
    for (const auto& x : e)
        t.add_row({names[static_cast<size_t>(x.dof)], unit_of(units, x.dof),
                   std::string(!x.bounded ? "unbounded peak" : x.peak ? "peak" : "antiresonance"),
                   u.factor * x.speed, x.amplitude});
    return t;
}

namespace {

// Columns of the curve to draw: `shown` (model DOFs), or all.
std::vector<size_t> columns_shown(const ResponseCurve& c, const std::vector<int>& shown) {
    std::vector<size_t> cols;
    for (size_t k = 0; k < c.dofs.size(); ++k)
        if (shown.empty() || std::find(shown.begin(), shown.end(), c.dofs[k]) != shown.end()) cols.push_back(k);
    return cols;
}

std::string amplitude_label(const std::string& unit, const std::string& what) {
    return unit.empty() ? what : what + " [" + unit + "]";
}

// The response's symbol: H for a frequency response (per unit force), Z for the unbalance response.
std::string symbol_of(const std::string& axis) { return axis == "frequency" ? "H" : "Z"; }

// A power of 1000 that brings the largest |value| of the panel to [1, 1000): tick labels
// such as -80 read where -8e-08 would run into its neighbours.
double engineering_scale(const Panel& p) {
    double top = 0.0;
    for (const Series& s : p.series)
        for (std::size_t i = 0; i < s.x.size(); ++i)   // an undamped resonance's point (inf) does not set the scale
            for (const double v : {s.x[i], s.y[i]})
                if (std::isfinite(v)) top = std::max(top, std::abs(v));
    if (!(top > 0.0) || !std::isfinite(top)) return 1.0;
    return std::pow(10.0, 3.0 * std::floor(std::log10(top) / 3.0));
}

}  // namespace

Figure response_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                       const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                       const std::vector<int>& shown, const std::string& axis, bool log_amplitude) {
    Figure f;
    f.title = title.empty() ? "Unbalance response" : title;
    const std::vector<size_t> cols = columns_shown(c, shown);
    std::vector<int> dofs;
    for (const size_t k : cols) dofs.push_back(c.dofs[k]);
    const std::string xlabel = axis + " [" + u.name + "]";
    Panel ph{xlabel, "phase [deg]", "", false, {}, -180.0, 180.0, {}, {}};
    for (const std::string& unit : units_in(units, dofs)) {
        Panel amp{xlabel, amplitude_label(unit, "amplitude |" + symbol_of(axis) + "|"), "", log_amplitude, {}, {}, {},
                  {}, {}};
        for (const size_t k : cols) {
            if (unit_of(units, c.dofs[k]) != unit) continue;
            Series a, p;
            a.label = p.label = names[static_cast<size_t>(c.dofs[k])];
            for (size_t i = 0; i < c.speeds.size(); ++i) {
                const auto z = c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
                a.x.push_back(u.factor * c.speeds[i]);
                a.y.push_back(std::abs(z));
                p.x.push_back(a.x.back());
                p.y.push_back(std::abs(z) == 0.0 ? 0.0 : std::arg(z) * 180.0 / kPi);
            }
            amp.series.push_back(std::move(a));
            ph.series.push_back(std::move(p));
        }
        f.panels.push_back(std::move(amp));
    }
    f.panels.push_back(std::move(ph));
    return f;
}

namespace {

// The grid points a polar plot marks with their speed (or frequency): for each round value
// inside the range (1, 2 or 5 x 10^k apart, about six; 0 left out, the origin of a response
// that starts at rest), the grid point nearest it, labelled with the grid's own value.
std::vector<std::string> polar_marks(const std::vector<double>& speeds, const SpeedUnit& u) {
    std::vector<std::string> labels(speeds.size());
    if (speeds.size() < 2) return labels;
    const double lo = u.factor * speeds.front(), hi = u.factor * speeds.back();
    if (!(hi > lo)) return labels;
    for (const double t : axis_ticks(lo, hi, false, 6)) {
        if (t == 0.0 || t < lo || t > hi) continue;
        std::size_t best = 0;
        for (std::size_t i = 1; i < speeds.size(); ++i)
            if (std::abs(u.factor * speeds[i] - t) < std::abs(u.factor * speeds[best] - t)) best = i;
        labels[best] = fmt::format("{:.6g} {}", u.factor * speeds[best], u.name);   // 15000, not 1.5e+04
    }
    return labels;
}

// A mark within 4 % of the panel's extent of an earlier one on its curve is left out: where
// the curve lingers (far above a resonance) the labels would print over each other.
void thin_marks(Panel& p) {
    double lo = 0.0, hi = 0.0;
    for (const Series& s : p.series)
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
                lo = std::min({lo, s.x[i], s.y[i]}), hi = std::max({hi, s.x[i], s.y[i]});
    const double near = 0.04 * (hi - lo);
    for (Series& s : p.series) {
        std::vector<std::size_t> kept;
        for (std::size_t i = 0; i < s.point_labels.size(); ++i) {
            if (s.point_labels[i].empty()) continue;
            bool crowded = false;
            for (const std::size_t j : kept) crowded = crowded || std::hypot(s.x[i] - s.x[j], s.y[i] - s.y[j]) < near;
            if (crowded) s.point_labels[i].clear();
            else kept.push_back(i);
        }
    }
}

}  // namespace

Figure response_polar_figure(const std::vector<std::string>& names, const std::vector<std::string>& units,
                             const ResponseCurve& c, const SpeedUnit& u, const std::string& title,
                             const std::vector<int>& shown, const std::string& axis) {
    Figure f;
    f.title = (title.empty() ? std::string("Unbalance response") : title) +
              fmt::format(" (polar, {} {:.6g} to {:.6g} {})", axis, u.factor * c.speeds.front(),
                          u.factor * c.speeds.back(), u.name);
    // True to shape, the plot is a square as high as the panel: taller panels give the
    // horizontal tick labels room.
    f.height_per_panel = 640;
    const std::vector<size_t> cols = columns_shown(c, shown);
    std::vector<int> dofs;
    for (const size_t k : cols) dofs.push_back(c.dofs[k]);
    for (const std::string& unit : units_in(units, dofs)) {
        const std::string z = symbol_of(axis);
        Panel p{"", "", "", false, {}, {}, {}, {}, {}};
        p.equal_axes = true;
        for (const size_t k : cols) {
            if (unit_of(units, c.dofs[k]) != unit) continue;
            Series s;
            s.label = names[static_cast<size_t>(c.dofs[k])];
            for (size_t i = 0; i < c.speeds.size(); ++i) {
                const auto z = c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k));
                s.x.push_back(z.real());
                s.y.push_back(z.imag());
            }
            s.point_labels = polar_marks(c.speeds, u);   // where along the curve each speed lies
            // Its own colour, so that the marks read with their curve.
            static const char* const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
            s.color = palette[p.series.size() % 6];
            p.series.push_back(std::move(s));
        }
        const double scale = engineering_scale(p);
        for (Series& s : p.series)
            for (std::size_t i = 0; i < s.x.size(); ++i) s.x[i] /= scale, s.y[i] /= scale;
        thin_marks(p);
        const std::string per = scale == 1.0 ? unit : fmt::format("{:g} {}", scale, unit.empty() ? "1" : unit);
        p.xlabel = amplitude_label(per, "Re " + z);
        p.ylabel = amplitude_label(per, "Im " + z);
        f.panels.push_back(std::move(p));
    }
    return f;
}

}  // namespace gyrokit
