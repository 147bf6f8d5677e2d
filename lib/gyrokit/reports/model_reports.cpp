#include <gyrokit/reports/model_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>
#include <gyrokit/solve/solver_choice.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

namespace gyrokit {

using detail::ll;

namespace {

// A solid cylinder of mass m with the inertias Ip = m r^2 / 2 and Id = m (3 r^2 + w^2) / 12:
// the radius and width a disk given by (m, Id, Ip) would have.
std::pair<double, double> disk_cylinder(const FeDisk& d) {
    if (d.mass <= 0.0) return {0.0, 0.0};
    const double r = std::sqrt(2.0 * d.polar_inertia / d.mass);
    const double w2 = 12.0 * d.diametral_inertia / d.mass - 3.0 * r * r;
    return {r, w2 > 0.0 ? std::sqrt(w2) : 0.0};
}

}  // namespace

namespace {

// The shaft node a speed-dependent bearing stands at (-1: none): its x DOF's node, or
// the node of the pedestal it acts on (a held shaft: px<node>).
int bearing_node(const GyroscopicSystem& s, const BearingTable& b) {
    if (s.dofs.nodes.empty()) return -1;
    const int node = s.dofs.nodes[static_cast<size_t>(b.dof_x)];
    return node >= 0 ? node : s.dofs.pedestal_node(b.dof_x);
}

// Circulatory forces: a speed-proportional N, or a skew part of the stiffness (cross-coupled
// bearings, constant or speed-dependent: the usual cause of oil whip).
std::string circulatory(const GyroscopicSystem& s) {
    const bool skew_K = SparseMatrix(s.K - SparseMatrix(s.K.transpose())).norm() > 0.0;
    const bool skew_tables = std::any_of(s.bearings.begin(), s.bearings.end(), [](const BearingTable& b) {
        return std::any_of(b.speeds.begin(), b.speeds.end(), [&](double w) {
            const Eigen::Matrix2d k = b.at(w).K;
            return k(0, 1) != k(1, 0);
        });
    });
    std::vector<std::string> why;
    if (s.has_circulatory()) why.push_back("N per unit speed");
    if (skew_K || skew_tables) why.push_back("cross-coupled stiffness");
    return why.empty() ? std::string("no") : fmt::format("yes ({})", fmt::join(why, ", "));
}

// The rows only an FE rotor has: elements, masses, diameters, and where its disks,
// bearings, supports and pedestals stand.
// A row; a length (unit "m") in the scene's unit.
void add_row(Table& t, const LengthUnit& length, const std::string& q, const Cell& v, const std::string& unit) {
    if (unit == "m" && std::holds_alternative<double>(v))
        t.add_row({q, length.in_unit(std::get<double>(v)), length.name});
    else
        t.add_row({q, v, unit});
}

void add_fe_rotor_rows(Table& t, const FeRotor& r, const GyroscopicSystem& s, const LengthUnit& length,
                       const BearingNumbers& numbers) {
    const auto add = [&](const std::string& q, const Cell& v, const std::string& unit = "") {
        add_row(t, length, q, v, unit);
    };
    add("elements", ll(static_cast<int>(r.elements.size())));
    add("motion", std::string(to_string(r.motion)));
    add("dofs_per_node", ll(dofs_per_node(r.motion)));
    add("couplings", ll(static_cast<int>(std::count_if(r.elements.begin(), r.elements.end(),
                                                        [](const FeShaftElement& e) { return e.coupling.has_value(); }))));
    double shaft = 0.0, dmin = 1e300, dmax = 0.0;
    for (const auto& e : r.elements) {
        shaft += fe_element_mass(e);   // couplings: their mass
        if (e.coupling) continue;
        for (const double d : {e.outer_diameter, e.outer_diameter_end.value_or(e.outer_diameter)}) {
            dmin = std::min(dmin, d);
            dmax = std::max(dmax, d);
        }
    }
    add("shaft_mass", shaft, "kg");
    double disks = 0.0;
    for (const auto& d : r.disks) disks += d.mass;
    add("total_mass", shaft + disks, "kg");
    add("shaft_outer_diameter_min", dmin, "m");
    add("shaft_outer_diameter_max", dmax, "m");
    add("shear_deformation", std::string(r.shear_deformation ? "yes" : "no"));
    add("rotary_inertia", std::string(r.rotary_inertia ? "yes" : "no"));
    int k = 0;
    for (const auto& d : r.disks) {
        const std::string p = fmt::format("disk{}_", ++k);
        add(p + "z", s.node_z[static_cast<size_t>(d.node)], "m");
        add(p + "mass", d.mass, "kg");
        add(p + "Id", d.diametral_inertia, "kg m^2");
        add(p + "Ip", d.polar_inertia, "kg m^2");
    }
    // Each bearing by its number in the model's list (as the static reactions name it).
    std::vector<std::pair<int, int>> bearing_nodes;   // number, node
    for (std::size_t i = 0; i < r.bearings.size(); ++i)
        bearing_nodes.emplace_back(i < numbers.constant.size() ? numbers.constant[i] : static_cast<int>(i) + 1,
                                   r.bearings[i].node);
    for (std::size_t j = 0; j < s.bearings.size(); ++j)
        if (const int node = bearing_node(s, s.bearings[j]); node >= 0)
            bearing_nodes.emplace_back(j < numbers.speed_dependent.size() ? numbers.speed_dependent[j]
                                                                          : static_cast<int>(r.bearings.size() + j) + 1,
                                       node);
    std::sort(bearing_nodes.begin(), bearing_nodes.end());
    for (const auto& [number, node] : bearing_nodes)
        add(fmt::format("bearing{}_z", number), s.node_z[static_cast<size_t>(node)], "m");
    k = 0;
    for (const auto& sp : r.supports)
        add(fmt::format("support{}_z", ++k), s.node_z[static_cast<size_t>(sp.node)], "m");
    k = 0;
    for (const auto& p : r.pedestals) {
        const std::string key = fmt::format("pedestal{}_", ++k);
        add(key + "z", s.node_z[static_cast<size_t>(p.node)], "m");
        add(key + "mass", p.mass, "kg");
        add(key + "kxx", p.kxx, "N/m");
        add(key + "kyy", p.kyy, "N/m");
        add(key + "cxx", p.cxx, "N s/m");
        add(key + "cyy", p.cyy, "N s/m");
    }
}

}  // namespace

Table model_summary(const Scene& sc) {
    Table t({"quantity", "value", "unit"});
    t.key = "model";
    t.title = "model " + sc.path + (sc.title.empty() ? std::string() : ": " + sc.title);
    const GyroscopicSystem& s = sc.system;
    const LengthUnit length = sc.length_unit();
    const auto add = [&](const std::string& q, const Cell& v, const std::string& unit = "") {
        add_row(t, length, q, v, unit);
    };
    add("type", sc.model_type());
    add("dofs", ll(s.size()));
    if (!s.dofs.units.empty()) {
        std::vector<std::string> seen;
        for (const auto& u : s.dofs.units)
            if (std::find(seen.begin(), seen.end(), u) == seen.end()) seen.push_back(u);
        for (const auto& u : seen)
            add("dofs_in_" + u, ll(static_cast<int>(std::count(s.dofs.units.begin(), s.dofs.units.end(), u))));
    }
    add("whirl_pairs", ll(static_cast<int>(s.whirl_pairs.size())));
    if (!s.node_z.empty()) {
        add("nodes", ll(static_cast<int>(s.node_z.size())));
        add("length", *std::max_element(s.node_z.begin(), s.node_z.end()) -
                          *std::min_element(s.node_z.begin(), s.node_z.end()), "m");
    }
    // Mass that a unit translation along u of every free translational pair moves: r^T M r
    // (nodes a support holds are not in the system, so their share is not either).
    if (!s.dofs.units.empty()) {
        Eigen::VectorXd r = Eigen::VectorXd::Zero(s.size());
        for (const auto& [u, v] : s.whirl_pairs)
            if (s.dofs.units[static_cast<size_t>(u)] == "m") r(u) = 1.0;
        if (r.sum() > 0) add("translating_mass", r.dot(SparseMatrix(s.M) * r), "kg");
    }
    add("nonzeros_M_K", ll(static_cast<int>(s.M.nonZeros() + s.K.nonZeros())));
    add("gyroscopic", std::string(s.G.nonZeros() > 0 && s.G.norm() > 0 ? "yes" : "no"));
    add("circulatory", circulatory(s));
    add("speed_squared_stiffness", std::string(s.has_speed_squared_stiffness() ? "yes" : "no"));
    std::string damping;
    for (const auto& n : s.damping_names()) damping += (damping.empty() ? "" : ", ") + n;
    add("damping", damping.empty() ? std::string("none") : damping);
    if (sc.rotor_model()) {   // the shaft's own damping as the scene gives it
        const ShaftDamping& d = sc.rotor_model()->shaft_damping;
        if (d.alpha > 0.0) add("shaft_damping_alpha", d.alpha, "1/s");
        if (d.beta > 0.0) add("shaft_damping_beta", d.beta, "s");
        if (!d.modal.empty()) {
            std::string z;
            for (const double v : d.modal) z += (z.empty() ? "" : ", ") + fmt::format("{:g}", v);
            add("shaft_damping_zeta", z);
        }
    }
    add("bearing_tables", ll(static_cast<int>(s.bearings.size())));
    add("unbalance", std::string(s.unbalance.size() > 0 && s.unbalance.norm() > 0 ? "yes" : "no"));
    if (s.size() <= kAutoSparseDofs) {
        const QuadraticSpectrum sp = solve_at_speed(s, 0.0);
        add("rigid_body_eigenvalues_at_rest", ll(static_cast<int>(sp.rigid_body.size())));
        if (!sp.modes.empty()) add("lowest_frequency_at_rest", sp.modes.front().frequency(), "rad/s");
    } else {
        add("rigid_body_eigenvalues_at_rest", std::string("not computed (sparse model)"));
    }
    if (sc.fe_rotor())
        add_fe_rotor_rows(t, *sc.fe_rotor(), s, length,
                          sc.rotor_model() ? bearing_numbers(*sc.rotor_model()) : BearingNumbers{});
    return t;
}

AxisMarks axis_marks(const Scene& scene) {
    AxisMarks m;
    if (!scene.fe_rotor() || scene.system.node_z.empty()) return m;
    const FeRotor& r = *scene.fe_rotor();
    const std::vector<double>& z = scene.system.node_z;
    const auto at = [&](int node) { return z.at(static_cast<std::size_t>(node)); };
    for (const auto& d : r.disks) m.disks.push_back(at(d.node));
    for (const auto& b : r.bearings) m.bearings.push_back(at(b.node));
    for (const auto& b : scene.system.bearings)
        if (const int node = bearing_node(scene.system, b); node >= 0) m.bearings.push_back(at(node));
    for (const auto& sp : r.supports) m.supports.push_back(at(sp.node));
    return m;
}

namespace {

// Disks as given: a geometry as its hollow cylinder (the bore left open, a rectangle
// above and below the axis); mass and inertias as the solid cylinder they make.
std::vector<Series> disk_series(const FeRotor& r, const std::vector<double>& z,
                                const std::vector<std::optional<DiskGeometry>>& geometry) {
    Series given, equivalent;
    given.label = "disks";
    equivalent.label = "disks (solid cylinders of their m, Id, Ip)";
    given.color = equivalent.color = "#d62728";
    const auto box = [](Series& s, double z0, double z1, double y0, double y1) {
        for (const auto& [x, y] : std::vector<std::pair<double, double>>{{z0, y0}, {z0, y1}, {z1, y1}, {z1, y0}, {z0, y0}})
            s.x.push_back(x), s.y.push_back(y);
        s.x.push_back(NAN), s.y.push_back(NAN);
    };
    for (std::size_t i = 0; i < r.disks.size(); ++i) {
        const FeDisk& d = r.disks[i];
        const double zc = z[static_cast<size_t>(d.node)];
        if (i < geometry.size() && geometry[i]) {
            const DiskGeometry& g = *geometry[i];
            const double h = std::max(g.width, 1e-3 * z.back()) / 2, ro = g.outer_diameter / 2, ri = g.inner_diameter / 2;
            box(given, zc - h, zc + h, ri, ro);
            box(given, zc - h, zc + h, -ro, -ri);
            continue;
        }
        const auto [rad, width] = disk_cylinder(d);
        const double h = std::max(width, 1e-3 * z.back()) / 2;
        box(equivalent, zc - h, zc + h, -rad, rad);
    }
    return {given, equivalent};
}

}  // namespace

Figure fe_rotor_figure(const Scene& scene) {
    std::vector<std::optional<DiskGeometry>> geometry;
    if (const RotorModel* m = scene.rotor_model())
        for (const RotorDisk& d : m->disks) geometry.push_back(d.geometry);
    return fe_rotor_figure(*scene.fe_rotor(), scene.system, scene.title, scene.length_unit(), geometry);
}

Figure fe_rotor_figure(const FeRotor& r, const GyroscopicSystem& sys, const std::string& title,
                       const LengthUnit& length, const std::vector<std::optional<DiskGeometry>>& geometry) {
    Figure f;
    f.title = title.empty() ? std::string("Finite-element rotor") : title;
    Panel p{"z [m]", "radius [m]", "", false, {}, {}, {}, {}, {}};
    std::vector<double> z(static_cast<size_t>(r.node_count()), 0.0);
    for (size_t e = 0; e < r.elements.size(); ++e) z[e + 1] = z[e] + r.elements[e].length;
    // Shaft outline: outer radius above and below the axis, the bore dashed.
    Series top, bottom, bore_top, bore_bottom;
    top.label = "shaft";
    top.color = bottom.color = "#1f77b4";
    bore_top.color = bore_bottom.color = "#1f77b4";
    bore_top.style = bore_bottom.style = "dashed";
    for (size_t e = 0; e < r.elements.size(); ++e) {
        const FeShaftElement& el = r.elements[e];
        if (el.coupling) {   // no outline: a gap in the drawn shaft
            for (Series* s : {&top, &bottom, &bore_top, &bore_bottom}) s->x.push_back(NAN), s->y.push_back(NAN);
            continue;
        }
        // Both ends of the element: a step between uniform elements, a slope along a cone.
        const double ends[2][2] = {{el.outer_diameter / 2, el.inner_diameter / 2},
                                   {el.outer_diameter_end.value_or(el.outer_diameter) / 2,
                                    el.inner_diameter_end.value_or(el.inner_diameter) / 2}};
        for (int k = 0; k < 2; ++k) {
            const double x = z[e + k], ro = ends[k][0], ri = ends[k][1];
            top.x.push_back(x), top.y.push_back(ro);
            bottom.x.push_back(x), bottom.y.push_back(-ro);
            bore_top.x.push_back(x), bore_top.y.push_back(ri > 0 ? ri : NAN);
            bore_bottom.x.push_back(x), bore_bottom.y.push_back(ri > 0 ? -ri : NAN);
        }
    }
    p.series = {top, bottom, bore_top, bore_bottom};
    for (Series& d : disk_series(r, z, geometry))
        if (!d.x.empty()) p.series.push_back(std::move(d));
    // Bearings and supports below the shaft at their nodes.
    const auto marks = [&](const std::vector<int>& nodes, const std::string& label, const std::string& color) {
        Series m;
        m.label = label;
        m.style = "points";
        m.color = color;
        for (const int n : nodes) {
            double ro = 0.0;
            if (n > 0) {
                const FeShaftElement& left = r.elements[static_cast<size_t>(n - 1)];
                ro = std::max(ro, left.outer_diameter_end.value_or(left.outer_diameter) / 2);
            }
            if (n < static_cast<int>(r.elements.size())) ro = std::max(ro, r.elements[static_cast<size_t>(n)].outer_diameter / 2);
            m.x.push_back(z[static_cast<size_t>(n)]);
            m.y.push_back(-1.5 * ro);
        }
        if (!nodes.empty()) p.series.push_back(m);
    };
    std::vector<int> bearing_nodes, support_nodes, nodes;
    for (const auto& b : r.bearings) bearing_nodes.push_back(b.node);
    for (const auto& b : sys.bearings)
        if (const int node = bearing_node(sys, b); node >= 0) bearing_nodes.push_back(node);
    for (const auto& s : r.supports) support_nodes.push_back(s.node);
    marks(bearing_nodes, "bearings", "#2ca02c");
    marks(support_nodes, "rigid supports", "#000000");
    Series axis;
    axis.label = "nodes";
    axis.style = "points";
    axis.color = "#7f7f7f";
    for (const double x : z) axis.x.push_back(x), axis.y.push_back(0.0);
    p.series.push_back(axis);
    f.panels = {p};
    // Drawn in the scene's length unit: every coordinate is a length.
    for (Panel& panel : f.panels) {
        panel.xlabel = "z [" + length.name + "]";
        panel.ylabel = "radius [" + length.name + "]";
        for (Series& sr : panel.series) {
            for (double& x : sr.x) x = length.in_unit(x);
            for (double& y : sr.y) y = length.in_unit(y);
        }
    }
    return f;
}

}  // namespace gyrokit
