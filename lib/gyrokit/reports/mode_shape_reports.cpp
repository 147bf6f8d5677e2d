#include <gyrokit/reports/mode_shape_reports.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/reports/detail/cells.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

namespace gyrokit {

using detail::ll;

namespace {

std::string mode_title(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u) {
    return fmt::format("mode shapes at {:.6g} {} ({} mode{})", u.factor * speed, u.name, shapes.size(),
                       shapes.size() == 1 ? "" : "s");
}

// Pairs a shape plot shows: those in metres, or all if none is.
std::vector<const PairOrbit*> shown_pairs(const ModeShape& s) {
    std::vector<const PairOrbit*> out;
    for (const auto& p : s.orbits)
        if (p.unit == "m") out.push_back(&p);
    if (out.empty())
        for (const auto& p : s.orbits) out.push_back(&p);
    return out;
}

}  // namespace

Table mode_list_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& names, double speed,
                      const SpeedUnit& u) {
    Table t({u.column("speed"), "mode", u.column("frequency"), "whirl", "damping_ratio", "largest", "error_bound"});
    t.key = "modes";
    t.title = mode_title(shapes, speed, u);
    for (const auto& s : shapes)
        t.add_row({u.factor * speed, ll(s.number), u.factor * s.mode.frequency(), to_string(s.mode.whirl),
                   s.mode.damping_ratio(), names[static_cast<size_t>(s.reference)], s.mode.error_bound});
    return t;
}

Table mode_orbit_table(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u, const LengthUnit& length) {
    // Node and axial position only for a model whose pairs sit on an axis.
    const bool nodes = !shapes.empty() && !shapes.front().orbits.empty() && shapes.front().orbits.front().node >= 0;
    std::vector<std::string> columns{u.column("speed"), "mode", u.column("frequency"), "pair"};
    if (nodes) columns.insert(columns.end(), {"node", length.column("z")});
    columns.insert(columns.end(), {"unit", "major", "minor", "angle_deg", "phase_deg", "whirl"});
    Table t(columns);
    t.key = "mode_orbits";
    t.title = mode_title(shapes, speed, u) + ": orbits, scaled to 1 at the largest entry";
    for (const auto& s : shapes) {
        for (const auto& p : s.orbits) {
            std::vector<Cell> row{u.factor * speed, ll(s.number), u.factor * s.mode.frequency(), p.name};
            if (nodes) row.insert(row.end(), {ll(p.node), length.in_unit(p.z)});
            row.insert(row.end(), {p.unit, p.orbit.major, p.orbit.minor, p.orbit.angle * kDegreesPerRadian,
                                   p.orbit.phase * kDegreesPerRadian, to_string(p.orbit.whirl)});
            t.add_row(std::move(row));
        }
    }
    return t;
}

Table mode_dof_table(const std::vector<ModeShape>& shapes, const std::vector<std::string>& names,
                     const std::vector<std::string>& units, double speed, const SpeedUnit& u) {
    Table t({u.column("speed"), "mode", u.column("frequency"), "dof", "unit", "re", "im", "amplitude", "phase_deg"});
    t.key = "mode_entries";
    t.title = mode_title(shapes, speed, u) + ": eigenvector entries, scaled to 1 at the largest";
    for (const auto& s : shapes) {
        for (Eigen::Index i = 0; i < s.shape.size(); ++i) {
            const auto x = s.shape(i);
            t.add_row({u.factor * speed, ll(s.number), u.factor * s.mode.frequency(), names[static_cast<size_t>(i)],
                       units.empty() ? std::string() : units[static_cast<size_t>(i)], x.real(), x.imag(),
                       std::abs(x), std::abs(x) == 0.0 ? 0.0 : std::arg(x) * kDegreesPerRadian});
        }
    }
    return t;
}

Figure mode_shape_figure(const std::vector<ModeShape>& shapes, double speed, const SpeedUnit& u,
                         const std::string& title, const LengthUnit& length, const AxisMarks& marks) {
    static const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                                   "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
    Figure f;
    f.title = (title.empty() ? std::string("Mode shapes") : title) +
              fmt::format(" at {:.6g} {}", u.factor * speed, u.name);
    const bool along_axis = !shapes.empty() && !shapes.front().orbits.empty() &&
                            std::all_of(shapes.front().orbits.begin(), shapes.front().orbits.end(),
                                        [](const PairOrbit& p) { return p.node >= 0; });
    const auto label = [&](size_t k) {
        const ModeShape& s = shapes[k];
        return fmt::format("mode {}: {:.5g} {} {}", s.number, u.factor * s.mode.frequency(), u.name,
                           to_string(s.mode.whirl));
    };
    if (along_axis) {
        const std::string z = "z [" + length.name + "]";
        Panel shape{z, "deflection at t = 0, plane of the largest entry", "", false, {}, {}, {}, {}, {}};
        Panel envelope{z, "orbit major semi-axis", "", false, {}, 0.0, {}, {}, {}};
        for (size_t k = 0; k < shapes.size(); ++k) {
            Series d, e;
            d.label = label(k);
            d.style = e.style = "linespoints";
            d.color = e.color = colors[k % 10];
            // The plane (u or v) in which the reference entry lies: there the shape is real at t = 0.
            const auto pairs = shown_pairs(shapes[k]);
            const bool v_plane = std::any_of(pairs.begin(), pairs.end(),
                                             [&](const PairOrbit* p) { return p->v == shapes[k].reference; });
            for (const PairOrbit* p : pairs) {
                d.x.push_back(length.in_unit(p->z));
                d.y.push_back(shapes[k].shape(v_plane ? p->v : p->u).real());
                e.x.push_back(length.in_unit(p->z));
                e.y.push_back(p->orbit.major);
            }
            shape.series.push_back(std::move(d));
            envelope.series.push_back(std::move(e));
        }
        // Disks, bearings and supports as points on the axis (deflection 0) of both panels.
        const auto mark = [&](const std::vector<double>& z, const char* what, const char* color) {
            if (z.empty()) return;
            Series m{{}, {}, what, "points", color};
            for (double zi : z) m.x.push_back(length.in_unit(zi)), m.y.push_back(0.0);
            shape.series.push_back(m);
            m.label.clear();
            envelope.series.push_back(std::move(m));
        };
        mark(marks.disks, "disks", "#000000");
        mark(marks.bearings, "bearings", "#7f7f7f");
        mark(marks.supports, "supports", "#bcbd22");
        f.panels = {std::move(shape), std::move(envelope)};
        return f;
    }
    // No axis: each mode's orbits, u(t) against v(t) over one period.
    for (size_t k = 0; k < shapes.size(); ++k) {
        Panel orbits{"u", "v", label(k), false, {}, {}, {}, {}, {}};
        orbits.equal_axes = true;
        int c = 0;
        for (const PairOrbit* p : shown_pairs(shapes[k])) {
            // The orbit, and its first eighth thicker as points: the sense of the whirl.
            Series e, start;
            e.label = p->name;
            e.color = start.color = colors[c++ % 10];
            start.style = "points";
            for (int i = 0; i <= 72; ++i) {
                const std::complex<double> phase = std::polar(1.0, 2.0 * kPi * i / 72.0);
                e.x.push_back((shapes[k].shape(p->u) * phase).real());
                e.y.push_back((shapes[k].shape(p->v) * phase).real());
                if (i <= 9) start.x.push_back(e.x.back()), start.y.push_back(e.y.back());
            }
            orbits.series.push_back(std::move(e));
            orbits.series.push_back(std::move(start));
        }
        f.panels.push_back(std::move(orbits));
    }
    return f;
}

}  // namespace gyrokit
