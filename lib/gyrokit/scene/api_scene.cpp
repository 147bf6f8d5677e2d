#include "gyrokit/scene/detail/api_scene.hpp"

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

namespace gyrokit {

// [api]: speeds in the scene's [speeds] units, lengths in its length_unit.
ApiMachine api_machine_from(const TomlKeys& k, const toml::table& t, const Scene& sc) {
    if (!sc.rotor_model())
        throw InputError(k.file() + ": [api] is given for a [model] of type " + sc.model_type() +
                         "; allowed: an fe_rotor model (Level I needs the rotor's nodes and bearings)");
    k.only({"machine", "mcs", "operating_speed", "qa", "station", "gas_density", "q_ratio", "stage", "min_speed",
            "trip_speed", "clearance"});
    ApiMachine m;
    m.origin = k.file() + ": [api]";
    const char* unit = sc.speed_unit.name.c_str();
    const double per_rad_s = sc.speed_unit.factor;
    const double metres = sc.length_unit().metres;
    const std::string lunit = sc.length_unit().name;
    m.kind = k.choice("machine", "centrifugal", {"centrifugal", "axial"}) == "axial" ? MachineKind::axial
                                                                                     : MachineKind::centrifugal;
    if (k.has("mcs")) m.mcs = k.number("mcs", std::nullopt, 0, true, unit) / per_rad_s;
    if (k.has("operating_speed")) m.operating_speed = k.number("operating_speed", std::nullopt, 0, true, unit) / per_rad_s;
    if (k.has("qa")) m.qa = k.number("qa", std::nullopt, 0, true, "N/m");
    if (k.has("station")) m.station = k.any_number("station", lunit.c_str()) * metres;
    if (k.has("gas_density")) m.gas_density = k.number("gas_density", std::nullopt, 0, true, "kg/m^3");
    m.q_ratio = k.number("q_ratio", kLevel1QRatio, 0, true, "multiples of QA");   // its range: validate
    if (k.has("min_speed")) m.min_speed = k.number("min_speed", std::nullopt, 0, true, unit) / per_rad_s;
    if (k.has("trip_speed")) m.trip_speed = k.number("trip_speed", std::nullopt, 0, true, unit) / per_rad_s;
    if (const toml::array* cl = t.get_as<toml::array>("clearance")) {
        for (std::size_t i = 0; i < cl->size(); ++i) {
            const toml::table* e = cl->get(i)->as_table();
            const std::string name = fmt::format("api.clearance[{}]", i);
            if (!e) throw InputError(k.where("clearance") + ": each entry must be a table [[api.clearance]]");
            TomlKeys s(k.file(), name, *e);
            s.only({"z", "clearance", "name"});
            CloseClearance c;
            c.origin = fmt::format("{}: [{}]", k.file(), name);
            c.z = s.any_number("z", lunit.c_str()) * metres;
            c.clearance = s.number("clearance", std::nullopt, 0, true, lunit.c_str()) * metres;
            c.name = s.text("name", "");
            m.clearances.push_back(c);
        }
    } else if (t.contains("clearance")) {
        throw InputError(k.where("clearance") + " must be an array of tables [[api.clearance]]");
    }
    // The speeds' order, in the file's unit (validate checks it again in rad/s).
    if (m.mcs && m.min_speed && *m.min_speed > *m.mcs)
        throw InputError(fmt::format("{} = {:.6g}: out of range; allowed: (0, {:.6g}] {} (at most the mcs)",
                                     k.where("min_speed"), *m.min_speed * per_rad_s, *m.mcs * per_rad_s, unit));
    if (m.mcs && m.trip_speed && *m.trip_speed < *m.mcs)
        throw InputError(fmt::format("{} = {:.6g}: out of range; allowed: at least the mcs, {:.6g} {}",
                                     k.where("trip_speed"), *m.trip_speed * per_rad_s, *m.mcs * per_rad_s, unit));
    if (const toml::array* st = t.get_as<toml::array>("stage")) {
        for (std::size_t i = 0; i < st->size(); ++i) {
            const toml::table* e = st->get(i)->as_table();
            const std::string name = fmt::format("api.stage[{}]", i);
            if (!e) throw InputError(k.where("stage") + ": each entry must be a table [[api.stage]]");
            TomlKeys s(k.file(), name, *e);
            s.only({"z", "power", "diameter", "width", "density_ratio"});
            AeroStage a;
            a.origin = fmt::format("{}: [{}]", k.file(), name);
            a.z = s.any_number("z", lunit.c_str()) * metres;
            a.power = s.number("power", std::nullopt, 0, true, "W");
            a.diameter = s.number("diameter", std::nullopt, 0, true, lunit.c_str()) * metres;
            a.width = s.number("width", std::nullopt, 0, true, lunit.c_str()) * metres;
            if (m.kind == MachineKind::centrifugal)
                a.density_ratio = s.number("density_ratio", std::nullopt, 0, true, "discharge / suction density");
            else if (s.has("density_ratio"))
                throw InputError(s.where("density_ratio") + " is given for an axial machine; allowed: only with "
                                                            "machine = \"centrifugal\" (Alford's form has none)");
            m.stages.push_back(a);
        }
    } else if (t.contains("stage")) {
        throw InputError(k.where("stage") + " must be an array of tables [[api.stage]]");
    }
    validate(m);
    return m;
}

}  // namespace gyrokit
