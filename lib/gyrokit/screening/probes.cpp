// [criteria.response] probes: reading, checks against the base scene, and the
// probe of each design.
#include <gyrokit/screening/detail/probes.hpp>

#include "gyrokit/scene/toml_keys.hpp"
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <climits>
#include <fmt/format.h>

namespace gyrokit {

namespace {

constexpr const char* kProbeExample = "{ name = \"NDE\", dof_x = \"x3\", dof_y = \"y3\", angle = 45.0 }";

ResponseProbe read_probe(const TomlKeys& k) {
    k.only({"name", "dof_x", "dof_y", "node", "angle"});
    ResponseProbe p;
    p.name = k.choice("name", "", {});
    if (p.name.empty()) throw InputError(k.where("name") + " is missing; required: the probe's name, e.g. \"NDE\"");
    if (std::any_of(p.name.begin(), p.name.end(), [](unsigned char ch) { return ch < 0x20 || ch == 0x7f; }))
        throw InputError(k.where("name") + ": a control character or line break; allowed: a name on one line");
    if (k.has("node")) {
        if (k.has("dof_x") || k.has("dof_y"))
            throw InputError(k.where(k.has("dof_x") ? "dof_x" : "dof_y") +
                             ": given with node; allowed: either node or dof_x and dof_y");
        p.node = static_cast<int>(k.integer("node", -1, 0, INT_MAX));
    } else {
        p.dof_x = k.choice("dof_x", "", {});
        p.dof_y = k.choice("dof_y", "", {});
        if (p.dof_x.empty() || p.dof_y.empty())
            throw InputError(k.where(p.dof_x.empty() ? "dof_x" : "dof_y") +
                             " is missing; required: the names of the x and y DOFs (dof_x, dof_y), or node = N of "
                             "an fe_rotor scene");
        if (p.dof_x == p.dof_y)
            throw InputError(fmt::format("{} = '{}' and dof_y = '{}': allowed: two different DOFs", k.where("dof_x"),
                                         p.dof_x, p.dof_y));
    }
    if (!k.has("angle"))
        throw InputError(k.where("angle") + " is missing; required: the probe's direction in degrees from +x towards "
                                            "+y, -360 to 360");
    p.angle_degrees = k.any_number("angle", "degrees from +x towards +y");
    if (p.angle_degrees < -360.0 || p.angle_degrees > 360.0)
        throw InputError(fmt::format("{} = {}: out of range; allowed: -360 to 360 (degrees from +x towards +y)",
                                     k.where("angle"), p.angle_degrees));
    return p;
}

// A scene's DOF names for a message: all of a few, else the first and the last.
std::string dof_list(const std::vector<std::string>& names) {
    if (names.size() <= 8) {
        std::string out;
        for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
        return out;
    }
    return fmt::format("{}, {}, ... {} ({} DOFs)", names[0], names[1], names.back(), names.size());
}

int dof_index(const GyroscopicSystem& sys, const std::string& name) { return sys.dofs.find(name); }

}  // namespace

std::vector<ResponseProbe> read_probes(const TomlKeys& response) {
    const toml::array* a = response.table().get_as<toml::array>("probes");
    if (!a) throw InputError(fmt::format("{} must be an array of tables such as [{}]", response.where("probes"),
                                         kProbeExample));
    if (a->empty()) throw InputError(response.where("probes") + " is empty; allowed: one or more probes, or omit it");
    std::vector<ResponseProbe> probes;
    for (std::size_t i = 0; i < a->size(); ++i) {
        const toml::table* t = (*a)[i].as_table();
        if (!t) throw InputError(fmt::format("{}[{}] is not a table; allowed: {}", response.where("probes"), i,
                                             kProbeExample));
        const TomlKeys k(response.file(), fmt::format("criteria.response.probes[{}]", i), *t);
        probes.push_back(read_probe(k));
        for (std::size_t j = 0; j < i; ++j)
            if (probes[j].name == probes[i].name)
                throw InputError(fmt::format("{} = '{}': probes[{}] has that name already; allowed: a name of its own",
                                             k.where("name"), probes[i].name, j));
    }
    return probes;
}

Probe resolve_probe(const ResponseProbe& p, const GyroscopicSystem& sys) {
    if (p.node >= 0) {
        if (sys.node_z.empty())
            throw InputError(fmt::format("node = {}: the model has no nodes on an axis (only an fe_rotor scene has); "
                                         "allowed: dof_x and dof_y by name",
                                         p.node));
        try {
            return probe_at_node(sys, p.name, p.node, p.angle_degrees);
        } catch (const InputError& e) {
            throw InputError(fmt::format("node = {}: {}", p.node, e.what()));
        }
    }
    Probe out{p.name, dof_index(sys, p.dof_x), dof_index(sys, p.dof_y), p.angle_degrees};
    const auto require = [&](const char* key, const std::string& name, int index) {
        if (index < 0)
            throw InputError(fmt::format("{} = '{}': not a DOF of the model; allowed: {}", key, name,
                                         dof_list(sys.dofs.names)));
    };
    require("dof_x", p.dof_x, out.dof_x);
    require("dof_y", p.dof_y, out.dof_y);
    const std::vector<std::string>& u = sys.dofs.units;
    if (!u.empty() && u.at(static_cast<std::size_t>(out.dof_x)) != u.at(static_cast<std::size_t>(out.dof_y)))
        throw InputError(fmt::format("dof_x = '{}' ({}) and dof_y = '{}' ({}): allowed: two DOFs of one unit",
                                     p.dof_x, u[static_cast<std::size_t>(out.dof_x)], p.dof_y,
                                     u[static_cast<std::size_t>(out.dof_y)]));
    return out;
}

void check_probes(const std::string& sweep, const std::string& scene, const std::vector<ResponseProbe>& probes,
                  const GyroscopicSystem& base) {
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const ResponseProbe& p = probes[i];
        const auto where = fmt::format("{}: [criteria.response.probes[{}]]", sweep, i);
        // A sweep assembled in code has not been through read_probes.
        if (p.name.empty()) throw InputError(where + " name is empty; allowed: the probe's name, e.g. \"NDE\"");
        for (std::size_t j = 0; j < i; ++j)
            if (probes[j].name == p.name)
                throw InputError(fmt::format("{} name = '{}': probes[{}] has that name already; allowed: a name of its "
                                             "own", where, p.name, j));
        if (!(p.angle_degrees >= -360.0 && p.angle_degrees <= 360.0))
            throw InputError(fmt::format("{} angle = {}: out of range; allowed: -360 to 360 (degrees from +x towards "
                                         "+y)", where, p.angle_degrees));
        try {
            resolve_probe(p, base);
        } catch (const InputError& e) {
            throw InputError(fmt::format("{} {} (probe '{}', scene {})", where, e.what(), p.name, scene));
        }
    }
}

}  // namespace gyrokit
