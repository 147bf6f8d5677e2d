#include <gyrokit/reports/static_reports.hpp>

#include <gyrokit/reports/detail/cells.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include <array>
#include <utility>

namespace gyrokit {

using detail::ll;

namespace {

// What the solve vouches for: a value within the error bound of the largest of its kind
// is rounding (a slope at a symmetric rotor's middle), printed as 0.
struct Vouched {
    double scale = 0.0, bound = 0.0;
    template <class T, class F>
    Vouched(const std::vector<T>& rows, const F& value, const StaticResult& s)
        : bound(10 * std::max({s.error_bound, s.balance_error, 1e-15})) {
        for (const T& r : rows) scale = std::max(scale, std::abs(value(r)));
    }
    double operator()(double v) const { return std::abs(v) <= bound * scale ? 0.0 : v; }
};

}  // namespace

Table static_node_table(const StaticResult& s, const LengthUnit& length) {
    const LengthUnit& u = length;
    Table t({"node", u.column("z"), u.column("x"), u.column("y"), "slope_x_rad", "slope_y_rad"});
    t.key = "deflection";
    t.title = "deflection at the nodes (slope_x = dx/dz, slope_y = dy/dz)";
    const Vouched d(s.nodes, [](const StaticNode& n) { return std::max(std::abs(n.x), std::abs(n.y)); }, s);
    const Vouched a(s.nodes, [](const StaticNode& n) { return std::max(std::abs(n.slope_x), std::abs(n.slope_y)); }, s);
    for (const StaticNode& n : s.nodes)
        t.add_row({ll(n.node), u.in_unit(n.z), u.in_unit(d(n.x)), u.in_unit(d(n.y)), a(n.slope_x), a(n.slope_y)});
    return t;
}

Table static_section_table(const StaticResult& s, const LengthUnit& length) {
    Table t({"element", length.column("z"), "shear_x_n", "moment_x_n_m", "shear_y_n", "moment_y_n_m"});
    t.key = "internal_forces";
    t.title = "shear force and bending moment at each element's ends (M = E I y'' vertical, E I x'' horizontal)";
    const Vouched v(s.sections, [](const StaticSection& c) { return std::max(std::abs(c.shear_x), std::abs(c.shear_y)); }, s);
    const Vouched m(s.sections, [](const StaticSection& c) { return std::max(std::abs(c.moment_x), std::abs(c.moment_y)); },
                    s);
    for (const StaticSection& c : s.sections)
        t.add_row({ll(c.element), length.in_unit(c.z), v(c.shear_x), m(c.moment_x), v(c.shear_y), m(c.moment_y)});
    return t;
}

Table static_reaction_table(const StaticResult& s, const LengthUnit& length) {
    Table t({"reaction", "node", length.column("z"), "fx_n", "fy_n", "mx_n_m", "my_n_m"});
    t.key = "reactions";
    t.title = "reactions: forces and moments on the rotor";
    const Vouched f(s.reactions, [](const StaticReaction& r) { return std::max(std::abs(r.fx), std::abs(r.fy)); }, s);
    const Vouched m(s.reactions, [](const StaticReaction& r) { return std::max(std::abs(r.mx), std::abs(r.my)); }, s);
    for (const StaticReaction& r : s.reactions)
        t.add_row({r.what, ll(r.node), length.in_unit(r.z), f(r.fx), f(r.fy), m(r.mx), m(r.my)});
    return t;
}

Table static_summary_table(const StaticResult& s, const LengthUnit& length) {
    Table t({"quantity", "value", "unit", length.column("at_z")});
    t.key = "static";
    t.title = "static analysis";
    const StaticNode* far = nullptr;
    for (const StaticNode& n : s.nodes)
        if (!far || std::hypot(n.x, n.y) > std::hypot(far->x, far->y)) far = &n;
    const StaticSection* bent = nullptr;
    for (const StaticSection& c : s.sections)
        if (!bent || std::hypot(c.moment_x, c.moment_y) > std::hypot(bent->moment_x, bent->moment_y)) bent = &c;
    t.add_row({std::string("weight"), s.weight, std::string("N"), std::string("-")});
    if (far)
        t.add_row({std::string("largest deflection"), length.in_unit(std::hypot(far->x, far->y)), length.name,
                   length.in_unit(far->z)});
    if (bent)
        t.add_row({std::string("largest bending moment"), std::hypot(bent->moment_x, bent->moment_y),
                   std::string("N m"), length.in_unit(bent->z)});
    // Bounds and estimates: two digits are all they hold.
    const auto bound = [&](const char* what, double v) {
        t.add_row({std::string(what), fmt::format("{:.2g}", v), std::string("1"), std::string("-")});
    };
    bound("backward error of the solve", s.backward_error);
    bound("condition number", s.condition);
    bound("deflection error bound", s.error_bound);
    bound("force balance error", s.balance_error);
    return t;
}

std::vector<Table> static_tables(const StaticResult& s, const LengthUnit& length) {
    return {static_node_table(s, length), static_summary_table(s, length), static_reaction_table(s, length),
            static_section_table(s, length)};
}

namespace {

// A panel of one quantity in the two planes along the shaft: `of(item)` gives the x and
// y plane values of each node or element end.
template <class Item, class Of>
Panel two_planes(const std::vector<Item>& items, const LengthUnit& length, const std::string& ylabel,
                 const std::string& title, const std::array<std::string, 2>& names, const std::string& style,
                 const Of& of) {
    Panel p{"z [" + length.name + "]", ylabel, title, false, {}, {}, {}, {}, {}, false};
    Series x{{}, {}, names[0], style, "#1f77b4"}, y{{}, {}, names[1], style, "#d62728"};
    for (const Item& i : items) {
        const std::pair<double, double> v = of(i);
        x.x.push_back(length.in_unit(i.z)), x.y.push_back(v.first);
        y.x.push_back(length.in_unit(i.z)), y.y.push_back(v.second);
    }
    p.series = {x, y};
    return p;
}

}  // namespace

Figure static_figure(const StaticResult& s, const std::string& title, const LengthUnit& length) {
    Figure f;
    f.title = title.empty() ? "static deflection" : title;
    Panel deflection = two_planes(s.nodes, length, "deflection [um]", "deflection at the nodes", {"x", "y"},
                                  "linespoints", [](const StaticNode& n) { return std::pair(n.x * 1e6, n.y * 1e6); });
    Series held{{}, {}, "reactions", "points", "#000000"};
    for (const StaticReaction& r : s.reactions) held.x.push_back(length.in_unit(r.z)), held.y.push_back(0.0);
    deflection.series.push_back(held);
    const std::array<std::string, 2> planes{"horizontal (x)", "vertical (y)"};
    f.panels = {deflection,
                two_planes(s.nodes, length, "slope [mrad]", "slope (dx/dz, dy/dz)", {"dx/dz", "dy/dz"}, "linespoints",
                           [](const StaticNode& n) { return std::pair(n.slope_x * 1e3, n.slope_y * 1e3); }),
                two_planes(s.sections, length, "shear force [N]", "shear force (V = dM/dz)", planes, "lines",
                           [](const StaticSection& c) { return std::pair(c.shear_x, c.shear_y); }),
                two_planes(s.sections, length, "bending moment [N m]", "bending moment (E I x'', E I y'')", planes,
                           "lines", [](const StaticSection& c) { return std::pair(c.moment_x, c.moment_y); })};
    return f;
}

}  // namespace gyrokit
