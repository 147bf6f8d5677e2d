#include <gyrokit/scene/scene_writer.hpp>

#include <gyrokit/io/output_file.hpp>
#include <gyrokit/core/run_files.hpp>

#include <gyrokit/core/solver_kind.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/length_unit.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <type_traits>
#include <variant>

namespace gyrokit {

namespace {

namespace fs = std::filesystem;

// A finite double in its shortest round-trip form, always a TOML float ("2e+11", "3.0").
std::string number(double v) {
    std::string s = fmt::format("{}", v);
    if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
    return s;
}

// A TOML basic string: quotes, backslashes and control characters escaped.
std::string quoted(const std::string& text) {
    std::string s = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\')
            s += {'\\', ch};
        else if (c < 0x20 || c == 0x7f)
            s += fmt::format("\\u{:04x}", c);
        else
            s += ch;
    }
    return s + "\"";
}

double degrees(double rad) { return rad * 180.0 / kPi; }   // as written before: the same digits

// A length in a unit of `metres` per unit, written back in that unit: in metres its shortest
// round-trip form; in another unit the shortest text x (15, 16 or 17 significant digits, of
// v / metres or its neighbours) that the reader's x * metres turns back into v, so that a
// value read from a scene in that unit is written as the x it was, and any other reads back
// bit for bit too.
std::string length_number(double v, double metres) {
    if (metres == 1.0 || !std::isfinite(v)) return number(v);
    const auto as_float = [](std::string s) {
        if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
        return s;
    };
    const double q = v / metres, up = std::nextafter(q, HUGE_VAL), down = std::nextafter(q, -HUGE_VAL);
    const double candidates[] = {q, up, down, std::nextafter(up, HUGE_VAL), std::nextafter(down, -HUGE_VAL)};
    for (const int digits : {15, 16, 17})
        for (const double x : candidates) {
            const std::string s = fmt::format("{:.{}g}", x, digits);
            if (std::strtod(s.c_str(), nullptr) * metres == v) return as_float(s);
        }
    return as_float(fmt::format("{:.17g}", q));   // within an ulp of v
}

class Writer {
public:
    explicit Writer(double metres = 1.0) : metres_(metres) {}
    void key(const char* name, double v) { out_ += fmt::format("{} = {}\n", name, number(v)); }
    // A length, in the model's length unit.
    void length(const char* name, double v) { out_ += fmt::format("{} = {}\n", name, length_number(v, metres_)); }
    void key(const char* name, int v) { out_ += fmt::format("{} = {}\n", name, v); }
    void key(const char* name, bool v) { out_ += fmt::format("{} = {}\n", name, v ? "true" : "false"); }
    void key(const char* name, const std::string& v) { out_ += fmt::format("{} = {}\n", name, quoted(v)); }
    void key(const char* name, const char* v) { key(name, std::string(v)); }
    template <class F>
    void array(const char* name, std::size_t n, const F& value) {
        out_ += fmt::format("{} = [", name);
        for (std::size_t i = 0; i < n; ++i) out_ += (i ? ", " : "") + number(value(i));
        out_ += "]\n";
    }
    void harmonics(const std::vector<int>& h) {
        out_ += "harmonics = [";
        for (std::size_t i = 0; i < h.size(); ++i) out_ += fmt::format("{}{}", i ? ", " : "", h[i]);
        out_ += "]\n";
    }
    void table(const std::string& header) { out_ += "\n" + header + "\n"; }
    std::string text() const { return out_; }

private:
    double metres_;
    std::string out_;
};

void write_section(Writer& w, const RotorSection& s) {
    w.table("[[model.shaft]]");
    const FeShaftElement& e = s.shape;
    if (e.coupling) {
        const FeCoupling& c = *e.coupling;
        w.key("type", "coupling");
        w.length("length", e.length);
        w.key("k_lateral", c.k_lateral);
        w.key("k_bending", c.k_bending);
        w.key("k_axial", c.k_axial);
        w.key("k_torsion", c.k_torsion);
        w.key("c_lateral", c.c_lateral);
        w.key("c_bending", c.c_bending);
        w.key("c_axial", c.c_axial);
        w.key("c_torsion", c.c_torsion);
        w.key("mass", c.mass);
        w.key("Id", c.diametral_inertia);
        w.key("Ip", c.polar_inertia);
        return;
    }
    w.length("length", e.length);
    w.key("elements", s.elements);
    w.length("outer_diameter", e.outer_diameter);
    w.length("inner_diameter", e.inner_diameter);
    if (e.outer_diameter_end) w.length("outer_diameter_end", *e.outer_diameter_end);
    if (e.inner_diameter_end) w.length("inner_diameter_end", *e.inner_diameter_end);
    w.key("E", e.youngs_modulus);
    if (e.shear_modulus != 0.0) w.key("G", e.shear_modulus);
    w.key("poisson", e.poisson_ratio);
    w.key("density", e.density);
}

void write_disk(Writer& w, const RotorDisk& d) {
    w.table("[[model.disk]]");
    w.length("z", d.z);
    if (d.geometry) {
        w.length("outer_diameter", d.geometry->outer_diameter);
        w.length("inner_diameter", d.geometry->inner_diameter);
        w.length("width", d.geometry->width);
        w.key("density", d.geometry->density);
    } else {
        w.key("mass", d.disk.mass);
        w.key("Id", d.disk.diametral_inertia);
        w.key("Ip", d.disk.polar_inertia);
    }
    w.key("unbalance", d.disk.unbalance);
    w.key("phase", degrees(d.disk.unbalance_phase));
}

void write_film(Writer& w, const RotorBearing& b) {
    const JournalBearing& j = b.film;
    w.key("type", "fluid_film");
    w.length("z", b.z);
    w.length("diameter", j.diameter);
    w.length("length", j.length);
    w.length("clearance", j.clearance);
    w.key("viscosity", j.viscosity);
    if (j.clearance_min) w.length("clearance_min", *j.clearance_min);
    if (j.clearance_max) w.length("clearance_max", *j.clearance_max);
    if (j.viscosity_min) w.key("viscosity_min", *j.viscosity_min);
    if (j.viscosity_max) w.key("viscosity_max", *j.viscosity_max);
    if (b.auto_load)
        w.key("load", "auto");
    else
        w.key("load", j.load);
    w.key("load_angle", degrees(j.load_angle));
    w.key("max_eccentricity", j.max_eccentricity);
    if (j.solution == FilmSolution::finite_difference) {
        w.key("solution", "finite_difference");
        w.key("grid_circumferential", j.grid_circumferential);
        w.key("grid_axial", j.grid_axial);
    }
}

void write_bearing(Writer& w, const RotorBearing& b) {
    w.table("[[model.bearing]]");
    if (b.kind == RotorBearing::Kind::fluid_film) return write_film(w, b);
    w.length("z", b.z);
    if (b.kind == RotorBearing::Kind::table && !b.table_file.empty()) {
        w.key("table", fs::absolute(b.table_file).lexically_normal().string());
        return;
    }
    if (b.kind == RotorBearing::Kind::table) {
        const BearingTable& t = b.table;
        w.array("speeds", t.speeds.size(), [&](std::size_t i) { return t.speeds[i]; });
        const char* names[2][4] = {{"kxx", "kxy", "kyx", "kyy"}, {"cxx", "cxy", "cyx", "cyy"}};
        for (int m = 0; m < 2; ++m)
            for (int k = 0; k < 4; ++k)
                w.array(names[m][k], t.rows.size(), [&](std::size_t i) {
                    const Eigen::Matrix2d& A = m == 0 ? t.rows[i].K : t.rows[i].C;
                    return A(k / 2, k % 2);
                });
        return;
    }
    const FeBearing& c = b.constant;
    w.key("kxx", c.kxx);
    w.key("kxy", c.kxy);
    w.key("kyx", c.kyx);
    w.key("kyy", c.kyy);
    w.key("cxx", c.cxx);
    w.key("cxy", c.cxy);
    w.key("cyx", c.cyx);
    w.key("cyy", c.cyy);
    w.key("kzz", c.kzz);
    w.key("czz", c.czz);
}

void write_support(Writer& w, const RotorSupport& s, std::size_t i) {
    const FeSupport& h = s.hold;
    const bool clamped = h.x && h.y && h.theta_x && h.theta_y;
    const bool pinned = h.x && h.y && !h.theta_x && !h.theta_y;
    if (!clamped && !pinned)
        throw InputError(fmt::format("{}: holds x = {}, y = {}, theta_x = {}, theta_y = {}, which a scene cannot "
                                     "say; allowed in a scene: pinned (x, y) or clamped (x, y, theta_x, theta_y)",
                                     s.origin.empty() ? fmt::format("support {}", i + 1) : s.origin, h.x, h.y, h.theta_x,
                                     h.theta_y));
    w.table("[[model.support]]");
    w.length("z", s.z);
    w.key("type", clamped ? "clamped" : "pinned");
    w.key("axial", h.z);
    w.key("torsion", h.theta_z);
}

void write_pedestal(Writer& w, const RotorPedestal& p) {
    w.table("[[model.pedestal]]");
    w.length("z", p.z);
    w.key("mass", p.pedestal.mass);
    w.key("kxx", p.pedestal.kxx);
    w.key("kyy", p.pedestal.kyy);
    w.key("cxx", p.pedestal.cxx);
    w.key("cyy", p.pedestal.cyy);
}

// [api] in the keys the reader takes: speeds in the scene's unit, lengths in the
// model's length_unit (as the written [model] states it).
void write_api(Writer& w, const ApiMachine& m, const SpeedUnit& unit) {
    w.table("[api]");
    w.key("machine", to_string(m.kind));
    if (m.mcs) w.key("mcs", *m.mcs * unit.factor);
    if (m.operating_speed) w.key("operating_speed", *m.operating_speed * unit.factor);
    if (m.qa) w.key("qa", *m.qa);
    if (m.station) w.length("station", *m.station);
    if (m.gas_density) w.key("gas_density", *m.gas_density);
    w.key("q_ratio", m.q_ratio);
    if (m.min_speed) w.key("min_speed", *m.min_speed * unit.factor);
    if (m.trip_speed) w.key("trip_speed", *m.trip_speed * unit.factor);
    for (const AeroStage& s : m.stages) {
        w.table("[[api.stage]]");
        w.length("z", s.z);
        w.key("power", s.power);
        w.length("diameter", s.diameter);
        w.length("width", s.width);
        if (s.density_ratio) w.key("density_ratio", *s.density_ratio);
    }
    for (const CloseClearance& c : m.clearances) {
        w.table("[[api.clearance]]");
        w.length("z", c.z);
        w.length("clearance", c.clearance);
        if (!c.name.empty()) w.key("name", c.name);
    }
}

void write_settings(Writer& w, const Scene& sc) {
    if (sc.speeds) {
        w.table("[speeds]");
        w.key("from", sc.speeds->from);
        w.key("to", sc.speeds->to);
        w.key("count", sc.speeds->count);
        w.key("units", sc.speed_unit.name);
    }
    w.table("[analysis]");
    w.key("solver", to_string(sc.solver.kind));
    if (sc.solver.modes != kModesInRange) w.key("modes", sc.solver.modes);
    if (sc.solver.target) w.key("target", *sc.solver.target);
    w.key("target_order", sc.solver.target_order);
    if (sc.analysis.f_cut) w.key("f_cut", *sc.analysis.f_cut);
    w.harmonics(sc.analysis.harmonics);
    if (sc.api) write_api(w, *sc.api, sc.speed_unit);
}

// A scene's start: title, [model] and its type.
void write_model_header(Writer& w, const Scene& sc, const char* type) {
    if (!sc.title.empty()) w.key("title", sc.title);
    w.table("[model]");
    w.key("type", type);
}

// The [model] of a gyrostat, in the keys the reader takes (docs/scene_format.md).
void write_gyrostat(Writer& w, const GyrostatParameters& p) {
    w.key("shaft", p.rigid_shaft ? "rigid" : "elastic");
    w.key("housing", p.rigid_housing ? "rigid" : "elastic");
    if (!p.rigid_housing) w.key("A_G", p.A_G), w.key("B_G", p.B_G), w.key("c_G", p.c_G);
    w.key("A_R", p.A_R);
    w.key("C_R", p.C_R);
    w.key("m", p.m);
    w.key("s", p.s);
    w.key("eps", p.eps);
    if (!p.rigid_shaft) w.key("c_T", p.c_T), w.key("c_R", p.c_R);
    w.key("d_G", p.d_G);
    w.key("d_T", p.d_T);
    w.key("d_R", p.d_R);
}

// The [model] of a liquid-filled rotor (docs/fluid_rotor.md).
void write_fluid_rotor(Writer& w, const FluidRotorParameters& p) {
    for (const auto& [name, v] : {std::pair<const char*, double>{"R", p.R}, {"R0", p.R0}, {"a", p.a}, {"l", p.l},
                                  {"rho", p.rho}, {"nu", p.nu}, {"c1", p.c1}, {"c2", p.c2}, {"c11", p.c11},
                                  {"m0", p.m0}, {"I0", p.I0}, {"J0", p.J0}, {"e", p.e}})
        w.key(name, v);
    if (p.modes > 0) w.key("modes", p.modes);
    else w.key("tolerance", p.tolerance);
    if (p.jstar_terms > 0) w.key("jstar_terms", p.jstar_terms);
}

std::string finished(const Writer& w) {
    std::string text = w.text();
    return text.front() == '\n' ? text.substr(1) : text;
}

}  // namespace

