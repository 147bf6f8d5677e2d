// FE rotors built in Python: the library's RotorModel and its items with keyword
// constructors (SI units; angles in degrees, as in scene files), scenes made from
// them, and scenes written back as TOML (to_toml, write, pickle).
#include "models.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/scene/scene_writer.hpp>
#include <gyrokit/models/materials.hpp>
#include <gyrokit/models/rotor_model.hpp>
#include <gyrokit/core/constants.hpp>

#include <pybind11/stl.h>

#include <functional>
#include <limits>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <string>

namespace py = pybind11;
using namespace gyrokit;

namespace {

using Opt = std::optional<double>;

double radians(double deg) { return deg * kPi / 180.0; }
double degrees(double rad) { return rad * 180.0 / kPi; }

// A keyword that takes one of `allowed`.
void require_choice(const char* keyword, const std::string& value, std::initializer_list<const char*> allowed) {
    std::string list;
    for (const char* a : allowed) {
        if (value == a) return;
        list += (list.empty() ? "" : ", ") + std::string(a);
    }
    throw InputError(fmt::format("{} = '{}'; allowed: {}", keyword, value, list));
}

// A material keyword: a Material, or the name of a standard one (gk.materials()).
std::optional<Material> material_of(const py::object& material) {
    if (material.is_none()) return std::nullopt;
    if (py::isinstance<Material>(material)) return material.cast<Material>();
    if (!py::isinstance<py::str>(material))
        throw InputError(fmt::format("material = {}: allowed: a gyrokit.Material or the name of one of "
                                     "gyrokit.materials()",
                                     py::repr(material).cast<std::string>()));
    return find_material(material.cast<std::string>(), {}, "material");
}

// Python's float repr: the shortest string that reads back to the same double.
std::string float_repr(double x) { return py::repr(py::float_(x)).cast<std::string>(); }

RotorSection section(double length, double outer_diameter, Opt E, Opt density, int elements, double inner_diameter,
                     Opt outer_diameter_end, Opt inner_diameter_end, Opt poisson, double G,
                     const py::object& material) {
    // As a scene's section: a value given wins over its material's, poisson 0.3 where neither gives one.
    const std::optional<Material> mat = material_of(material);
    if (!E && mat) E = mat->youngs_modulus;
    if (!density && mat) density = mat->density;
    if (!poisson) poisson = mat ? mat->poisson_ratio : 0.3;
    if (!E || !density)
        throw InputError(std::string(E ? "density" : "E") +
                         " is missing; required: a number > 0, or material = one of gyrokit.materials()");
    RotorSection s;
    s.shape.length = length;
    s.shape.outer_diameter = outer_diameter;
    s.shape.inner_diameter = inner_diameter;
    s.shape.outer_diameter_end = outer_diameter_end;
    s.shape.inner_diameter_end = inner_diameter_end;
    s.shape.youngs_modulus = *E;
    s.shape.density = *density;
    s.shape.poisson_ratio = *poisson;
    s.shape.shear_modulus = G;
    s.elements = elements;
    return s;
}

// A section as the call that makes it (round-trip values; keywords left at their defaults omitted).
std::string section_repr(const RotorSection& s) {
    const FeShaftElement& e = s.shape;
    if (const auto& c = e.coupling) {
        std::string r = "coupling(length=" + float_repr(e.length);
        const std::pair<const char*, double> fields[] = {
            {"k_lateral", c->k_lateral}, {"k_bending", c->k_bending}, {"k_axial", c->k_axial},
            {"k_torsion", c->k_torsion}, {"c_lateral", c->c_lateral}, {"c_bending", c->c_bending},
            {"c_axial", c->c_axial},     {"c_torsion", c->c_torsion}, {"mass", c->mass},
            {"Id", c->diametral_inertia}, {"Ip", c->polar_inertia}};
        for (const auto& [key, value] : fields)
            if (value != 0.0) r += fmt::format(", {}={}", key, float_repr(value));
        return r + ")";
    }
    std::string r = fmt::format("Section(length={}, outer_diameter={}", float_repr(e.length), float_repr(e.outer_diameter));
    if (e.inner_diameter != 0.0) r += ", inner_diameter=" + float_repr(e.inner_diameter);
    if (e.outer_diameter_end) r += ", outer_diameter_end=" + float_repr(*e.outer_diameter_end);
    if (e.inner_diameter_end) r += ", inner_diameter_end=" + float_repr(*e.inner_diameter_end);
    if (s.elements != 1) r += fmt::format(", elements={}", s.elements);
    r += fmt::format(", E={}, density={}, poisson={}", float_repr(e.youngs_modulus), float_repr(e.density),
                     float_repr(e.poisson_ratio));
    if (e.shear_modulus != 0.0) r += ", G=" + float_repr(e.shear_modulus);
    return r + ")";
}

// The degrees that Disk(phase=...) turns back into exactly `rad`: the shortest of the
// doubles next to rad * 180 / pi that does (30, not 29.999999999999996).
double degrees_back(double rad) {
    const double d = degrees(rad);
    std::optional<double> best;
    double x = d;
    for (int k = 0; k < 3; ++k) x = std::nextafter(x, -HUGE_VAL);
    for (int k = 0; k < 7; ++k, x = std::nextafter(x, HUGE_VAL))
        if (radians(x) == rad && (!best || float_repr(x).size() < float_repr(*best).size())) best = x;
    return best.value_or(d);
}

std::string disk_repr(const RotorDisk& d) {
    std::string r = "Disk(z=" + float_repr(d.z);
    if (const auto& g = d.geometry) {
        r += ", outer_diameter=" + float_repr(g->outer_diameter);
        if (g->inner_diameter != 0.0) r += ", inner_diameter=" + float_repr(g->inner_diameter);
        r += fmt::format(", width={}, density={}", float_repr(g->width), float_repr(g->density));
    } else {
        r += ", mass=" + float_repr(d.disk.mass);
        if (d.disk.diametral_inertia != 0.0) r += ", Id=" + float_repr(d.disk.diametral_inertia);
        if (d.disk.polar_inertia != 0.0) r += ", Ip=" + float_repr(d.disk.polar_inertia);
    }
    if (d.disk.unbalance != 0.0) r += ", unbalance=" + float_repr(d.disk.unbalance);
    if (d.disk.unbalance_phase != 0.0) r += ", phase=" + float_repr(degrees_back(d.disk.unbalance_phase));
    return r + ")";
}

RotorSection coupling(double length, double k_lateral, double k_bending, double k_axial, double k_torsion,
                      double c_lateral, double c_bending, double c_axial, double c_torsion, double mass, double Id,
                      double Ip) {
    RotorSection s;
    s.shape.length = length;
    s.shape.coupling = FeCoupling{k_lateral, k_bending, k_axial, k_torsion, c_lateral, c_bending,
                                  c_axial,   c_torsion, mass,     Id,        Ip};
    return s;
}

RotorDisk disk(double z, Opt mass, double Id, double Ip, Opt outer_diameter, double inner_diameter, Opt width,
               Opt density, double unbalance, double phase, const py::object& material) {
    RotorDisk d;
    d.z = z;
    const std::optional<Material> mat = material_of(material);
    if (outer_diameter) {
        if (mass || Id != 0.0 || Ip != 0.0)
            throw InputError("mass, Id, Ip are given together with outer_diameter; allowed: either mass, Id, Ip or "
                             "the geometry outer_diameter, inner_diameter, width, density (or material)");
        if (!density && mat) density = mat->density;
        if (!width || !density)
            throw InputError(std::string(width ? "density" : "width") +
                             " is missing; required with outer_diameter (density: or material)");
        d.geometry = DiskGeometry{*outer_diameter, inner_diameter, *width, *density};
    } else {
        if (mat || density)
            throw InputError(std::string(mat ? "material" : "density") +
                             " needs outer_diameter; allowed: the geometry outer_diameter, inner_diameter, width (and "
                             "material or density), or mass, Id, Ip");
        if (!mass) throw InputError("mass is missing; required: mass (kg), or the geometry outer_diameter, width, density");
        d.disk.mass = *mass;
        d.disk.diametral_inertia = Id;
        d.disk.polar_inertia = Ip;
    }
    d.disk.unbalance = unbalance;
    d.disk.unbalance_phase = radians(phase);
    return d;
}

RotorBearing bearing(double z, double k, double c, Opt kxx, Opt kxy, Opt kyx, Opt kyy, Opt cxx, Opt cxy, Opt cyx,
                     Opt cyy, double kzz, double czz) {
    RotorBearing b;
    b.z = z;
    b.constant = FeBearing{0,
                           kxx.value_or(k),
                           kxy.value_or(0.0),
                           kyx.value_or(0.0),
                           kyy.value_or(k),
                           cxx.value_or(c),
                           cxy.value_or(0.0),
                           cyx.value_or(0.0),
                           cyy.value_or(c),
                           kzz,
                           czz};
    return b;
}

using Column = std::optional<std::vector<double>>;

// Coefficient arrays of a table: `k`, `c` isotropic, kxx ... cyy each; missing ones 0.
RotorBearing table(double z, const std::vector<double>& speeds, const Column& k, const Column& c, const Column& kxx,
                   const Column& kxy, const Column& kyx, const Column& kyy, const Column& cxx, const Column& cxy,
                   const Column& cyx, const Column& cyy) {
    RotorBearing b;
    b.z = z;
    b.kind = RotorBearing::Kind::table;
    b.table.speeds = speeds;
    const std::size_t n = speeds.size();
    const auto column = [&](const char* name, const Column& own, const Column& iso) {
        const Column& v = own ? own : iso;
        if (!v) return std::vector<double>(n, 0.0);
        if (v->size() != n)
            throw InputError(fmt::format("{}: {} entries; allowed: {}, one per speed", own ? name : (name[0] == 'k' ? "k" : "c"),
                                         v->size(), n));
        return *v;
    };
    const Column none;
    const std::vector<double> Kxx = column("kxx", kxx, k), Kxy = column("kxy", kxy, none), Kyx = column("kyx", kyx, none),
                              Kyy = column("kyy", kyy, k), Cxx = column("cxx", cxx, c), Cxy = column("cxy", cxy, none),
                              Cyx = column("cyx", cyx, none), Cyy = column("cyy", cyy, c);
    b.table.rows.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        b.table.rows[i].K << Kxx[i], Kxy[i], Kyx[i], Kyy[i];
        b.table.rows[i].C << Cxx[i], Cxy[i], Cyx[i], Cyy[i];
    }
    return b;
}

