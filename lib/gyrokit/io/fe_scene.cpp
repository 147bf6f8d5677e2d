#include "gyrokit/io/detail/fe_scene.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/io/bearing_csv.hpp>
#include <gyrokit/models/journal_bearing.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/materials.hpp>

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

// The node at axial position z; the position must be a node within 1e-9 of the length.
int node_at(const TomlKeys& e, const std::vector<double>& z, const LengthUnit& unit) {
    const double L = z.back();
    const double zi = unit(e, "z", std::nullopt, false);
    const auto it = std::lower_bound(z.begin(), z.end(), zi - 1e-9 * L);
    if (it == z.end() || std::abs(*it - zi) > 1e-9 * L) {
        double nearest = z.front();
        for (double x : z)
            if (std::abs(x - zi) < std::abs(nearest - zi)) nearest = x;
        throw InputError(fmt::format("{} = {} {} is not a node of the mesh; allowed: a section end or "
                                     "subdivision, the nearest is {:.12g} (rotor length {:.12g})",
                                     e.where("z"), zi / unit.scale, unit.name, nearest / unit.scale,
                                     L / unit.scale));
    }
    return static_cast<int>(it - z.begin());
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

}  // namespace

GyroscopicSystem fe_rotor_from(const TomlKeys& k, const std::string& dir, FeRotor* rotor) {
    k.only({"type", "shaft", "disk", "bearing", "support", "E", "poisson", "density", "material", "materials",
            "shear_deformation", "rotary_inertia", "dofs_per_node", "motion", "length_unit", "pedestal"});
    FeRotor r;
    // The DOF set: motion, or dofs_per_node (4: lateral, 6: all); given both, they agree.
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
        r.motion = per == 6 ? FeMotion::all : FeMotion::lateral;
    } else {
        if (k.has("dofs_per_node") && per != dofs_per_node(by_motion))
            throw InputError(fmt::format("{} = {} disagrees with motion = \"{}\"; allowed: {} (or leave it out)",
                                         k.where("dofs_per_node"), per, motion, dofs_per_node(by_motion)));
        r.motion = by_motion;
    }
    // A model whose motion is given uses of each item only what acts on its DOFs, so one
    // rotor description serves every motion; without it (lateral: by default or by
    // dofs_per_node = 4) axial and torsional keys are refused: they would model nothing.
    const bool lateral_only = r.motion == FeMotion::lateral && !k.has("motion");
    const std::string needs_axial_dofs = "allowed: with dofs_per_node = 6 or a motion in [model] (without a motion "
                                         "the model is lateral, 4 DOFs per node)";
    LengthUnit len;
    if (k.choice("length_unit", "m", {"m", "mm"}) == "mm") len = {1e-3, "mm"};
    const auto flag = [&](const char* key) {
        const toml::node* n = k.table().get(key);
        if (!n) return true;
        if (!n->is_boolean()) throw InputError(k.where(key) + " must be true or false");
        return *n->value<bool>();
    };
    r.shear_deformation = flag("shear_deformation");
    r.rotary_inertia = flag("rotary_inertia");
    // The scene's own materials, then the model's material: E, poisson and density
    // where the keys do not give them.
    std::vector<Material> own;
    for_each_entry(k, "materials", false, [&](const TomlKeys& e) {
        e.only({"name", "E", "poisson", "density"});
        Material m;
        m.name = e.choice("name", "", {});
        if (m.name.empty()) throw InputError(e.where("name") + " is missing; required: the material's name");
        m.youngs_modulus = e.number("E", std::nullopt, 0, true, "Pa");
        m.poisson_ratio = e.number("poisson", 0.3, -1, true, "1");
        if (m.poisson_ratio > 0.5)
            throw InputError(fmt::format("{} = {}: out of range; allowed: -1 < poisson <= 0.5", e.where("poisson"),
                                         m.poisson_ratio));
        m.density = e.number("density", std::nullopt, 0, true, "kg/m^3");
        m.source = "scene";
        for (const Material& o : own)
            if (o.name == m.name)
                throw InputError(e.where("name") + " = '" + m.name + "' names a material twice; allowed: each name once");
        own.push_back(m);
    });
    const auto material_of = [&](const TomlKeys& e) -> std::optional<Material> {
        if (!e.has("material")) return std::nullopt;
        return find_material(e.choice("material", "", {}), own, e.where("material"));
    };
    const std::optional<Material> mat0 = material_of(k);
    const std::optional<double> E0 = k.has("E") ? std::optional(k.number("E", std::nullopt, 0, true, "Pa"))
                                     : mat0     ? std::optional(mat0->youngs_modulus)
                                                : std::nullopt;
    const std::optional<double> rho0 = k.has("density")
                                           ? std::optional(k.number("density", std::nullopt, 0, true, "kg/m^3"))
                                       : mat0 ? std::optional(mat0->density)
                                              : std::nullopt;
    const double nu0 = k.has("poisson") ? k.number("poisson", std::nullopt, -1, true, "1")
                       : mat0           ? mat0->poisson_ratio
                                        : 0.3;
    if (nu0 > 0.5) throw InputError(fmt::format("{} = {}: out of range; allowed: -1 < poisson <= 0.5", k.where("poisson"), nu0));

    std::vector<double> z{0.0};
    for_each_entry(k, "shaft", true, [&](const TomlKeys& e) {
        if (e.choice("type", "beam", {"beam", "coupling"}) == "coupling") {
            // A flexible coupling in the chain: one element of its length.
            e.only({"type", "length", "k_lateral", "k_bending", "k_axial", "k_torsion", "c_lateral", "c_bending",
                    "c_axial", "c_torsion", "mass", "Id", "Ip"});
            if (lateral_only)
                for (const char* key : {"k_axial", "k_torsion", "c_axial", "c_torsion"})
                    if (e.has(key))
                        throw InputError(e.where(key) + " acts on an axial or torsional DOF; " + needs_axial_dofs);
            if (r.elements.size() + 1 > static_cast<std::size_t>(kMaxFeElements))
                throw InputError(fmt::format("{} makes {} elements in all; allowed: at most {}", e.where("type"),
                                             r.elements.size() + 1, kMaxFeElements));
            FeShaftElement el;
            el.length = len(e, "length", std::nullopt, true);
            // The springs of the DOFs the model has are required, the dampers optional.
            const auto needed = [](bool has) { return has ? std::nullopt : std::optional(0.0); };
            FeCoupling c;
            c.k_lateral = e.number("k_lateral", needed(r.has_lateral()), 0, false, "N/m");
            c.k_bending = e.number("k_bending", needed(r.has_lateral()), 0, false, "N m/rad");
            c.k_axial = e.number("k_axial", needed(r.has_axial()), 0, false, "N/m");
            c.k_torsion = e.number("k_torsion", needed(r.has_torsion()), 0, false, "N m/rad");
            c.c_lateral = e.number("c_lateral", 0.0, 0, false, "N s/m");
            c.c_bending = e.number("c_bending", 0.0, 0, false, "N m s/rad");
            c.c_axial = e.number("c_axial", 0.0, 0, false, "N s/m");
            c.c_torsion = e.number("c_torsion", 0.0, 0, false, "N m s/rad");
            c.mass = e.number("mass", 0.0, 0, false, "kg");
            c.diametral_inertia = e.number("Id", 0.0, 0, false, "kg m^2");
            c.polar_inertia = e.number("Ip", 0.0, 0, false, "kg m^2");
            el.coupling = c;
            r.elements.push_back(el);
            z.push_back(z.back() + el.length);
            return;
        }
        e.only({"type", "length", "elements", "outer_diameter", "inner_diameter", "outer_diameter_end", "inner_diameter_end",
                "E", "poisson", "density", "material"});
        const std::optional<Material> mat = material_of(e);
        FeShaftElement el;
        const double length = len(e, "length", std::nullopt, true);
        const int count = static_cast<int>(e.integer("elements", 1, 1, kMaxFeElements));
        // The sum over the sections, before any element is stored.
        if (r.elements.size() + static_cast<std::size_t>(count) > static_cast<std::size_t>(kMaxFeElements))
            throw InputError(fmt::format("{} = {} makes {} elements in all; allowed: at most {} (20,000,000 DOFs)",
                                         e.where("elements"), count, r.elements.size() + count, kMaxFeElements));
        el.length = length / count;
        // A conical section: the diameters vary linearly from its start to its end
        // (outer_diameter_end, inner_diameter_end); each of its elements is tapered.
        const double o0 = len(e, "outer_diameter", std::nullopt, true);
        const double i0 = len(e, "inner_diameter", 0.0, false);
        const bool tapered = e.has("outer_diameter_end") || e.has("inner_diameter_end");
        const double o1 = e.has("outer_diameter_end") ? len(e, "outer_diameter_end", std::nullopt, true) : o0;
        const double i1 = e.has("inner_diameter_end") ? len(e, "inner_diameter_end", std::nullopt, false) : i0;
        if (i0 >= o0)
            throw InputError(fmt::format("{} = {} is not below outer_diameter = {}; allowed: 0 <= inner < outer ({})",
                                         e.where("inner_diameter"), i0 / len.scale, o0 / len.scale, len.name));
        if (i1 >= o1)
            throw InputError(fmt::format("{} = {} is not below the outer diameter {} there; allowed: 0 <= inner < "
                                         "outer at the section's end ({})",
                                         e.where(e.has("inner_diameter_end") ? "inner_diameter_end" : "inner_diameter"),
                                         i1 / len.scale, o1 / len.scale, len.name));
        el.youngs_modulus = e.number("E", mat ? std::optional(mat->youngs_modulus) : E0, 0, true, "Pa");
        el.density = e.number("density", mat ? std::optional(mat->density) : rho0, 0, true, "kg/m^3");
        el.poisson_ratio = e.has("poisson") ? e.number("poisson", std::nullopt, -1, true, "1")
                           : mat            ? mat->poisson_ratio
                                            : nu0;
        if (el.poisson_ratio > 0.5)
            throw InputError(fmt::format("{} = {}: out of range; allowed: -1 < poisson <= 0.5", e.where("poisson"),
                                         el.poisson_ratio));
        for (int i = 0; i < count; ++i) {
            if (tapered) {
                const double a = static_cast<double>(i) / count, b = static_cast<double>(i + 1) / count;
                el.outer_diameter = o0 + a * (o1 - o0);
                el.inner_diameter = i0 + a * (i1 - i0);
                el.outer_diameter_end = o0 + b * (o1 - o0);
                el.inner_diameter_end = i0 + b * (i1 - i0);
            } else {
                el.outer_diameter = o0;
                el.inner_diameter = i0;
            }
            r.elements.push_back(el);
            z.push_back(z.back() + el.length);
        }
    });

    for_each_entry(k, "disk", false, [&](const TomlKeys& e) {
        e.only({"z", "mass", "Id", "Ip", "unbalance", "phase", "outer_diameter", "inner_diameter", "width",
                "material", "density"});
        FeDisk d;
        d.node = node_at(e, z, len);
        if (e.has("outer_diameter")) {
            // From its geometry: a hollow cylinder of the disk's (or the model's) material.
            for (const char* key : {"mass", "Id", "Ip"})
                if (e.has(key))
                    throw InputError(e.where(key) + " is given together with outer_diameter; allowed: either mass, "
                                                    "Id, Ip or the geometry outer_diameter, inner_diameter, width");
            const double Do = len(e, "outer_diameter", std::nullopt, true);
            const double Di = len(e, "inner_diameter", 0.0, false);
            if (Di >= Do)
                throw InputError(fmt::format("{} = {} is not below outer_diameter = {}; allowed: 0 <= inner < outer ({})",
                                             e.where("inner_diameter"), Di / len.scale, Do / len.scale, len.name));
            const double w = len(e, "width", std::nullopt, true);
            const std::optional<Material> mat = material_of(e);
            const double rho = e.number("density", mat ? std::optional(mat->density) : rho0, 0, true, "kg/m^3");
            const DiskInertia di = disk_inertia(Do, Di, w, rho);
            d.mass = di.mass;
            d.diametral_inertia = di.diametral_inertia;
            d.polar_inertia = di.polar_inertia;
        } else {
            for (const char* key : {"inner_diameter", "width", "material", "density"})
                if (e.has(key))
                    throw InputError(e.where(key) + " needs outer_diameter; allowed: the geometry outer_diameter, "
                                                    "inner_diameter, width (and material or density), or mass, Id, Ip");
            d.mass = e.number("mass", std::nullopt, 0, false, "kg");
            d.diametral_inertia = e.number("Id", 0.0, 0, false, "kg m^2");
            d.polar_inertia = e.number("Ip", 0.0, 0, false, "kg m^2");
        }
        d.unbalance = e.number("unbalance", 0.0, 0, false, "kg m");
        d.unbalance_phase = e.has("phase") ? e.any_number("phase", "deg") * std::acos(-1.0) / 180.0 : 0.0;
        r.disks.push_back(d);
    });

    // Speed-dependent bearings, attached once the constrained DOFs are known:
    // a coefficient table (CSV) or a fluid-film bearing from its geometry.
    struct Tabulated {
        int node;
        std::string path;                        // a table, or empty
        std::optional<JournalBearing> journal;   // a fluid-film bearing
        std::optional<BearingTable> written;     // a table written in the scene
        std::string where;
        bool auto_load = false;                  // a fluid film's load from the rotor's weight
        std::string origin;                      // "file: [table]" of a fluid film
    };
    std::vector<Tabulated> tables;
    for_each_entry(k, "bearing", false, [&](const TomlKeys& e) {
        const std::string type = e.choice("type", "linear", {"linear", "fluid_film"});
        if (type == "fluid_film") {
            e.only({"type", "z", "diameter", "length", "clearance", "viscosity", "load", "load_angle",
                    "max_eccentricity", "solution", "grid_circumferential", "grid_axial"});
            JournalBearing j;
            j.diameter = len(e, "diameter", std::nullopt, true);
            j.length = len(e, "length", std::nullopt, true);
            j.clearance = len(e, "clearance", std::nullopt, true);
            j.viscosity = e.number("viscosity", std::nullopt, 0.0, true, "Pa s");
            // load = "auto": the bearing's share of the rotor's weight (set once the rotor is built).
            const toml::node* load = e.table().get("load");
            const bool auto_load = load && load->is_string();
            if (auto_load && *load->value<std::string>() != "auto")
                throw InputError(e.where("load") + " = '" + *load->value<std::string>() +
                                 "'; allowed: a number > 0 (N) or \"auto\" (from the rotor's weight)");
            j.load = auto_load ? 1.0 : e.number("load", std::nullopt, 0.0, true, "N");
            if (e.has("load_angle")) {
                const double deg = e.any_number("load_angle", "deg");
                if (!(std::fabs(deg) <= 360.0))
                    throw InputError(fmt::format("{} = {}; allowed: -360 to 360 (deg)", e.where("load_angle"), deg));
                j.load_angle = deg * std::acos(-1.0) / 180.0;
            }
            j.max_eccentricity = e.number("max_eccentricity", 0.95, 0.0, true, "eccentricity ratio, 0.01 to 0.999");
            // The film's solution: the short-bearing closed form or the finite-difference Reynolds
            // solution on a grid (intervals around the circumference and over the length).
            if (e.choice("solution", "short", {"short", "finite_difference"}) == "finite_difference") {
                j.solution = FilmSolution::finite_difference;
                j.grid_circumferential =
                    static_cast<int>(e.integer("grid_circumferential", j.grid_circumferential, 16, 2880));
                j.grid_axial = static_cast<int>(e.integer("grid_axial", j.grid_axial, 4, 256));
            } else {
                for (const char* key : {"grid_circumferential", "grid_axial"})
                    if (e.has(key))
                        throw InputError(e.where(key) + " is given with solution = \"short\"; allowed: grid keys only "
                                                        "with solution = \"finite_difference\"");
            }
            std::string origin = e.where("");   // "file: [table] "
            origin.pop_back();
            if (!auto_load) j.validate(origin, len.scale, len.name);   // lengths in the scene's unit
            tables.push_back({node_at(e, z, len), "", j, std::nullopt, e.where("type"), auto_load, origin});
            return;
        }
        e.only({"type", "z", "k", "c", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy", "kzz", "czz",
                "table", "speeds", "speed_unit"});
        const int node = node_at(e, z, len);
        if (e.has("speeds")) {
            for (const char* key : {"table", "kzz", "czz"})
                if (e.has(key))
                    throw InputError(e.where(key) + " is given together with speeds; allowed: a table in the scene "
                                                    "(speeds with k, c or kxx ... cyy arrays) without " + key);
            tables.push_back({node, "", std::nullopt, inline_bearing_table(e), e.where("speeds")});
            return;
        }
        if (e.has("speed_unit"))
            throw InputError(e.where("speed_unit") + " needs speeds; allowed: with a table in the scene (speeds = [...])");
        if (lateral_only)
            for (const char* key : {"kzz", "czz"})
                if (e.has(key))
                    throw InputError(e.where(key) + " acts on the axial DOF z; " + needs_axial_dofs);
        if (e.has("table")) {
            for (const char* key : {"k", "c", "kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"})
                if (e.has(key))
                    throw InputError(e.where(key) + " is given together with table; allowed: either a table or "
                                                    "constant coefficients");
            tables.push_back({node, (std::filesystem::path(dir) / e.choice("table", "", {})).string(), std::nullopt,
                              std::nullopt, e.where("table")});
            return;
        }
        FeBearing b;
        b.node = node;
        const double kk = e.number("k", 0.0, 0, false, "N/m"), cc = e.number("c", 0.0, 0, false, "N s/m");
        b.kxx = e.has("kxx") ? e.any_number("kxx", "N/m") : kk;
        b.kyy = e.has("kyy") ? e.any_number("kyy", "N/m") : kk;
        b.kxy = e.has("kxy") ? e.any_number("kxy", "N/m") : 0.0;
        b.kyx = e.has("kyx") ? e.any_number("kyx", "N/m") : 0.0;
        b.cxx = e.has("cxx") ? e.any_number("cxx", "N s/m") : cc;
        b.cyy = e.has("cyy") ? e.any_number("cyy", "N s/m") : cc;
        b.cxy = e.has("cxy") ? e.any_number("cxy", "N s/m") : 0.0;
        b.cyx = e.has("cyx") ? e.any_number("cyx", "N s/m") : 0.0;
        b.kzz = e.number("kzz", 0.0, 0, false, "N/m");
        b.czz = e.number("czz", 0.0, 0, false, "N s/m");
        r.bearings.push_back(b);
    });

    for_each_entry(k, "support", false, [&](const TomlKeys& e) {
        e.only({"z", "type", "axial", "torsion"});
        FeSupport s;
        s.node = node_at(e, z, len);
        const std::string type = e.choice("type", "pinned", {"pinned", "clamped"});
        s.theta_x = s.theta_y = type == "clamped";
        // Axial and torsional holds: a clamped end holds them too; a pinned one where it says so.
        const auto hold = [&](const char* key) {
            const toml::node* n = e.table().get(key);
            if (!n) return !lateral_only && type == "clamped";
            if (!n->is_boolean()) throw InputError(e.where(key) + " must be true or false");
            if (lateral_only && *n->value<bool>())
                throw InputError(e.where(key) + " = true holds a DOF the model does not have; " + needs_axial_dofs);
            return *n->value<bool>();
        };
        s.z = hold("axial");
        s.theta_z = hold("torsion");
        r.supports.push_back(s);
    });

    // Pedestals: a mass on springs to the ground under the bearings of its node.
    for_each_entry(k, "pedestal", false, [&](const TomlKeys& e) {
        e.only({"z", "mass", "k", "c", "kxx", "kyy", "cxx", "cyy"});
        FePedestal p;
        p.node = node_at(e, z, len);
        p.mass = e.number("mass", std::nullopt, 0, true, "kg");
        const double kk = e.number("k", 0.0, 0, false, "N/m"), cc = e.number("c", 0.0, 0, false, "N s/m");
        p.kxx = e.number("kxx", kk, 0, false, "N/m");
        p.kyy = e.number("kyy", kk, 0, false, "N/m");
        p.cxx = e.number("cxx", cc, 0, false, "N s/m");
        p.cyy = e.number("cyy", cc, 0, false, "N s/m");
        const bool carries = std::any_of(r.bearings.begin(), r.bearings.end(),
                                         [&](const FeBearing& b) { return b.node == p.node; }) ||
                             std::any_of(tables.begin(), tables.end(), [&](const Tabulated& t) { return t.node == p.node; });
        if (!carries)
            throw InputError(fmt::format("{} is at node {}, where no bearing stands; allowed: the z of a bearing "
                                         "(a pedestal carries the bearings at its node)",
                                         e.where("z"), p.node));
        for (const FePedestal& q : r.pedestals)
            if (q.node == p.node)
                throw InputError(fmt::format("{}: a second pedestal at node {}; allowed: one pedestal per bearing "
                                             "position",
                                             e.where("z"), p.node));
        r.pedestals.push_back(p);
    });

    const FeRotorMatrices m = r.assemble();
    GyroscopicSystem sys = m.to_system();
    // Speed-dependent bearings act on x and y alone: an axial or torsional model has no use for them.
    if (!r.has_lateral()) tables.clear();
    // Fluid films with load = "auto": the weight's reactions with every speed-dependent
    // bearing as a rigid support (constant bearings as their springs); films at one node
    // share their node's reaction equally.
    if (std::any_of(tables.begin(), tables.end(), [](const Tabulated& t) { return t.auto_load; })) {
        std::vector<int> held, auto_nodes;
        for (const Tabulated& t : tables) {
            held.push_back(t.node);
            if (t.auto_load) auto_nodes.push_back(t.node);
        }
        const std::vector<double> reactions = fe_gravity_reactions(r, held);
        for (std::size_t i = 0; i < tables.size(); ++i) {
            Tabulated& t = tables[i];
            if (!t.auto_load) continue;
            const double share =
                reactions[i] / static_cast<double>(std::count(auto_nodes.begin(), auto_nodes.end(), t.node));
            if (!(share > 0.0))
                throw InputError(fmt::format("{} load = \"auto\": the rotor's weight lifts the journal off this "
                                             "bearing (reaction {:.6g} N at node {}); allowed: a bearing that carries "
                                             "weight, or load = a number (N) with load_angle",
                                             t.origin, share, t.node));
            t.journal->load = share;
            t.journal->validate(t.origin, len.scale, len.name);
        }
    }
    for (const Tabulated& t : tables) {
        const bool on_pedestal =
            std::any_of(r.pedestals.begin(), r.pedestals.end(), [&](const FePedestal& p) { return p.node == t.node; });
        const auto has = [&](const std::string& name) {
            return std::find(m.dof_names.begin(), m.dof_names.end(), name) != m.dof_names.end();
        };
        // A shaft held at a pedestal: the bearing acts between the pedestal and the held
        // shaft, i.e. from the pedestal to the ground (as a constant bearing does there).
        const bool pedestal_only = on_pedestal && !has("x" + std::to_string(t.node)) &&
                                   !has("y" + std::to_string(t.node));
        const auto dof = [&](std::string prefix) {
            if (pedestal_only && (prefix == "x" || prefix == "y")) prefix = "p" + prefix;
            const std::string name = prefix + std::to_string(t.node);
            const auto it = std::find(m.dof_names.begin(), m.dof_names.end(), name);
            if (it == m.dof_names.end())
                throw InputError(fmt::format("{}: the bearing at node {} acts on DOF {}, which a support holds; "
                                             "allowed: a bearing at a node whose x and y are free",
                                             t.where, t.node, name));
            return static_cast<int>(it - m.dof_names.begin());
        };
        // Named by kind and node; a second one at the same node gets a suffix (damping
        // components need unique names).
        const auto unique_name = [&](const std::string& kind) {
            std::string name = kind + "_" + std::to_string(t.node);
            for (int k = 2; std::any_of(sys.bearings.begin(), sys.bearings.end(),
                                        [&](const BearingTable& b) { return b.name == name; });
                 ++k)
                name = kind + "_" + std::to_string(t.node) + "_" + std::to_string(k);
            return name;
        };
        if (t.journal) {
            const std::string name = unique_name("fluid_film");
            const int dx = dof("x"), dy = dof("y");
            sys.bearings.push_back(journal_bearing_table(*t.journal, name, dx, dy));
        }
        else if (t.written) {
            BearingTable b = *t.written;
            b.dof_x = dof("x");
            b.dof_y = dof("y");
            b.validate(sys.size());   // errors name the scene's table
            b.name = unique_name("table");
            sys.bearings.push_back(b);
        } else
            sys.bearings.push_back(read_bearing_csv(t.path, sys.size(), dof("x"), dof("y")));
        // On a pedestal: the bearing acts between the shaft and the pedestal.
        if (on_pedestal && !pedestal_only) {
            sys.bearings.back().pedestal_x = dof("px");
            sys.bearings.back().pedestal_y = dof("py");
        }
    }
    if (rotor) *rotor = r;
    return sys;
}

}  // namespace gyrokit
