// Sweep files: the TOML of a design study read into a Sweep (read_sweep), each table
// by its own reader; the Sweep is then completed and checked by finalize_sweep.
#include <gyrokit/screening/sweep.hpp>

#include <gyrokit/screening/detail/probes.hpp>

#include <gyrokit/analysis/pervasive_damping.hpp>
#include <gyrokit/core/error.hpp>
#include "gyrokit/scene/toml_keys.hpp"
#include <gyrokit/core/input_file.hpp>

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <limits>
#include <toml++/toml.h>

namespace gyrokit {

namespace {

namespace fs = std::filesystem;

std::vector<double> numbers_of(const TomlKeys& k, const std::string& key) {
    const toml::array* a = k.table().get_as<toml::array>(key);
    if (!a) throw InputError(k.where(key) + " must be an array of numbers");
    std::vector<double> v;
    for (const auto& e : *a) {
        const std::optional<double> x = e.value<double>();
        if (!x || !(e.is_floating_point() || e.is_integer()) || !std::isfinite(*x))
            throw InputError(k.where(key) + ": every entry must be a finite number");
        v.push_back(*x);
    }
    return v;
}

std::vector<std::string> strings_of(const TomlKeys& k, const std::string& key) {
    const toml::array* a = k.table().get_as<toml::array>(key);
    if (!a) throw InputError(k.where(key) + " must be an array of strings");
    std::vector<std::string> v;
    for (const auto& e : *a) {
        const std::optional<std::string> x = e.value<std::string>();
        if (!x) throw InputError(k.where(key) + ": every entry must be a string");
        v.push_back(*x);
    }
    return v;
}

const toml::table& sub_table(const toml::table& root, const std::string& file, const std::string& key) {
    const toml::table* t = root.get_as<toml::table>(key);
    if (!t) throw InputError(fmt::format("{}: {} must be a table [{}]", file, key, key));
    return *t;
}

SweepParameter read_parameter(const std::string& file, const toml::table& t, std::size_t i, Sampling sampling) {
    TomlKeys k(file, fmt::format("parameter {}", i + 1), t);
    k.only({"name", "paths", "from", "to", "count", "values", "scale"});
    SweepParameter p;
    p.name = k.choice("name", "", {});
    if (p.name.empty()) throw InputError(k.where("name") + " is missing; required: a scene key such as \"model.c_G\"");
    if (k.has("paths")) {
        p.paths = strings_of(k, "paths");
        if (p.paths.empty()) throw InputError(k.where("paths") + " is empty; allowed: one or more scene paths");
    }
    // Each path goes below [model]; what it names is checked against the scene (check_parameter).
    for (const std::string& path : p.paths.empty() ? std::vector<std::string>{p.name} : p.paths)
        if (path.rfind("model.", 0) != 0 || path.size() <= 6)
            throw InputError(fmt::format("{} = '{}': allowed: a path to a numeric value of the scene's [model], e.g. "
                                         "model.c_G, model.bearing[0].kxx, model.shaft[*].outer_diameter",
                                         k.where(p.paths.empty() ? "name" : "paths"), path));
    p.log_scale = k.choice("scale", "linear", {"linear", "log"}) == "log";
    if (k.has("values")) {
        if (sampling == Sampling::LatinHypercube)
            throw InputError(k.where("values") + ": Latin hypercube sampling needs from and to, not values");
        if (k.has("from") || k.has("to") || k.has("count"))
            throw InputError(k.where("values") + ": give either values or from/to/count, not both");
        p.values = numbers_of(k, "values");
        if (p.values.empty()) throw InputError(k.where("values") + " is empty; allowed: at least one number");
        return p;
    }
    p.from = k.any_number("from", "scene units");
    p.to = k.any_number("to", "scene units");
    const bool single = sampling == Sampling::Grid && k.has("count") && k.integer("count", 0, 1, 1000000) == 1;
    if (!(p.to > p.from) && !(p.to == p.from && single))
        throw InputError(fmt::format("{}: empty range from = {} to = {}; allowed: to > from", k.where("to"), p.from,
                                     p.to));
    if (p.log_scale && !(p.from > 0))
        throw InputError(fmt::format("{} = {}: scale = \"log\" needs from > 0", k.where("from"), p.from));
    if (sampling == Sampling::Grid) {
        if (!k.has("count")) throw InputError(k.where("count") + " is missing; required: a whole number >= 1 (grid points)");
        p.count = static_cast<int>(k.integer("count", 0, 1, 1000000));
    } else if (k.has("count")) {
        throw InputError(k.where("count") + ": not used with Latin hypercube sampling (set [sampling] samples)");
    }
    return p;
}

// title, the base scene (a file beside the sweep's, or the text given in code) and the
// speed unit of the top level.
void read_scene_keys(const TomlKeys& top, const std::string& path, const std::string& scene_text,
                     const std::string& scene_name, Sweep& s) {
    s.title = top.choice("title", "", {});
    const std::string scene = top.choice("scene", "", {});
    if (!scene_text.empty()) {
        // The base scene given in code: its text, parsed for each design with the design's overrides.
        s.scene = scene_name.empty() ? std::string("scene") : scene_name;
        s.scene_text = scene_text;
        s.loader = [text = s.scene_text, name = s.scene](const std::map<std::string, double>& o) {
            return parse_scene(text, name, ".", o);
        };
    } else if (scene.empty()) {
        throw InputError(top.where("scene") + " is missing; required: path of the base scene file");
    } else {
        s.scene = fs::path(scene).is_absolute() ? scene : (fs::path(path).parent_path() / scene).string();
    }
    s.unit = SpeedUnit::parse(top.choice("units", "rad/s", {"rad/s", "Hz", "rpm"}));
}

// [sampling]: a grid of the parameters' values, or a Latin hypercube of `samples` designs.
void read_sampling(const toml::table& root, const std::string& path, Sweep& s) {
    TomlKeys k(path, "sampling", sub_table(root, path, "sampling"));
    k.only({"method", "samples", "seed"});
    s.sampling = k.choice("method", "grid", {"grid", "lhs"}) == "lhs" ? Sampling::LatinHypercube : Sampling::Grid;
    if (s.sampling == Sampling::LatinHypercube) {
        if (!k.has("samples")) throw InputError(k.where("samples") + " is missing; required: a whole number >= 1");
        s.samples = k.integer("samples", 0, 1, 10000000);
        s.seed = static_cast<std::uint64_t>(k.integer("seed", 1, 0, std::numeric_limits<long long>::max()));
    } else if (k.has("samples") || k.has("seed")) {
        throw InputError(k.where(k.has("samples") ? "samples" : "seed") + ": only used with method = \"lhs\"");
    }
}

// [[parameter]]: the design parameters, each with its scene paths and values.
void read_parameters(const toml::table& root, const std::string& path, Sweep& s) {
    const toml::array* ps = root.get_as<toml::array>("parameter");
    if (!ps) throw InputError(path + ": parameter must be an array of tables [[parameter]]");
    for (std::size_t i = 0; i < ps->size(); ++i) {
        const toml::table* t = (*ps)[i].as_table();
        if (!t) throw InputError(path + ": parameter must be an array of tables [[parameter]]");
        s.parameters.push_back(read_parameter(path, *t, i, s.sampling));
    }
}

// [operating]: the operating speed range, in the sweep's unit.
void read_operating(const toml::table& root, const std::string& path, Sweep& s) {
    const double f = s.unit.factor;
    TomlKeys k(path, "operating", sub_table(root, path, "operating"));
    k.only({"from", "to", "count"});
    s.op_from = k.number("from", std::nullopt, 0, false, s.unit.name.c_str()) / f;
    s.op_to = k.number("to", std::nullopt, 0, false, s.unit.name.c_str()) / f;
    if (s.op_to < s.op_from)
        throw InputError(fmt::format("{}: empty range from = {} to = {}; allowed: to >= from", k.where("to"),
                                     s.op_from * f, s.op_to * f));
    s.op_count = static_cast<int>(k.integer("count", 41, 2, 100000));
}

// [criteria.separation]: the margin of critical speeds from the operating range.
SeparationCriterion read_separation(const TomlKeys& c) {
    c.only({"margin_percent", "rule", "whirl", "harmonics", "count", "max_amplification_factor", "heavily_damped"});
    SeparationCriterion sc;
    sc.api684 = c.choice("rule", "margin", {"margin", "api684"}) == "api684";
    if (sc.api684 && c.has("margin_percent"))
        throw InputError(c.where("margin_percent") + ": not used with rule = \"api684\" (the margin follows "
                         "each critical speed's amplification factor)");
    sc.margin_percent = sc.api684 ? 26.0 : c.number("margin_percent", 15.0, 0, false, "%");
    sc.forward_only = c.choice("whirl", "all", {"all", "forward"}) == "forward";
    sc.count_heavily_damped = c.choice("heavily_damped", "skip", {"skip", "count"}) == "count";
    if (sc.api684 && sc.count_heavily_damped)
        throw InputError(c.where("heavily_damped") + " = \"count\": not used with rule = \"api684\" (a heavily damped "
                         "crossing needs no margin there)");
    if (c.has("harmonics")) {
        for (double h : numbers_of(c, "harmonics")) {
            if (h != std::floor(h) || h < 1 || h > 1000)
                throw InputError(c.where("harmonics") + ": each entry must be a whole number in [1, 1000]");
            sc.harmonics.push_back(static_cast<int>(h));
        }
        if (sc.harmonics.empty()) throw InputError(c.where("harmonics") + " is empty; allowed: e.g. [1]");
    }
    sc.count = static_cast<int>(c.integer("count", 121, 3, 100000));
    if (c.has("max_amplification_factor"))
        sc.max_amplification = c.number("max_amplification_factor", std::nullopt, 1.0, true,
                                        "dimensionless; API 684 calls a peak below 2.5 critically damped");
    return sc;
}

// [criteria.stability]: the least log dec up to a speed ([operating] to by default).
StabilityCriterion read_stability(const TomlKeys& c, const Sweep& s) {
    c.only({"up_to", "count", "min_log_dec"});
    StabilityCriterion sc;
    if (c.has("min_log_dec"))
        sc.min_log_dec = c.number("min_log_dec", std::nullopt, 0, true, "dimensionless; API 684 Level I: 0.1");
    sc.up_to = c.number("up_to", s.op_to * s.unit.factor, 0, true, s.unit.name.c_str()) / s.unit.factor;
    if (!(sc.up_to > 0.0))   // the default, [operating] to, may be 0
        throw InputError(fmt::format("{}: [criteria.stability] up_to is missing and [operating] to = {} gives "
                                     "no speed range; required: up_to > 0 ({})",
                                     s.path, s.op_to * s.unit.factor, s.unit.name));
    sc.count = static_cast<int>(c.integer("count", 121, 3, 100000));
    return sc;
}

// [criteria.pervasive]: the damping components that must reach every mode.
PervasiveCriterion read_pervasive(const TomlKeys& c) {
    c.only({"damping", "tolerance"});
    PervasiveCriterion pc;
    if (c.has("damping")) pc.damping = strings_of(c, "damping");
    if (pc.damping.empty()) throw InputError(c.where("damping") + " is empty; allowed: e.g. [\"total\"]");
    pc.tolerance = c.number("tolerance", kPervasiveTolerance, 0, true, "1");
    if (pc.tolerance >= 1) throw InputError(c.where("tolerance") + ": allowed: 0 < tolerance < 1");
    return pc;
}

// [criteria.response]: the largest unbalance response at DOFs or probes.
ResponseCriterion read_response(const TomlKeys& c) {
    c.only({"max_amplitude", "dofs", "probes"});
    ResponseCriterion rc;
    rc.max_amplitude = c.number("max_amplitude", std::nullopt, 0, true, "DOF units");
    if (c.has("dofs") && c.has("probes"))
        throw InputError(c.where("probes") + ": given with dofs; allowed: either dofs or probes");
    if (c.has("dofs")) {
        rc.dofs = strings_of(c, "dofs");
        if (rc.dofs.empty()) throw InputError(c.where("dofs") + " is empty; allowed: DOF names, or omit it");
    }
    if (c.has("probes")) rc.probes = read_probes(c);
    return rc;
}

// [criteria]: which verdicts a design gets, each criterion in its own table.
void read_criteria(const toml::table& root, const std::string& path, Sweep& s) {
    const toml::table& ct = sub_table(root, path, "criteria");
    TomlKeys k(path, "criteria", ct);
    k.only({"separation", "stability", "pervasive", "response", "balancer"});
    if (ct.contains("balancer"))
        throw InputError(fmt::format("{}: [criteria.balancer] needs a balancer model: no balancer model in scene "
                                     "{}", path, s.scene));
    if (ct.contains("separation")) {
        TomlKeys c(path, "criteria.separation", sub_table(ct, path + ": criteria", "separation"));
        s.criteria.separation = read_separation(c);
    }
    if (ct.contains("stability")) {
        TomlKeys c(path, "criteria.stability", sub_table(ct, path + ": criteria", "stability"));
        s.criteria.stability = read_stability(c, s);
    }
    if (ct.contains("pervasive")) {
        TomlKeys c(path, "criteria.pervasive", sub_table(ct, path + ": criteria", "pervasive"));
        s.criteria.pervasive = read_pervasive(c);
    }
    if (ct.contains("response")) {
        TomlKeys c(path, "criteria.response", sub_table(ct, path + ": criteria", "response"));
        s.criteria.response = read_response(c);
    }
}

}  // namespace

Sweep read_sweep(const std::string& path, const std::string& scene_text, const std::string& scene_name) {
    Sweep s;
    s.path = path;
    toml::table root = parse_toml(read_toml_text(path, "sweep file"), path);
    TomlKeys top(path, "top level", root);
    top.only({"title", "scene", "units", "sampling", "parameter", "operating", "criteria", "plot"});
    read_scene_keys(top, path, scene_text, scene_name, s);
    if (root.contains("sampling")) read_sampling(root, path, s);
    if (root.contains("parameter")) read_parameters(root, path, s);
    if (!root.contains("operating"))
        throw InputError(path + ": table [operating] is missing; required: from, to (operating speed range)");
    read_operating(root, path, s);
    if (root.contains("criteria")) read_criteria(root, path, s);
    if (root.contains("plot")) {
        TomlKeys k(path, "plot", sub_table(root, path, "plot"));
        k.only({"axes"});
        s.plot_axes = strings_of(k, "axes");
    }
    finalize_sweep(s);
    return s;
}

}  // namespace gyrokit