RotorBearing fluid_film(double z, double diameter, double length, double clearance, double viscosity,
                        const py::object& load, double load_angle, double max_eccentricity, const std::string& solution,
                        int grid_circumferential, int grid_axial, std::optional<double> clearance_min,
                        std::optional<double> clearance_max, std::optional<double> viscosity_min,
                        std::optional<double> viscosity_max) {
    RotorBearing b;
    b.z = z;
    b.kind = RotorBearing::Kind::fluid_film;
    JournalBearing& j = b.film;
    j.diameter = diameter;
    j.length = length;
    j.clearance = clearance;
    j.viscosity = viscosity;
    if (py::isinstance<py::str>(load)) {
        require_choice("load", load.cast<std::string>(), {"auto"});
        b.auto_load = true;
        j.load = 1.0;
    } else {
        j.load = load.cast<double>();
    }
    j.load_angle = radians(load_angle);
    j.max_eccentricity = max_eccentricity;
    require_choice("solution", solution, {"short", "finite_difference"});
    j.solution = solution == "short" ? FilmSolution::short_bearing : FilmSolution::finite_difference;
    j.grid_circumferential = grid_circumferential;
    j.grid_axial = grid_axial;
    j.clearance_min = clearance_min;
    j.clearance_max = clearance_max;
    j.viscosity_min = viscosity_min;
    j.viscosity_max = viscosity_max;
    return b;
}

