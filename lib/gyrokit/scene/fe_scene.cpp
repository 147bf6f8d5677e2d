#include "gyrokit/scene/detail/fe_scene.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/bearing_csv.hpp>
#include <gyrokit/models/journal_bearing.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/materials.hpp>
#include <gyrokit/core/constants.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <fmt/format.h>

namespace gyrokit {

namespace {

// The entries of an array of tables [[model.NAME]], each with its TomlKeys.
template <class F>
void for_each_entry(const TomlKeys& k, const std::string& name, bool required, const F& f) {
    const toml::node* n = k.table().get(name);
    if (!n) {
        if (required) throw InputError(k.where(name) + " is missing; required: one or more [[model." + name + "]] tables");
        return;
    }
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables())
        throw InputError(k.where(name) + " must be an array of tables [[model." + name + "]]");
    // Numbered from 0, as a sweep's parameter paths address them (model.bearing[0].kxx).
    int i = 0;
    for (const auto& e : *a) f(TomlKeys(k.file(), fmt::format("model.{}[{}]", name, i++), *e.as_table()));
}

// Lengths as the scene writes them: `length_unit` = "m" (default) or "mm" in [model].
struct LengthUnit {
    double scale = 1.0;      // metres per scene unit
    const char* name = "m";
    // A length key with lower bound 0 (strict if `strict`), in metres.
    double operator()(const TomlKeys& e, const char* key, std::optional<double> fallback, bool strict) const {
        return e.number(key, fallback, 0.0, strict, name) * scale;
    }
};

// "file: [model.bearing[1]]": an item's origin in messages (where(key) is origin + " " + key).
std::string origin_of(const TomlKeys& e) {
    std::string origin = e.where("");
    origin.pop_back();
    return origin;
}

// An array of numbers [[model.bearing]] KEY = [...] of `count` entries (0: any count >= 2).
std::vector<double> numbers(const TomlKeys& e, const char* key, std::size_t count, const char* unit) {
    const toml::array* a = e.table().get(key) ? e.table().get(key)->as_array() : nullptr;
    const std::string want = count ? fmt::format("an array of {} numbers ({}), one per speed", count, unit)
                                   : fmt::format("an array of at least 2 numbers ({})", unit);
    if (!a) throw InputError(e.where(key) + " must be " + want);
    std::vector<double> v;
    for (const auto& x : *a) {
        const std::optional<double> d = x.value<double>();
        if (!d || !std::isfinite(*d))
            throw InputError(fmt::format("{} entry {} is not a finite number; allowed: {}", e.where(key), v.size() + 1,
                                         want));
        e.refuse_subnormal(fmt::format("{}[{}]", key, v.size()), *d);
        v.push_back(*d);
    }
    if (count ? v.size() != count : v.size() < 2)
        throw InputError(fmt::format("{} has {} entries; allowed: {}", e.where(key), v.size(), want));
    return v;
}

// Modal damping of the shaft: damping_zeta = 0.005 (every mode) or [0.005, 0.01, ...]
// (the lowest modes in order, the last for every mode above); each 0 <= zeta < 1.
std::vector<double> modal_zeta(const TomlKeys& k) {
    const toml::node* n = k.table().get("damping_zeta");
    if (!n) return {};
    const std::string allowed = "a damping ratio 0 <= zeta < 1, or an array of them for the shaft's lowest modes";
    std::vector<double> out;
    const auto take = [&](const toml::node& x, const std::string& where) {
        const std::optional<double> d = x.value<double>();
        if (!d || !(x.is_floating_point() || x.is_integer()))
            throw InputError(fmt::format("{} is not a number; allowed: {}", where, allowed));
        if (!(*d >= 0.0 && *d < 1.0))
            throw InputError(fmt::format("{} = {}: out of range; allowed: {}", where, *d, allowed));
        out.push_back(*d);
    };
    if (const toml::array* a = n->as_array()) {
        if (a->empty()) throw InputError(k.where("damping_zeta") + " is empty; allowed: " + allowed);
        for (std::size_t i = 0; i < a->size(); ++i) take(*a->get(i), fmt::format("{}[{}]", k.where("damping_zeta"), i));
    } else {
        take(*n, k.where("damping_zeta"));
    }
    return out;
}

// A bearing table written in the scene: `speeds` (in `speed_unit`, default rad/s) and
// the coefficient arrays (`k`, `c` isotropic, or kxx ... cyy; missing ones are 0).
BearingTable inline_bearing_table(const TomlKeys& e) {
    BearingTable t;
    t.name = e.where("speeds");   // until it is attached (then table_<node>)
    SpeedUnit unit;
    const std::string unit_name = e.choice("speed_unit", "rad/s", {});
    try {
        unit = SpeedUnit::parse(unit_name);
    } catch (const InputError&) {
        throw InputError(e.where("speed_unit") + " = '" + unit_name + "': allowed: rad/s, Hz, rpm");
    }
    t.speeds = numbers(e, "speeds", 0, unit.name.c_str());
    // Order and sign in the scene's unit, as written (the table's own checks would show rad/s).
    for (std::size_t i = 0; i < t.speeds.size(); ++i) {
        if (t.speeds[i] < 0)
            throw InputError(fmt::format("{} entry {} = {} {}; allowed: >= 0", e.where("speeds"), i + 1, t.speeds[i],
                                         unit.name));
        if (i > 0 && !(t.speeds[i] > t.speeds[i - 1]))
            throw InputError(fmt::format("{} entry {} = {} {} does not exceed entry {} = {}; allowed: strictly "
                                         "increasing speeds",
                                         e.where("speeds"), i + 1, t.speeds[i], unit.name, i, t.speeds[i - 1]));
    }
    for (double& w : t.speeds) w /= unit.factor;
    const std::size_t n = t.speeds.size();
    t.rows.resize(n);
    const auto column = [&](const char* key, const char* iso, const char* u) {
        if (e.has(key)) return numbers(e, key, n, u);
        if (e.has(iso)) return numbers(e, iso, n, u);
        return std::vector<double>(n, 0.0);
    };
    const std::vector<double> kxx = column("kxx", "k", "N/m"), kyy = column("kyy", "k", "N/m"),
                              kxy = column("kxy", "", "N/m"), kyx = column("kyx", "", "N/m"),
                              cxx = column("cxx", "c", "N s/m"), cyy = column("cyy", "c", "N s/m"),
                              cxy = column("cxy", "", "N s/m"), cyx = column("cyx", "", "N s/m");
    for (std::size_t i = 0; i < n; ++i) {
        t.rows[i].K << kxx[i], kxy[i], kyx[i], kyy[i];
        t.rows[i].C << cxx[i], cxy[i], cyx[i], cyy[i];
    }
    return t;
}

// What every item's reader needs from the [model] table.
struct ModelContext {
    LengthUnit len;
    FeMotion motion = FeMotion::lateral;
    // A model whose motion is given uses of each item only what acts on its DOFs, so one
    // rotor description serves every motion; without it (lateral: by default or by
    // dofs_per_node = 4) axial and torsional keys are refused: they would model nothing.
    bool lateral_only = true;
    std::vector<Material> own;   // the scene's [[model.materials]]
    std::optional<double> E0, rho0;
    double nu0 = 0.3;