Scene model_scene(const GyrostatParameters& parameters, const std::string& title) {
    Scene sc;
    sc.path = title.empty() ? "gyrostat" : title;
    sc.title = title;
    validate(parameters, sc.path);
    sc.system = make_system(parameters);
    sc.system.validate(sc.path);
    sc.model = GyrostatScene{parameters, {}};
    return sc;
}

Scene model_scene(const FluidRotorParameters& parameters, const std::string& title) {
    Scene sc;
    sc.path = title.empty() ? "fluid_rotor" : title;
    sc.title = title;
    validate(parameters, sc.path);
    sc.system = make_system(build_fluid_rotor(parameters));
    sc.system.validate(sc.path);
    sc.model = FluidRotorScene{parameters, {}};
    return sc;
}

Scene rotor_scene(const RotorModel& model, const std::string& title) {
    Scene sc;
    sc.path = title.empty() ? "fe_rotor" : title;
    sc.title = title;
    BuiltRotor built = build(model);
    built.system.validate(sc.path);
    sc.system = std::move(built.system);
    sc.model = FeRotorScene{model, std::move(built.rotor)};
    return sc;
}

std::string scene_text(const Scene& sc) {
    const std::string document =
        std::visit([](const auto& m) -> std::string {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, FeRotorScene>) return {};
            else return m.document;
        }, sc.model);
    if (!document.empty()) return document;   // read from a document: as read
    if (const GyrostatParameters* g = sc.gyrostat()) {
        Writer w;
        write_model_header(w, sc, "gyrostat");
        write_gyrostat(w, *g);
        write_settings(w, sc);
        return finished(w);
    }
    if (const FluidRotorParameters* f = sc.fluid()) {
        Writer w;
        write_model_header(w, sc, "fluid_rotor");
        write_fluid_rotor(w, *f);
        write_settings(w, sc);
        return finished(w);
    }
    if (!sc.rotor_model())
        throw InputError(fmt::format("{}: a [model] of type {} built in code cannot be written (it has no document); "
                                     "allowed: an fe_rotor, gyrostat or fluid_rotor model (read from a scene or built "
                                     "from its parameters), or any model read from a scene",
                                     sc.path, sc.model_type()));
    const RotorModel& m = *sc.rotor_model();
    // Lengths in the model's own unit (a scene in mm is written back in mm).
    const LengthUnit unit = LengthUnit::parse(m.length_unit);
    Writer w(unit.metres);
    write_model_header(w, sc, "fe_rotor");
    w.key("motion", to_string(m.motion));
    w.key("length_unit", unit.name);
    w.key("shear_deformation", m.shear_deformation);
    w.key("rotary_inertia", m.rotary_inertia);
    if (m.shaft_damping.alpha != 0.0) w.key("damping_alpha", m.shaft_damping.alpha);
    if (m.shaft_damping.beta != 0.0) w.key("damping_beta", m.shaft_damping.beta);
    const std::vector<double>& zeta = m.shaft_damping.modal;
    if (!zeta.empty()) w.array("damping_zeta", zeta.size(), [&](std::size_t i) { return zeta[i]; });
    for (const RotorSection& s : m.sections) write_section(w, s);
    for (const RotorDisk& d : m.disks) write_disk(w, d);
    for (const RotorBearing& b : m.bearings) write_bearing(w, b);
    for (std::size_t i = 0; i < m.supports.size(); ++i) write_support(w, m.supports[i], i);
    for (const RotorPedestal& p : m.pedestals) write_pedestal(w, p);
    write_settings(w, sc);
    return finished(w);
}

void write_scene(const Scene& scene, const std::string& path) {
    // A scene may be written back over its own file (an edit), never over a matrix or table it reads.
    const FileIdentity own = identify_file(scene.path);
    std::vector<std::string> reads;
    for (const auto& in : scene.inputs)
        if (!identify_file(in).same_file(own)) reads.push_back(in);
    RunFiles files(reads);
    RunScope run(files);
    replace_file(path, scene_text(scene), "scene");
}

}  // namespace gyrokit