RotorSupport support(double z, const std::string& type, bool axial, bool torsion) {
    require_choice("type", type, {"pinned", "clamped"});
    RotorSupport s;
    s.z = z;
    s.hold.theta_x = s.hold.theta_y = type == "clamped";
    s.hold.z = axial;
    s.hold.theta_z = torsion;
    return s;
}

RotorPedestal pedestal(double z, double mass, double k, double c, Opt kxx, Opt kyy, Opt cxx, Opt cyy) {
    RotorPedestal p;
    p.z = z;
    p.pedestal = FePedestal{0, mass, kxx.value_or(k), kyy.value_or(k), cxx.value_or(c), cyy.value_or(c)};
    return p;
}

FeMotion motion_of(const std::string& m) {
    require_choice("motion", m, {"lateral", "all", "axial", "torsional"});
    return m == "all" ? FeMotion::all : m == "axial" ? FeMotion::axial : m == "torsional" ? FeMotion::torsional
                                                                                           : FeMotion::lateral;
}

// Items built in Python are named by their list and index in messages ("bearings[1] z = ...").
template <class T>
std::vector<T> named(std::vector<T> items, const char* list) {
    for (std::size_t i = 0; i < items.size(); ++i)
        if (items[i].origin.empty()) items[i].origin = fmt::format("{}[{}]", list, i);
    return items;
}