    bool has(FeMotion m) const { return motion == m || motion == FeMotion::all; }
    std::optional<Material> material_of(const TomlKeys& e) const {
        if (!e.has("material")) return std::nullopt;
        return find_material(e.choice("material", "", {}), own, e.where("material"));
    }
};

const char* const kNeedsAxialDofs = "allowed: with dofs_per_node = 6 or a motion in [model] (without a motion "
                                    "the model is lateral, 4 DOFs per node)";

double poisson_of(const TomlKeys& e, std::optional<double> fallback) {
    const double nu = e.number("poisson", fallback, -1, true, "1");
    if (nu > 0.5)
        throw InputError(fmt::format("{} = {}: out of range; allowed: -1 < poisson <= 0.5", e.where("poisson"), nu));
    return nu;
}

// The DOF set: motion, or dofs_per_node (4: lateral, 6: all); given both, they agree.
FeMotion motion_of(const TomlKeys& k) {
    const std::string motion = k.choice("motion", "", {"lateral", "all", "axial", "torsional"});
    const long long per = k.integer("dofs_per_node", 4, std::numeric_limits<long long>::min(),
                                    std::numeric_limits<long long>::max());
    const FeMotion by_motion = motion == "all"         ? FeMotion::all
                               : motion == "axial"     ? FeMotion::axial
                               : motion == "torsional" ? FeMotion::torsional
                                                       : FeMotion::lateral;
    if (motion.empty()) {
        if (per != 4 && per != 6)
            throw InputError(fmt::format("{} = {}; allowed: 4 (lateral) or 6 (lateral, axial, torsion), or 1 with "
                                         "motion = \"axial\" or \"torsional\"",
                                         k.where("dofs_per_node"), per));
        return per == 6 ? FeMotion::all : FeMotion::lateral;
    }
    if (k.has("dofs_per_node") && per != dofs_per_node(by_motion))
        throw InputError(fmt::format("{} = {} disagrees with motion = \"{}\"; allowed: {} (or leave it out)",
                                     k.where("dofs_per_node"), per, motion, dofs_per_node(by_motion)));
    return by_motion;
}

// The scene's own materials, then the model's material: E, poisson and density
// where the items' keys do not give them.
void read_materials(const TomlKeys& k, ModelContext& c) {
    for_each_entry(k, "materials", false, [&](const TomlKeys& e) {
        e.only({"name", "E", "poisson", "density"});
        Material m;
        m.name = e.choice("name", "", {});
        if (m.name.empty()) throw InputError(e.where("name") + " is missing; required: the material's name");
        m.youngs_modulus = e.number("E", std::nullopt, 0, true, "Pa");
        m.poisson_ratio = poisson_of(e, 0.3);
        m.density = e.number("density", std::nullopt, 0, true, "kg/m^3");
        m.source = "scene";
        for (const Material& o : c.own)
            if (o.name == m.name)
                throw InputError(e.where("name") + " = '" + m.name + "' names a material twice; allowed: each name once");
        c.own.push_back(m);
    });
    const std::optional<Material> mat0 = c.material_of(k);
    if (k.has("E"))
        c.E0 = k.number("E", std::nullopt, 0, true, "Pa");
    else if (mat0)
        c.E0 = mat0->youngs_modulus;
    if (k.has("density"))
        c.rho0 = k.number("density", std::nullopt, 0, true, "kg/m^3");
    else if (mat0)
        c.rho0 = mat0->density;
    c.nu0 = k.has("poisson") ? poisson_of(k, std::nullopt) : mat0 ? mat0->poisson_ratio : 0.3;
}

// A flexible coupling in the chain: one element of its length.
RotorSection read_coupling(const TomlKeys& e, const ModelContext& c) {
    e.only({"type", "length", "k_lateral", "k_bending", "k_axial", "k_torsion", "c_lateral", "c_bending", "c_axial",
            "c_torsion", "mass", "Id", "Ip"});
    if (c.lateral_only)
        for (const char* key : {"k_axial", "k_torsion", "c_axial", "c_torsion"})
            if (e.has(key))
                throw InputError(e.where(key) + " acts on an axial or torsional DOF; " + kNeedsAxialDofs);
    RotorSection s;
    s.origin = origin_of(e);
    s.shape.length = c.len(e, "length", std::nullopt, true);
    // The springs of the DOFs the model has are required, the dampers optional.
    const auto needed = [](bool has) { return has ? std::nullopt : std::optional(0.0); };
    const bool lateral = c.has(FeMotion::lateral);
    FeCoupling& k = s.shape.coupling.emplace();
    k.k_lateral = e.number("k_lateral", needed(lateral), 0, false, "N/m");
    k.k_bending = e.number("k_bending", needed(lateral), 0, false, "N m/rad");
    k.k_axial = e.number("k_axial", needed(c.has(FeMotion::axial)), 0, false, "N/m");
    k.k_torsion = e.number("k_torsion", needed(c.has(FeMotion::torsional)), 0, false, "N m/rad");
    k.c_lateral = e.number("c_lateral", 0.0, 0, false, "N s/m");
    k.c_bending = e.number("c_bending", 0.0, 0, false, "N m s/rad");
    k.c_axial = e.number("c_axial", 0.0, 0, false, "N s/m");
    k.c_torsion = e.number("c_torsion", 0.0, 0, false, "N m s/rad");
    k.mass = e.number("mass", 0.0, 0, false, "kg");
    k.diametral_inertia = e.number("Id", 0.0, 0, false, "kg m^2");
    k.polar_inertia = e.number("Ip", 0.0, 0, false, "kg m^2");
    return s;
}

// A beam section of `elements` equal elements; conical when outer_diameter_end or
// inner_diameter_end is given. `before`: the elements of the sections before it.
RotorSection read_section(const TomlKeys& e, const ModelContext& c, std::size_t before) {
    if (e.choice("type", "beam", {"beam", "coupling"}) == "coupling") return read_coupling(e, c);
    e.only({"type", "length", "elements", "outer_diameter", "inner_diameter", "outer_diameter_end",
            "inner_diameter_end", "E", "G", "poisson", "density", "material"});
    const LengthUnit& len = c.len;
    const std::optional<Material> mat = c.material_of(e);
    RotorSection s;
    s.origin = origin_of(e);
    FeShaftElement& el = s.shape;
    el.length = len(e, "length", std::nullopt, true);
    s.elements = static_cast<int>(e.integer("elements", 1, 1, kMaxFeElements));
    if (before + static_cast<std::size_t>(s.elements) > static_cast<std::size_t>(kMaxFeElements))
        throw InputError(fmt::format("{} = {} makes {} elements in all; allowed: at most {} (20,000,000 DOFs)",
                                     e.where("elements"), s.elements, before + s.elements, kMaxFeElements));
    el.outer_diameter = len(e, "outer_diameter", std::nullopt, true);
    el.inner_diameter = len(e, "inner_diameter", 0.0, false);
    if (e.has("outer_diameter_end")) el.outer_diameter_end = len(e, "outer_diameter_end", std::nullopt, true);
    if (e.has("inner_diameter_end")) el.inner_diameter_end = len(e, "inner_diameter_end", std::nullopt, false);
    const double o1 = el.outer_diameter_end.value_or(el.outer_diameter);
    const double i1 = el.inner_diameter_end.value_or(el.inner_diameter);
    if (el.inner_diameter >= el.outer_diameter)
        throw InputError(fmt::format("{} = {} is not below outer_diameter = {}; allowed: 0 <= inner < outer ({})",
                                     e.where("inner_diameter"), el.inner_diameter / len.scale,
                                     el.outer_diameter / len.scale, len.name));
    if (i1 >= o1)
        throw InputError(fmt::format("{} = {} is not below the outer diameter {} there; allowed: 0 <= inner < "
                                     "outer at the section's end ({})",
                                     e.where(e.has("inner_diameter_end") ? "inner_diameter_end" : "inner_diameter"),
                                     i1 / len.scale, o1 / len.scale, len.name));
    el.youngs_modulus = e.number("E", mat ? std::optional(mat->youngs_modulus) : c.E0, 0, true, "Pa");
    el.density = e.number("density", mat ? std::optional(mat->density) : c.rho0, 0, true, "kg/m^3");
    el.poisson_ratio = e.has("poisson") ? poisson_of(e, std::nullopt) : mat ? mat->poisson_ratio : c.nu0;
    // The shear modulus where it is not E / (2 (1 + poisson)) (an orthotropic composite shaft).
    if (e.has("G")) el.shear_modulus = e.number("G", std::nullopt, 0, true, "Pa");
    return s;
}

RotorDisk read_disk(const TomlKeys& e, const ModelContext& c) {
    e.only({"z", "mass", "Id", "Ip", "unbalance", "phase", "outer_diameter", "inner_diameter", "width", "material",
            "density"});
    const LengthUnit& len = c.len;
    RotorDisk d;
    d.origin = origin_of(e);
    d.z = len(e, "z", std::nullopt, false);
    if (e.has("outer_diameter")) {
        // From its geometry: a hollow cylinder of the disk's (or the model's) material.
        for (const char* key : {"mass", "Id", "Ip"})
            if (e.has(key))
                throw InputError(e.where(key) + " is given together with outer_diameter; allowed: either mass, "
                                                "Id, Ip or the geometry outer_diameter, inner_diameter, width");
        DiskGeometry& g = d.geometry.emplace();
        g.outer_diameter = len(e, "outer_diameter", std::nullopt, true);
        g.inner_diameter = len(e, "inner_diameter", 0.0, false);
        if (g.inner_diameter >= g.outer_diameter)
            throw InputError(fmt::format("{} = {} is not below outer_diameter = {}; allowed: 0 <= inner < outer ({})",
                                         e.where("inner_diameter"), g.inner_diameter / len.scale,
                                         g.outer_diameter / len.scale, len.name));
        g.width = len(e, "width", std::nullopt, true);
        const std::optional<Material> mat = c.material_of(e);
        g.density = e.number("density", mat ? std::optional(mat->density) : c.rho0, 0, true, "kg/m^3");
    } else {
        for (const char* key : {"inner_diameter", "width", "material", "density"})
            if (e.has(key))
                throw InputError(e.where(key) + " needs outer_diameter; allowed: the geometry outer_diameter, "
                                                "inner_diameter, width (and material or density), or mass, Id, Ip");
        d.disk.mass = e.number("mass", std::nullopt, 0, false, "kg");
        d.disk.diametral_inertia = e.number("Id", 0.0, 0, false, "kg m^2");
        d.disk.polar_inertia = e.number("Ip", 0.0, 0, false, "kg m^2");
    }
    d.disk.unbalance = e.number("unbalance", 0.0, 0, false, "kg m");
    d.disk.unbalance_phase = e.has("phase") ? e.any_number("phase", "deg") * kPi / 180.0 : 0.0;
    return d;
}

// A fluid-film journal bearing from its geometry; load = "auto": its share of the rotor's weight.
void read_fluid_film(const TomlKeys& e, const ModelContext& c, RotorBearing& b) {
    e.only({"type", "z", "diameter", "length", "clearance", "viscosity", "load", "load_angle", "max_eccentricity",
            "solution", "grid_circumferential", "grid_axial", "clearance_min", "clearance_max", "viscosity_min",
            "viscosity_max"});
    b.kind = RotorBearing::Kind::fluid_film;
    JournalBearing& j = b.film;
    j.diameter = c.len(e, "diameter", std::nullopt, true);
    j.length = c.len(e, "length", std::nullopt, true);
    j.clearance = c.len(e, "clearance", std::nullopt, true);
    j.viscosity = e.number("viscosity", std::nullopt, 0.0, true, "Pa s");
    // The tolerance bands (their order is checked by JournalBearing::validate).
    if (e.has("clearance_min")) j.clearance_min = c.len(e, "clearance_min", std::nullopt, true);
    if (e.has("clearance_max")) j.clearance_max = c.len(e, "clearance_max", std::nullopt, true);
    if (e.has("viscosity_min")) j.viscosity_min = e.number("viscosity_min", std::nullopt, 0.0, true, "Pa s");
    if (e.has("viscosity_max")) j.viscosity_max = e.number("viscosity_max", std::nullopt, 0.0, true, "Pa s");
    const toml::node* load = e.table().get("load");
    b.auto_load = load && load->is_string();
    if (b.auto_load && *load->value<std::string>() != "auto")
        throw InputError(e.where("load") + " = '" + *load->value<std::string>() +
                         "'; allowed: a number > 0 (N) or \"auto\" (from the rotor's weight)");
    j.load = b.auto_load ? 1.0 : e.number("load", std::nullopt, 0.0, true, "N");
    if (e.has("load_angle")) {
        const double deg = e.any_number("load_angle", "deg");
        if (!(std::fabs(deg) <= 360.0))
            throw InputError(fmt::format("{} = {}; allowed: -360 to 360 (deg)", e.where("load_angle"), deg));
        j.load_angle = deg * kPi / 180.0;
    }
    j.max_eccentricity = e.number("max_eccentricity", 0.95, 0.0, true, "eccentricity ratio, 0.01 to 0.999");
    // The film's solution: the short-bearing closed form or the finite-difference Reynolds
    // solution on a grid (intervals around the circumference and over the length).
    if (e.choice("solution", "short", {"short", "finite_difference"}) == "finite_difference") {
        j.solution = FilmSolution::finite_difference;
        j.grid_circumferential = static_cast<int>(e.integer("grid_circumferential", j.grid_circumferential, 16, 2880));
        j.grid_axial = static_cast<int>(e.integer("grid_axial", j.grid_axial, 4, 256));
    } else {
        for (const char* key : {"grid_circumferential", "grid_axial"})
            if (e.has(key))
                throw InputError(e.where(key) + " is given with solution = \"short\"; allowed: grid keys only "
                                                "with solution = \"finite_difference\"");
    }
    if (!b.auto_load) j.validate(b.origin, c.len.scale, c.len.name);   // lengths in the scene's unit
}

// A bearing: constant coefficients, a table (in the scene or a CSV file relative to
// `dir`) or a fluid film.
RotorBearing read_bearing(const TomlKeys& e, const ModelContext& c, const std::string& dir) {
    RotorBearing b;
    b.origin = origin_of(e);
    const std::string type = e.choice("type", "linear", {"linear", "fluid_film"});
    if (type == "fluid_film") {
        read_fluid_film(e, c, b);
        b.z = c.len(e, "z", std::nullopt, false);
        return b;
    }
    e.only({"type", "z", "k", "c", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "kzz", "czz", "table",
            "speeds", "speed_unit"});
    b.z = c.len(e, "z", std::nullopt, false);
    if (e.has("speeds")) {
        for (const char* key : {"table", "kzz", "czz"})
            if (e.has(key))
                throw InputError(e.where(key) + " is given together with speeds; allowed: a table in the scene "
                                                "(speeds with k, c or kxx ... cyy arrays) without " + key);
        b.kind = RotorBearing::Kind::table;
        b.table = inline_bearing_table(e);
        return b;
    }
    if (e.has("speed_unit"))
        throw InputError(e.where("speed_unit") + " needs speeds; allowed: with a table in the scene (speeds = [...])");
    if (c.lateral_only)
        for (const char* key : {"kzz", "czz"})
            if (e.has(key)) throw InputError(e.where(key) + " acts on the axial DOF z; " + kNeedsAxialDofs);
    if (e.has("table")) {
        for (const char* key : {"k", "c", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"})
            if (e.has(key))
                throw InputError(e.where(key) + " is given together with table; allowed: either a table or "
                                                "constant coefficients");
        b.kind = RotorBearing::Kind::table;
        b.table_file = (std::filesystem::path(dir) / e.choice("table", "", {})).string();
        b.table = read_bearing_csv(b.table_file, 2, 0, 1);   // its DOFs are found when the rotor is built
        return b;
    }
    FeBearing& f = b.constant;
    const double kk = e.number("k", 0.0, 0, false, "N/m"), cc = e.number("c", 0.0, 0, false, "N s/m");
    f.kxx = e.has("kxx") ? e.any_number("kxx", "N/m") : kk;
    f.kyy = e.has("kyy") ? e.any_number("kyy", "N/m") : kk;
    f.kxy = e.has("kxy") ? e.any_number("kxy", "N/m") : 0.0;
    f.kyx = e.has("kyx") ? e.any_number("kyx", "N/m") : 0.0;
    f.cxx = e.has("cxx") ? e.any_number("cxx", "N s/m") : cc;
    f.cyy = e.has("cyy") ? e.any_number("cyy", "N s/m") : cc;
    f.cxy = e.has("cxy") ? e.any_number("cxy", "N s/m") : 0.0;
    f.cyx = e.has("cyx") ? e.any_number("cyx", "N s/m") : 0.0;
    f.kzz = e.number("kzz", 0.0, 0, false, "N/m");
    f.czz = e.number("czz", 0.0, 0, false, "N s/m");
    return b;
}

RotorSupport read_support(const TomlKeys& e, const ModelContext& c) {
    e.only({"z", "type", "axial", "torsion"});
    RotorSupport s;
    s.origin = origin_of(e);
    s.z = c.len(e, "z", std::nullopt, false);
    const std::string type = e.choice("type", "pinned", {"pinned", "clamped"});
    s.hold.theta_x = s.hold.theta_y = type == "clamped";
    // Axial and torsional holds: a clamped end holds them too; a pinned one where it says so.
    const auto hold = [&](const char* key) {
        const toml::node* n = e.table().get(key);
        if (!n) return !c.lateral_only && type == "clamped";
        if (!n->is_boolean()) throw InputError(e.where(key) + " must be true or false");
        if (c.lateral_only && *n->value<bool>())
            throw InputError(e.where(key) + " = true holds a DOF the model does not have; " + kNeedsAxialDofs);
        return *n->value<bool>();
    };
    s.hold.z = hold("axial");
    s.hold.theta_z = hold("torsion");
    return s;
}

RotorPedestal read_pedestal(const TomlKeys& e, const ModelContext& c) {
    e.only({"z", "mass", "k", "c", "kxx", "kyy", "cxx", "cyy"});
    RotorPedestal p;
    p.origin = origin_of(e);
    p.z = c.len(e, "z", std::nullopt, false);
    p.pedestal.mass = e.number("mass", std::nullopt, 0, true, "kg");
    const double kk = e.number("k", 0.0, 0, false, "N/m"), cc = e.number("c", 0.0, 0, false, "N s/m");
    p.pedestal.kxx = e.number("kxx", kk, 0, false, "N/m");
    p.pedestal.kyy = e.number("kyy", kk, 0, false, "N/m");
    p.pedestal.cxx = e.number("cxx", cc, 0, false, "N s/m");
    p.pedestal.cyy = e.number("cyy", cc, 0, false, "N s/m");
    return p;
}

}  // namespace

RotorModel rotor_model_from(const TomlKeys& k, const std::string& dir) {
    k.only({"type", "shaft", "disk", "bearing", "support", "E", "poisson", "density", "material", "materials",
            "shear_deformation", "rotary_inertia", "dofs_per_node", "motion", "length_unit", "pedestal",
            "damping_alpha", "damping_beta", "damping_zeta"});
    RotorModel model;
    ModelContext c;
    c.motion = model.motion = motion_of(k);
    c.lateral_only = model.motion == FeMotion::lateral && !k.has("motion");
    if (k.choice("length_unit", "m", {"m", "mm"}) == "mm") {
        c.len = {1e-3, "mm"};
        model.length_unit = "mm";
    }
    const auto flag = [&](const char* key) {
        const toml::node* n = k.table().get(key);
        if (!n) return true;
        if (!n->is_boolean()) throw InputError(k.where(key) + " must be true or false");
        return *n->value<bool>();
    };
    model.shear_deformation = flag("shear_deformation");
    model.rotary_inertia = flag("rotary_inertia");
    // Proportional damping of the shaft: D = alpha M_shaft + beta K_shaft.
    model.shaft_damping.alpha = k.number("damping_alpha", 0.0, 0, false, "1/s");
    model.shaft_damping.beta = k.number("damping_beta", 0.0, 0, false, "s");
    model.shaft_damping.modal = modal_zeta(k);
    read_materials(k, c);
    std::size_t elements = 0;
    for_each_entry(k, "shaft", true, [&](const TomlKeys& e) {
        model.sections.push_back(read_section(e, c, elements));
        elements += static_cast<std::size_t>(model.sections.back().shape.coupling ? 1 : model.sections.back().elements);
    });
    for_each_entry(k, "disk", false, [&](const TomlKeys& e) { model.disks.push_back(read_disk(e, c)); });
    for_each_entry(k, "bearing", false, [&](const TomlKeys& e) { model.bearings.push_back(read_bearing(e, c, dir)); });
    for_each_entry(k, "support", false, [&](const TomlKeys& e) { model.supports.push_back(read_support(e, c)); });
    for_each_entry(k, "pedestal", false, [&](const TomlKeys& e) { model.pedestals.push_back(read_pedestal(e, c)); });
    return model;
}

}  // namespace gyrokit
