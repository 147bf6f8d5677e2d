#include <gyrokit/scene/scene.hpp>

#include <gyrokit/core/input_file.hpp>
#include <gyrokit/core/run_files.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/bearing_csv.hpp>
#include "gyrokit/scene/detail/fe_scene.hpp"
#include "gyrokit/scene/detail/api_scene.hpp"
#include "gyrokit/scene/detail/fluid_scene.hpp"
#include <gyrokit/io/matrix_market.hpp>
#include "gyrokit/scene/toml_keys.hpp"
#include <gyrokit/models/gyrostat.hpp>

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <functional>
#include <map>
#include <set>
#include <type_traits>
#include <variant>
#include <sstream>
#include <toml++/toml.h>

namespace gyrokit {

namespace {

namespace fs = std::filesystem;

GyrostatParameters gyrostat_from(const TomlKeys& k) {
    k.only({"type", "A_G", "B_G", "A_R", "C_R", "m", "s", "eps", "c_G", "c_T", "c_R", "d_G", "d_T", "d_R", "shaft",
            "housing"});
    GyrostatParameters p;
    p.rigid_shaft = k.choice("shaft", "elastic", {"elastic", "rigid"}) == "rigid";
    p.rigid_housing = k.choice("housing", "elastic", {"elastic", "rigid"}) == "rigid";
    if (p.rigid_shaft && p.rigid_housing)
        throw InputError(k.where("shaft") + " = 'rigid' with housing = 'rigid' leaves no degree of freedom; "
                                            "allowed: at most one of them rigid");
    const std::optional<double> unused = 0.0;   // keys a rigid element makes irrelevant
    p.A_G = k.number("A_G", p.rigid_housing ? unused : std::nullopt, 0, true, "kg m^2");
    p.B_G = k.number("B_G", p.rigid_housing ? unused : std::nullopt, 0, true, "kg m^2");
    p.c_G = k.number("c_G", p.rigid_housing ? unused : std::nullopt, 0, true, "N m/rad");
    p.A_R = k.number("A_R", std::nullopt, 0, true, "kg m^2");
    p.C_R = k.number("C_R", std::nullopt, 0, true, "kg m^2");
    p.m = k.number("m", std::nullopt, 0, true, "kg");
    p.s = k.any_number("s", "m");
    p.eps = k.number("eps", 0.0, 0, false, "m");
    p.c_T = k.number("c_T", p.rigid_shaft ? unused : std::nullopt, 0, true, "N/m");
    p.c_R = k.number("c_R", p.rigid_shaft ? unused : std::nullopt, 0, true, "N m/rad");
    p.d_G = k.number("d_G", 0.0, 0, false, "N m s/rad");
    p.d_T = k.number("d_T", 0.0, 0, false, "N s/m");
    p.d_R = k.number("d_R", 0.0, 0, false, "N m s/rad");
    return p;
}

// A matrix model, read in sparse form.
GyroscopicSystem matrices_from(const TomlKeys& k, const fs::path& dir) {
    k.only({"type", "M", "K", "D", "G", "N", "unbalance", "dof_names", "whirl_pairs", "bearings"});
    const auto path_of = [&](const std::string& key) -> std::optional<std::string> {
        if (!k.has(key)) return std::nullopt;
        const std::string rel = k.choice(key, "", {});
        return (dir / rel).string();
    };
    GyroscopicSystem sys;
    const auto m = path_of("M"), kk = path_of("K");
    if (!m) throw InputError(k.where("M") + " is missing; required: path of a Matrix Market file");
    if (!kk) throw InputError(k.where("K") + " is missing; required: path of a Matrix Market file");
    sys.M = read_matrix_market_sparse(*m);
    sys.K = read_matrix_market_sparse(*kk);
    if (auto d = path_of("D")) sys.damping.push_back({"D", read_matrix_market_sparse(*d)});
    if (auto g = path_of("G")) sys.G = read_matrix_market_sparse(*g);
    if (auto n = path_of("N")) sys.N = read_matrix_market_sparse(*n);
    if (auto u = path_of("unbalance")) sys.unbalance = read_matrix_market_vector(*u);
    const int n = static_cast<int>(sys.M.rows());
    if (const toml::array* names = k.table().get_as<toml::array>("dof_names")) {
        for (const auto& e : *names) {
            auto s = e.value<std::string>();
            if (!s) throw InputError(k.where("dof_names") + ": every entry must be a string");
            sys.dofs.names.push_back(*s);
        }
        if (static_cast<int>(sys.dofs.names.size()) != n)
            throw InputError(fmt::format("{} has {} names for {} DOFs; allowed: exactly one name per DOF",
                                         k.where("dof_names"), sys.dofs.names.size(), n));
    } else {
        if (k.has("dof_names")) throw InputError(k.where("dof_names") + " must be an array of strings");
        for (int i = 0; i < n; ++i) sys.dofs.names.push_back("q" + std::to_string(i));
    }
    if (const toml::array* pairs = k.table().get_as<toml::array>("whirl_pairs")) {
        for (const auto& e : *pairs) {
            const toml::array* pr = e.as_array();
            if (!pr || pr->size() != 2 || !(*pr)[0].is_integer() || !(*pr)[1].is_integer())
                throw InputError(k.where("whirl_pairs") + ": each entry must be a pair [u, v] of 0-based DOF indices");
            const long long u = *(*pr)[0].value<long long>(), v = *(*pr)[1].value<long long>();
            if (u < 0 || v < 0 || u >= n || v >= n || u == v)
                throw InputError(fmt::format("{}: pair [{}, {}] out of range; allowed: two distinct indices in [0, {}]",
                                             k.where("whirl_pairs"), u, v, n - 1));
            sys.whirl_pairs.emplace_back(static_cast<int>(u), static_cast<int>(v));
        }
    } else {
        if (k.has("whirl_pairs")) throw InputError(k.where("whirl_pairs") + " must be an array of pairs");
        // Lateral DOFs usually come as (x, y) pairs.
        if (n % 2 == 0)
            for (int i = 0; i < n; i += 2) sys.whirl_pairs.emplace_back(i, i + 1);
    }
    if (k.has("bearings")) {
        const toml::array* files = k.table().get_as<toml::array>("bearings");
        if (!files) throw InputError(k.where("bearings") + " must be an array of CSV file paths");
        for (const auto& e : *files) {
            auto f = e.value<std::string>();
            if (!f) throw InputError(k.where("bearings") + ": every entry must be a string (a CSV file path)");
            sys.bearings.push_back(read_bearing_csv((dir / *f).string(), n));
        }
    }
    return sys;
}

// The model readers: [model] type -> reader. A new model type plugs in here
// with one line (and its keys in docs/scene_format.md).
using ModelReader = std::function<void(const TomlKeys&, const fs::path& dir, Scene&)>;
const std::map<std::string, ModelReader>& model_readers() {
    static const std::map<std::string, ModelReader> readers = {
        {"fe_rotor",
         [](const TomlKeys& k, const fs::path& dir, Scene& sc) {
             RotorModel model = rotor_model_from(k, dir.string());
             BuiltRotor built = build(model);
             sc.system = std::move(built.system);
             sc.model = FeRotorScene{std::move(model), std::move(built.rotor)};
         }},
        {"fluid_rotor",
         [](const TomlKeys& k, const fs::path&, Scene& sc) {
             FluidRotorParameters p = fluid_rotor_from(k);
             sc.system = make_system(build_fluid_rotor(p));
             sc.model = FluidRotorScene{std::move(p), {}};
         }},
        {"gyrostat",
         [](const TomlKeys& k, const fs::path&, Scene& sc) {
             GyrostatParameters p = gyrostat_from(k);
             sc.system = make_system(p);
             sc.model = GyrostatScene{p, {}};
         }},
        {"matrices",
         [](const TomlKeys& k, const fs::path& dir, Scene& sc) {
             sc.system = matrices_from(k, dir);
             sc.model = MatricesScene{};
         }},
    };
    return readers;
}

std::set<std::string> model_types() {
    std::set<std::string> t;
    for (const auto& [name, reader] : model_readers()) t.insert(name);
    return t;
}

toml::table parse_scene_file(const std::string& path) { return parse_toml(read_toml_text(path, "scene file"), path); }

// One step of a parameter path: a key, and for an array of tables [[...]] the
// entry ([i], from 0) or every entry ([*]).
struct PathStep {
    std::string key;
    bool indexed = false, every = false;
    std::size_t index = 0;
};

std::vector<PathStep> parse_path(const std::string& file, const std::string& name) {
    const auto bad = [&](const std::string& why) {
        return InputError(fmt::format("{}: parameter '{}': {}; allowed: TABLE.KEY, or through arrays of tables "
                                      "TABLE.ARRAY[i].KEY (i from 0) or TABLE.ARRAY[*].KEY (every entry), e.g. "
                                      "model.c_G, model.bearing[0].kxx, model.shaft[*].outer_diameter",
                                      file, name, why));
    };
    std::vector<PathStep> steps;
    std::size_t at = 0;
    while (at <= name.size()) {
        const std::size_t dot = std::min(name.find('.', at), name.size());
        std::string part = name.substr(at, dot - at);
        PathStep s;
        const std::size_t open = part.find('[');
        if (open != std::string::npos) {
            if (part.back() != ']') throw bad("'" + part + "' does not end its index with ]");
            const std::string index = part.substr(open + 1, part.size() - open - 2);
            s.indexed = true;
            if (index == "*") {
                s.every = true;
            } else if (!index.empty() && index.size() <= 9 && index.find_first_not_of("0123456789") == std::string::npos) {
                s.index = std::stoul(index);
            } else {
                throw bad("'[" + index + "]' is not an index");
            }
            part = part.substr(0, open);
        }
        if (part.empty()) throw bad("an empty key");
        s.key = part;
        steps.push_back(s);
        at = dot + 1;
    }
    if (steps.size() < 2) throw bad("no key below a table");
    if (steps.back().indexed) throw bad("the last step indexes an array; a parameter is a number");
    return steps;
}

// Names the keys of `t` one can go on through (tables and arrays of tables).
std::string inner_keys(const toml::table& t) {
    std::string list;
    for (const auto& [k, v] : t) {
        const toml::array* a = v.as_array();
        if (v.is_table()) list += (list.empty() ? "" : ", ") + std::string(k.str());
        if (a && a->is_array_of_tables() && !a->empty())
            list += fmt::format("{}{}[0..{}]", list.empty() ? "" : ", ", k.str(), a->size() - 1);
    }
    return list.empty() ? std::string("none") : list;
}

void assign_path(toml::table& t, const std::vector<PathStep>& steps, std::size_t i, double value,
                 const std::string& where, const std::string& file, const std::string& name) {
    const PathStep& s = steps[i];
    const std::string here = where.empty() ? s.key : where + "." + s.key;
    if (i + 1 == steps.size()) {
        const toml::node* old = t.get(s.key);
        if (old && !old->is_number())
            throw InputError(fmt::format("{}: parameter '{}': {} is not a number in the scene; allowed: a numeric key",
                                         file, name, here));
        t.insert_or_assign(s.key, value);
        return;
    }
    toml::node* n = t.get(s.key);
    toml::array* a = n ? n->as_array() : nullptr;
    if (!n || (s.indexed && !(a && a->is_array_of_tables())) || (!s.indexed && !n->is_table()))
        throw InputError(fmt::format("{}: parameter '{}': {} is not {}; allowed below {}: {}", file, name,
                                     here + (s.indexed ? "[...]" : ""),
                                     s.indexed ? "an array of tables of the scene" : "a table of the scene",
                                     where.empty() ? std::string("the top") : where,
                                     inner_keys(t)));
    if (!s.indexed) return assign_path(*n->as_table(), steps, i + 1, value, here, file, name);
    if (a->empty())
        throw InputError(fmt::format("{}: parameter '{}': {} has no entries", file, name, here));
    if (!s.every && s.index >= a->size())
        throw InputError(fmt::format("{}: parameter '{}': {} has {} entries; allowed: {}[0] to {}[{}], or {}[*]", file,
                                     name, here, a->size(), here, here, a->size() - 1, here));
    for (std::size_t k = 0; k < a->size(); ++k)
        if (s.every || k == s.index)
            assign_path(*a->get(k)->as_table(), steps, i + 1, value, fmt::format("{}[{}]", here, k), file, name);
}

void apply_overrides(toml::table& root, const std::string& path, const std::map<std::string, double>& overrides) {
    for (const auto& [name, value] : overrides) assign_path(root, parse_path(path, name), 0, value, "", path, name);
}

}  // namespace

namespace {

// The document with the file names of its [model] (a matrices model's M, K, D, G, N,
// unbalance and bearing tables; the other models name no files) made absolute: the
// same scene wherever its text is written. Only these keys: any other string (a type,
// a DOF name) stays as written even where a file of that name happens to exist.
std::string portable_document(toml::table root, const fs::path& dir) {
    const auto absolute = [&](toml::node* n) {
        if (auto* s = n ? n->as_string() : nullptr; s && !s->get().empty() && fs::path(s->get()).is_relative())
            *s = (fs::absolute(dir) / s->get()).lexically_normal().string();
    };
    toml::table* model = root.get_as<toml::table>("model");
    const auto* type = model ? model->get_as<std::string>("type") : nullptr;
    if (type && type->get() == "matrices") {
        for (const char* key : {"M", "K", "D", "G", "N", "unbalance"}) absolute(model->get(key));
        if (toml::array* tables = model->get_as<toml::array>("bearings"))
            for (auto& t : *tables) absolute(&t);
    }
    std::ostringstream out;
    out << root << "\n";
    return out.str();
}

// A parsed scene document: `path` names it in messages, `dir` resolves its relative files.
Scene scene_from(toml::table root, const std::string& path, const fs::path& dir,
                 const std::map<std::string, double>& overrides, const std::string& fe_motion = "") {
    Scene sc;
    sc.path = path;
    apply_overrides(root, path, overrides);
    if (!fe_motion.empty()) {
        // The DOF set of an FE rotor in place of the scene's motion and dofs_per_node.
        if (fe_motion != "lateral" && fe_motion != "all" && fe_motion != "axial" && fe_motion != "torsional")
            throw InputError(option_field("motion") + " '" + fe_motion + "': allowed: lateral, all, axial, torsional");
        toml::table* model = root.get_as<toml::table>("model");
        const auto* given = model ? model->get_as<std::string>("type") : nullptr;
        const std::string type = given ? given->get() : "(none)";
        if (type != "fe_rotor")
            throw InputError(fmt::format("{} '{}' does not apply to {}, a [model] of type {}; allowed: a "
                                         "[model] of type fe_rotor",
                                         option_field("motion"), fe_motion, path, type));
        model->erase("dofs_per_node");
        model->insert_or_assign("motion", fe_motion);
    }
    TomlKeys top(path, "top level", root);
    top.only({"title", "model", "speeds", "analysis", "api"});
    sc.title = top.choice("title", "", {});
    const toml::table* model = root.get_as<toml::table>("model");
    const std::string types = fmt::format("{}", fmt::join(model_types(), ", "));
    if (!model) throw InputError(path + ": table [model] is missing; required: [model] with type = one of " + types);
    TomlKeys mk(path, "model", *model);
    const std::string type = mk.choice("type", "", model_types());
    if (type.empty()) throw InputError(mk.where("type") + " is missing; allowed: " + types);
    model_readers().at(type)(mk, dir, sc);
    sc.system.validate(path);
    // The models written back as read keep their document.
    std::visit(
        [&](auto& m) {
            if constexpr (!std::is_same_v<std::decay_t<decltype(m)>, FeRotorScene>) m.document = portable_document(root, dir);
        },
        sc.model);

    if (const toml::table* sp = root.get_as<toml::table>("speeds")) {
        TomlKeys k(path, "speeds", *sp);
        k.only({"from", "to", "count", "units"});
        // from and to in `units` (rad/s, Hz or rpm, any case); rad/s inside.
        SpeedUnit unit;
        const std::string unit_name = k.choice("units", "rad/s", {});
        try {
            unit = SpeedUnit::parse(unit_name);
        } catch (const InputError&) {
            throw InputError(k.where("units") + " = '" + unit_name + "': allowed: rad/s, Hz, rpm");
        }
        SpeedRange r;
        r.from = k.number("from", std::nullopt, 0, false, unit.name.c_str());
        r.to = k.number("to", std::nullopt, 0, false, unit.name.c_str());
        r.count = static_cast<int>(k.integer("count", 201, 1, 10000000));
        r.validate(path + ": [speeds]");   // in the scene's unit, as the user wrote them
        sc.speeds = r;
        sc.speed_unit = unit;
    } else if (root.contains("speeds")) {
        throw InputError(path + ": speeds must be a table [speeds] with from, to, count");
    }
    if (const toml::table* an = root.get_as<toml::table>("analysis")) {
        TomlKeys k(path, "analysis", *an);
        k.only({"modes", "harmonics", "solver", "target", "target_order", "f_cut"});
        if (k.has("modes")) sc.solver.modes = static_cast<int>(k.integer("modes", 0, 0, 100000));
        sc.solver.kind = parse_solver_kind(k.choice("solver", "auto", {"auto", "dense", "sparse"}));
        if (k.has("target")) sc.solver.target = k.number("target", std::nullopt, 0, false, "rad/s");
        sc.solver.target_order = k.number("target_order", 0.0, 0, false, "multiple of the speed");
        if (k.has("f_cut")) sc.analysis.f_cut = k.number("f_cut", std::nullopt, 0, true, "rad/s");
        if (const toml::array* h = an->get_as<toml::array>("harmonics")) {
            sc.analysis.harmonics.clear();
            for (const auto& e : *h) {
                if (!e.is_integer() || *e.value<long long>() < 1 || *e.value<long long>() > 1000)
                    throw InputError(k.where("harmonics") + ": each entry must be a whole number in [1, 1000]");
                sc.analysis.harmonics.push_back(static_cast<int>(*e.value<long long>()));
            }
            if (sc.analysis.harmonics.empty()) throw InputError(k.where("harmonics") + " is empty; allowed: e.g. [1] or [1, 2]");
        } else if (an->contains("harmonics")) {
            throw InputError(k.where("harmonics") + " must be an array such as [1, 2]");
        }
    }
    if (const toml::table* api = root.get_as<toml::table>("api")) {
        sc.api = api_machine_from(TomlKeys(path, "api", *api), *api, sc);
    } else if (root.contains("api")) {
        throw InputError(path + ": api must be a table [api] with mcs and qa or [[api.stage]] entries");
    }
    return sc;
}

}  // namespace

Scene load_scene(const std::string& path, const std::map<std::string, double>& overrides,
                 const std::string& fe_motion) {
    InputCollector read;
    // A bare file name lives in the working folder: its relative file names resolve from ".".
    const fs::path dir = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
    Scene sc = scene_from(parse_scene_file(path), path, dir, overrides, fe_motion);
    sc.inputs = read.paths();
    return sc;
}

Scene parse_scene(const std::string& text, const std::string& origin, const std::string& dir,
                  const std::map<std::string, double>& overrides) {
    check_toml_depth(text, origin);
    toml::table root = parse_toml(text, origin);
    InputCollector read;
    Scene sc = scene_from(std::move(root), origin, dir.empty() ? "." : dir, overrides);
    sc.inputs = read.paths();
    return sc;
}

void validate_settings(const Scene& sc) {
    if (sc.speeds) sc.speeds->validate(sc.path + ": speeds");
    if (sc.solver.modes != kModesInRange && !(sc.solver.modes >= 0 && sc.solver.modes <= 100000))
        throw InputError(fmt::format("{}: modes = {}; allowed: 0 (all) to 100000, or unset (those in range)", sc.path,
                                     sc.solver.modes));
    if (sc.analysis.harmonics.empty()) throw InputError(sc.path + ": harmonics is empty; allowed: e.g. [1] or [1, 2]");
    for (const int h : sc.analysis.harmonics)
        if (h < 1 || h > 1000)
            throw InputError(fmt::format("{}: harmonics entry {}; allowed: whole numbers in [1, 1000]", sc.path, h));
    if (sc.solver.target && !(std::isfinite(*sc.solver.target) && *sc.solver.target >= 0))
        throw InputError(fmt::format("{}: target = {}; allowed: a finite number >= 0 (rad/s)", sc.path, *sc.solver.target));
    if (!(std::isfinite(sc.solver.target_order) && sc.solver.target_order >= 0))
        throw InputError(fmt::format("{}: target_order = {}; allowed: a finite number >= 0 (multiple of the speed)",
                                     sc.path, sc.solver.target_order));
    if (sc.analysis.f_cut && !(std::isfinite(*sc.analysis.f_cut) && *sc.analysis.f_cut > 0))
        throw InputError(fmt::format("{}: f_cut = {}; allowed: a finite frequency > 0 (rad/s)", sc.path, *sc.analysis.f_cut));
}

std::string Scene::model_type() const {
    static const char* const names[] = {"matrices", "gyrostat", "fluid_rotor", "fe_rotor"};
    static_assert(std::variant_size_v<SceneModel> == 4, "a name for each model type");
    return names[model.index()];
}

const RotorModel* Scene::rotor_model() const {
    const auto* fe = std::get_if<FeRotorScene>(&model);
    return fe ? &fe->model : nullptr;
}

const FeRotor* Scene::fe_rotor() const {
    const auto* fe = std::get_if<FeRotorScene>(&model);
    return fe ? &fe->mesh : nullptr;
}

const FluidRotorParameters* Scene::fluid() const {
    const auto* f = std::get_if<FluidRotorScene>(&model);
    return f ? &f->parameters : nullptr;
}

const GyrostatParameters* Scene::gyrostat() const {
    const auto* g = std::get_if<GyrostatScene>(&model);
    return g ? &g->parameters : nullptr;
}

std::vector<double> Scene::speed_points() const {
    std::vector<double> w = speeds ? speeds->points() : std::vector<double>{};
    for (double& x : w) x /= speed_unit.factor;
    return w;
}

}  // namespace gyrokit