// A scene's [speeds] and [analysis] from Python's dicts (mapped by gyrokit/__init__.py), checked.
Scene with_settings(Scene sc, const py::object& speeds, const py::object& modes, const py::object& harmonics,
                    const std::string& solver, const py::object& target, double target_order, const py::object& f_cut) {
    if (!speeds.is_none()) {
        const auto t = speeds.cast<std::tuple<double, double, int, std::string>>();
        sc.speeds = SpeedRange{std::get<0>(t), std::get<1>(t), std::get<2>(t)};
        sc.speed_unit = SpeedUnit::parse(std::get<3>(t));
    }
    if (!modes.is_none()) sc.solver.modes = modes.cast<int>();
    if (!harmonics.is_none()) sc.analysis.harmonics = harmonics.cast<std::vector<int>>();
    require_choice("solver", solver, {"auto", "dense", "sparse"});
    sc.solver.kind = parse_solver_kind(solver);
    if (!target.is_none()) sc.solver.target = target.cast<double>();
    sc.solver.target_order = target_order;
    if (!f_cut.is_none()) sc.analysis.f_cut = f_cut.cast<double>();
    validate_settings(sc);
    return sc;
}

// A model's parameters from keywords named as the scene's [model] keys: each a number
// (an int or float, numpy's too; or, where `choices` names it, one of its words); unknown
// keys named with the allowed ones; a required key missing named as the scene reader
// names it; `rules` for what the keys say together (InputError).
template <class P>
struct ParameterKeys {
    const char* model;
    std::vector<std::pair<const char*, double P::*>> numbers;
    std::vector<std::pair<const char*, int P::*>> integers;
    std::vector<std::tuple<const char*, bool P::*, const char*, const char*>> choices;   // key, flag, false word, true word
    // Keys without a default: each with whether the parameters (the choices set) need it.
    std::vector<std::pair<const char*, std::function<bool(const P&)>>> required;
    std::function<void(const P&, const std::set<std::string>& given)> rules;

    P from(const py::kwargs& kw) const {
        P p;
        std::set<std::string> given;
        for (const auto& [key, value] : kw) {
            const std::string k = py::cast<std::string>(key);
            given.insert(k);
            if (set(p, k, value)) continue;
            std::string allowed;
            for (const auto& n : numbers) allowed += (allowed.empty() ? "" : ", ") + std::string(n.first);
            for (const auto& n : integers) allowed += ", " + std::string(n.first);
            for (const auto& c : choices) allowed += ", " + std::string(std::get<0>(c));
            throw InputError(fmt::format("{}: unknown key '{}'; allowed: {}", model, k, allowed));
        }
        for (const auto& [key, needed] : required)
            if (!given.count(key) && needed(p))
                throw InputError(fmt::format("{}: key '{}' is missing; required: a finite number", model, key));
        if (rules) rules(p, given);
        return p;
    }

    // The keywords that make `p` again (pickle).
    py::dict keywords(const P& p) const {
        py::dict d;
        for (const auto& [key, field] : numbers) d[key] = p.*field;
        for (const auto& [key, field] : integers) d[key] = p.*field;
        for (const auto& [key, field, no, yes] : choices) d[key] = p.*field ? yes : no;
        return d;
    }

private:
    bool set(P& p, const std::string& k, const py::handle& value) const {
        const auto bad = [&](const std::string& what) {
            return InputError(fmt::format("{}: {} = {}: allowed: {}", model, k, py::repr(value).cast<std::string>(), what));
        };
        const bool word = py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value);
        for (const auto& [name, field] : numbers)
            if (k == name) {
                if (word || !py::hasattr(value, "__float__")) throw bad("a number");
                p.*field = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
                return true;
            }
        for (const auto& [name, field] : integers)
            if (k == name) {
                if (word || !py::hasattr(value, "__index__")) throw bad("a whole number");
                const py::int_ i(py::reinterpret_borrow<py::object>(value));
                const long long v = i.cast<long long>();
                if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
                    throw bad("a whole number within a C int");
                p.*field = static_cast<int>(v);
                return true;
            }
        for (const auto& [name, field, no, yes] : choices)
            if (k == name) {
                const std::string w = py::isinstance<py::str>(value) ? value.cast<std::string>() : "";
                if (w != no && w != yes) throw bad(fmt::format("'{}' or '{}'", no, yes));
                p.*field = w == yes;
                return true;
            }
        return false;
    }
};

const ParameterKeys<GyrostatParameters>& gyrostat_keys() {
    using G = GyrostatParameters;
    const auto always = [](const G&) { return true; };
    const auto elastic_housing = [](const G& g) { return !g.rigid_housing; };
    const auto elastic_shaft = [](const G& g) { return !g.rigid_shaft; };
    static const ParameterKeys<G> keys{
        "gyrostat",
        {{"A_G", &G::A_G}, {"B_G", &G::B_G}, {"A_R", &G::A_R}, {"C_R", &G::C_R}, {"m", &G::m}, {"s", &G::s},
         {"eps", &G::eps}, {"c_G", &G::c_G}, {"c_T", &G::c_T}, {"c_R", &G::c_R}, {"d_G", &G::d_G}, {"d_T", &G::d_T},
         {"d_R", &G::d_R}},
        {},
        {{"shaft", &G::rigid_shaft, "elastic", "rigid"}, {"housing", &G::rigid_housing, "elastic", "rigid"}},
        {{"A_G", elastic_housing}, {"B_G", elastic_housing}, {"c_G", elastic_housing}, {"A_R", always},
         {"C_R", always}, {"m", always}, {"s", always}, {"c_T", elastic_shaft}, {"c_R", elastic_shaft}},
        {}};
    return keys;
}

const ParameterKeys<FluidRotorParameters>& fluid_keys() {
    using F = FluidRotorParameters;
    const auto always = [](const F&) { return true; };
    static const ParameterKeys<F> keys{
        "fluid_rotor",
        {{"R", &F::R}, {"R0", &F::R0}, {"a", &F::a}, {"l", &F::l}, {"rho", &F::rho}, {"nu", &F::nu}, {"c1", &F::c1},
         {"c2", &F::c2}, {"c11", &F::c11}, {"m0", &F::m0}, {"I0", &F::I0}, {"J0", &F::J0}, {"e", &F::e},
         {"tolerance", &F::tolerance}},
        {{"modes", &F::modes}, {"jstar_terms", &F::jstar_terms}},
        {},
        {{"R", always}, {"R0", always}, {"a", always}, {"l", always}, {"rho", always}, {"c1", always}, {"c2", always},
         {"c11", always}, {"m0", always}, {"I0", always}, {"J0", always}},
        // As the scene reader: modes, where given, in [1, 100000] and not with a tolerance.
        [](const F& f, const std::set<std::string>& given) {
            if (given.count("modes") && f.modes < 1)
                throw InputError(fmt::format("fluid_rotor: modes = {}: out of range; allowed: [1, 100000], or absent "
                                             "for a tolerance",
                                             f.modes));
            if (given.count("modes") && given.count("tolerance"))
                throw InputError("fluid_rotor: tolerance given together with modes; allowed: one of modes, tolerance");
        }};
    return keys;
}

// Each field readable and writable under its [model] key, and a repr that lists them.
template <class P>
void bind_parameters(py::module_& m, const char* name, const char* doc, const ParameterKeys<P>& keys) {
    py::class_<P> c(m, name, doc);
    c.def(py::init([&keys](const py::kwargs& kw) { return keys.from(kw); }));
    for (const auto& [key, field] : keys.numbers) c.def_readwrite(key, field);
    for (const auto& [key, field] : keys.integers) c.def_readwrite(key, field);
    for (const auto& [key, field, no, yes] : keys.choices) {
        const auto f = field;
        const std::string n = no, y = yes;
        c.def_property(
            key, [f, n, y](const P& p) { return p.*f ? y : n; },
            [f, n, y, key = std::string(key)](P& p, const std::string& w) {
                require_choice(key.c_str(), w, {n.c_str(), y.c_str()});
                p.*f = w == y;
            });
    }
    c.def(py::pickle([&keys](const P& p) { return keys.keywords(p); },
                     [&keys](const py::dict& d) { return keys.from(py::kwargs(d)); }));
    c.def("__repr__", [&keys, name](const P& p) {
        std::string r = std::string(name) + "(";
        const char* sep = "";
        for (const auto& [key, field] : keys.numbers)   // Python's float repr: shortest round trip, "2.0"
            r += fmt::format("{}{}={}", std::exchange(sep, ", "), key, py::repr(py::float_(p.*field)).cast<std::string>());
        for (const auto& [key, field] : keys.integers) r += fmt::format("{}{}={}", std::exchange(sep, ", "), key, p.*field);
        for (const auto& [key, field, no, yes] : keys.choices)
            r += fmt::format("{}{}='{}'", std::exchange(sep, ", "), key, p.*field ? yes : no);
        return r + ")";
    });
}

}  // namespace

void bind_models(py::module_& m, py::class_<Scene>& scene) {
    py::class_<Material>(m, "Material", "A shaft and disk material: E (Pa), poisson, density (kg/m^3)")
        .def(py::init([](const std::string& name, double E, double density, double poisson) {
                 if (name.empty()) throw InputError("name is missing; required: the material's name");
                 if (!(E > 0) || !std::isfinite(E)) throw InputError(fmt::format("E = {}: allowed: a number > 0 (Pa)", E));
                 if (!(density > 0) || !std::isfinite(density))
                     throw InputError(fmt::format("density = {}: allowed: a number > 0 (kg/m^3)", density));
                 if (!(poisson > -1.0 && poisson < 0.5))
                     throw InputError(fmt::format("poisson = {}: allowed: -1 < poisson < 0.5", poisson));
                 return Material{name, E, poisson, density, "given"};
             }),
             py::kw_only(), py::arg("name"), py::arg("E"), py::arg("density"), py::arg("poisson") = 0.3)
        .def_readonly("name", &Material::name)
        .def_readonly("E", &Material::youngs_modulus)
        .def_readonly("poisson", &Material::poisson_ratio)
        .def_readonly("density", &Material::density)
        .def_readonly("source", &Material::source)
        .def("__repr__", [](const Material& x) {
            return fmt::format("Material(name='{}', E={}, density={}, poisson={})", x.name, float_repr(x.youngs_modulus),
                               float_repr(x.density), float_repr(x.poisson_ratio));
        });
    m.def("materials", &standard_materials,
          "The named materials a scene's `material` key and Section/Disk(material=...) know (the scene's values)");
    py::class_<RotorSection>(m, "Section", "A shaft section of equal elements, or a flexible coupling (coupling())")
        .def(py::init(&section), py::kw_only(), py::arg("length"), py::arg("outer_diameter"), py::arg("E") = py::none(),
             py::arg("density") = py::none(), py::arg("elements") = 1, py::arg("inner_diameter") = 0.0,
             py::arg("outer_diameter_end") = py::none(), py::arg("inner_diameter_end") = py::none(),
             py::arg("poisson") = py::none(), py::arg("G") = 0.0, py::arg("material") = py::none())
        .def_property_readonly("length", [](const RotorSection& s) { return s.shape.length; })
        .def_property_readonly("elements", [](const RotorSection& s) { return s.elements; })
        .def_property_readonly("outer_diameter", [](const RotorSection& s) { return s.shape.outer_diameter; })
        .def_property_readonly("inner_diameter", [](const RotorSection& s) { return s.shape.inner_diameter; })
        .def_property_readonly("E", [](const RotorSection& s) { return s.shape.youngs_modulus; })
        .def_property_readonly("density", [](const RotorSection& s) { return s.shape.density; })
        .def_property_readonly("poisson", [](const RotorSection& s) { return s.shape.poisson_ratio; })
        .def_property_readonly("is_coupling", [](const RotorSection& s) { return s.shape.coupling.has_value(); })
        .def("__repr__", &section_repr);
    m.def("coupling", &coupling, "A flexible coupling of `length` in the shaft chain", py::kw_only(), py::arg("length"),
          py::arg("k_lateral") = 0.0, py::arg("k_bending") = 0.0, py::arg("k_axial") = 0.0, py::arg("k_torsion") = 0.0,
          py::arg("c_lateral") = 0.0, py::arg("c_bending") = 0.0, py::arg("c_axial") = 0.0,
          py::arg("c_torsion") = 0.0, py::arg("mass") = 0.0, py::arg("Id") = 0.0, py::arg("Ip") = 0.0);
    py::class_<RotorDisk>(m, "Disk", "A rigid disk at z: mass, Id, Ip or its geometry; unbalance (kg m), phase (deg)")
        .def(py::init(&disk), py::kw_only(), py::arg("z"), py::arg("mass") = py::none(), py::arg("Id") = 0.0,
             py::arg("Ip") = 0.0, py::arg("outer_diameter") = py::none(), py::arg("inner_diameter") = 0.0,
             py::arg("width") = py::none(), py::arg("density") = py::none(), py::arg("unbalance") = 0.0,
             py::arg("phase") = 0.0, py::arg("material") = py::none())
        .def("__repr__", &disk_repr)
        .def_property_readonly("z", [](const RotorDisk& d) { return d.z; })
        .def_property_readonly("unbalance", [](const RotorDisk& d) { return d.disk.unbalance; })
        .def_property_readonly("phase", [](const RotorDisk& d) { return degrees(d.disk.unbalance_phase); });
    py::class_<RotorBearing>(m, "Bearing", "A bearing at z: constant coefficients, a table or a fluid film")
        .def(py::init(&bearing), py::kw_only(), py::arg("z"), py::arg("k") = 0.0, py::arg("c") = 0.0,
             py::arg("kxx") = py::none(), py::arg("kxy") = py::none(), py::arg("kyx") = py::none(),
             py::arg("kyy") = py::none(), py::arg("cxx") = py::none(), py::arg("cxy") = py::none(),
             py::arg("cyx") = py::none(), py::arg("cyy") = py::none(), py::arg("kzz") = 0.0, py::arg("czz") = 0.0)
        .def_static("table", &table, "Coefficients tabulated over speeds (rad/s)", py::kw_only(), py::arg("z"),
                    py::arg("speeds"), py::arg("k") = py::none(), py::arg("c") = py::none(), py::arg("kxx") = py::none(),
                    py::arg("kxy") = py::none(), py::arg("kyx") = py::none(), py::arg("kyy") = py::none(),
                    py::arg("cxx") = py::none(), py::arg("cxy") = py::none(), py::arg("cyx") = py::none(),
                    py::arg("cyy") = py::none())
        .def_static("fluid_film", &fluid_film, "A plain journal bearing from its geometry; load in N or \"auto\"",
                    py::kw_only(), py::arg("z"), py::arg("diameter"), py::arg("length"), py::arg("clearance"),
                    py::arg("viscosity"), py::arg("load") = py::str("auto"), py::arg("load_angle") = -90.0,
                    py::arg("max_eccentricity") = 0.95, py::arg("solution") = "short",
                    py::arg("grid_circumferential") = 240, py::arg("grid_axial") = 32,
                    py::arg("clearance_min") = py::none(), py::arg("clearance_max") = py::none(),
                    py::arg("viscosity_min") = py::none(), py::arg("viscosity_max") = py::none())
        .def_property_readonly("z", [](const RotorBearing& b) { return b.z; })
        .def_property_readonly("kind", [](const RotorBearing& b) {
            return b.kind == RotorBearing::Kind::constant ? "constant"
                   : b.kind == RotorBearing::Kind::table  ? "table"
                                                          : "fluid_film";
        });
    py::class_<RotorSupport>(m, "Support", "A rigid support at z: pinned (x, y) or clamped (and the rotations)")
        .def(py::init(&support), py::kw_only(), py::arg("z"), py::arg("type") = "pinned", py::arg("axial") = false,
             py::arg("torsion") = false)
        .def_property_readonly("z", [](const RotorSupport& s) { return s.z; });
    py::class_<RotorPedestal>(m, "Pedestal", "A mass on springs and dampers under the bearings at z")
        .def(py::init(&pedestal), py::kw_only(), py::arg("z"), py::arg("mass"), py::arg("k") = 0.0, py::arg("c") = 0.0,
             py::arg("kxx") = py::none(), py::arg("kyy") = py::none(), py::arg("cxx") = py::none(),
             py::arg("cyy") = py::none())
        .def_property_readonly("z", [](const RotorPedestal& p) { return p.z; });
    py::class_<RotorModel>(m, "Rotor", "An FE rotor: sections from z = 0, and disks, bearings, supports, pedestals at z")
        .def(py::init([](std::vector<RotorSection> sections, std::vector<RotorDisk> disks,
                         std::vector<RotorBearing> bearings, std::vector<RotorSupport> supports,
                         std::vector<RotorPedestal> pedestals, const std::string& motion, bool shear_deformation,
                         bool rotary_inertia, double damping_alpha, double damping_beta,
                         const py::object& damping_zeta) {
                 RotorModel r;
                 r.sections = named(std::move(sections), "sections");
                 r.disks = named(std::move(disks), "disks");
                 r.bearings = named(std::move(bearings), "bearings");
                 r.supports = named(std::move(supports), "supports");
                 r.pedestals = named(std::move(pedestals), "pedestals");
                 r.motion = motion_of(motion);
                 r.shear_deformation = shear_deformation;
                 r.rotary_inertia = rotary_inertia;
                 r.shaft_damping = {damping_alpha, damping_beta, {}};
                 // One ratio for every mode, or the ratios of the lowest modes (the last for those above).
                 if (!damping_zeta.is_none())
                     r.shaft_damping.modal = py::isinstance<py::sequence>(damping_zeta)
                                                 ? damping_zeta.cast<std::vector<double>>()
                                                 : std::vector<double>{damping_zeta.cast<double>()};
                 return r;
             }),
             py::kw_only(), py::arg("sections"), py::arg("disks") = std::vector<RotorDisk>{},
             py::arg("bearings") = std::vector<RotorBearing>{}, py::arg("supports") = std::vector<RotorSupport>{},
             py::arg("pedestals") = std::vector<RotorPedestal>{}, py::arg("motion") = "lateral",
             py::arg("shear_deformation") = true, py::arg("rotary_inertia") = true, py::arg("damping_alpha") = 0.0,
             py::arg("damping_beta") = 0.0, py::arg("damping_zeta") = py::none())
        .def_readonly("sections", &RotorModel::sections)
        .def_readonly("disks", &RotorModel::disks)
        .def_readonly("bearings", &RotorModel::bearings)
        .def_readonly("supports", &RotorModel::supports)
        .def_readonly("pedestals", &RotorModel::pedestals)
        .def_property_readonly("motion", [](const RotorModel& r) { return to_string(r.motion); });

    bind_parameters(m, "GyrostatParameters",
                    "The gyrostat with elastic shaft (docs/gyrostat.md): keywords and attributes named as the "
                    "scene's [model] keys (SI units); shaft and housing 'elastic' or 'rigid'",
                    gyrostat_keys());
    bind_parameters(m, "FluidRotorParameters",
                    "The liquid-filled rotor (docs/fluid_rotor.md): keywords and attributes named as the scene's "
                    "[model] keys (SI units); modes 0: the sloshing sum truncated at `tolerance`",
                    fluid_keys());
    // One call per model kind; each with the scene's [speeds] and [analysis] as mapped by gyrokit/__init__.py.
    m.def("rotor_scene",
          [](const RotorModel& model, const std::string& title, const py::object& speeds, const py::object& modes,
             const py::object& harmonics, const std::string& solver, const py::object& target, double target_order,
             const py::object& f_cut) {
              return with_settings(rotor_scene(model, title), speeds, modes, harmonics, solver, target, target_order,
                                   f_cut);
          },
          py::arg("rotor"), py::arg("title"), py::arg("speeds"), py::arg("modes"), py::arg("harmonics"),
          py::arg("solver"), py::arg("target"), py::arg("target_order"), py::arg("f_cut") = py::none());
    m.def("gyrostat_scene",
          [](const GyrostatParameters& p, const std::string& title, const py::object& speeds, const py::object& modes,
             const py::object& harmonics, const std::string& solver, const py::object& target, double target_order,
             const py::object& f_cut) {
              return with_settings(model_scene(p, title), speeds, modes, harmonics, solver, target, target_order,
                                   f_cut);
          },
          py::arg("parameters"), py::arg("title"), py::arg("speeds"), py::arg("modes"), py::arg("harmonics"),
          py::arg("solver"), py::arg("target"), py::arg("target_order"), py::arg("f_cut") = py::none());
    m.def("fluid_rotor_scene",
          [](const FluidRotorParameters& p, const std::string& title, const py::object& speeds,
             const py::object& modes, const py::object& harmonics, const std::string& solver,
             const py::object& target, double target_order, const py::object& f_cut) {
              return with_settings(model_scene(p, title), speeds, modes, harmonics, solver, target, target_order,
                                   f_cut);
          },
          py::arg("parameters"), py::arg("title"), py::arg("speeds"), py::arg("modes"), py::arg("harmonics"),
          py::arg("solver"), py::arg("target"), py::arg("target_order"), py::arg("f_cut") = py::none());
    scene.def_property_readonly("rotor", [](const Scene& s) {
        return s.rotor_model() ? std::optional<RotorModel>(*s.rotor_model()) : std::nullopt;
    })
        .def_property_readonly("gyrostat", [](const Scene& s) {
            return s.gyrostat() ? std::optional<GyrostatParameters>(*s.gyrostat()) : std::nullopt;
        }, "A copy of the gyrostat's parameters (None for another model): edit it and make a new scene")
        .def_property_readonly("fluid_rotor", [](const Scene& s) {
            return s.fluid() ? std::optional<FluidRotorParameters>(*s.fluid()) : std::nullopt;
        }, "A copy of the liquid-filled rotor's parameters (None for another model): edit it and make a new scene")
        .def("to_toml", &scene_text, "The scene as TOML that load_scene reads back to the same model and settings")
        .def("write", &write_scene, py::arg("path"), "Writes the scene to `path` (to_toml)")
        .def(py::pickle([](const Scene& s) { return py::make_tuple(scene_text(s), s.path); },
                        [](const py::tuple& t) {
                            return parse_scene(t[0].cast<std::string>(), t[1].cast<std::string>(), ".");
                        }));
}
