#include <gyrokit/scene/balancer_scene.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include "gyrokit/scene/toml_keys.hpp"
#include <gyrokit/core/input_file.hpp>

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <toml++/toml.h>

namespace gyrokit {

namespace {

toml::table parse(const std::string& path) { return parse_toml(read_toml_text(path, "scene file"), path); }

// The ODE method and tolerances of [simulation] or [runup] (default tolerance `tol`).
void read_ode_method(const TomlKeys& s, double tol, OdeOptions& ode) {
    std::set<std::string> names(ode_method_names().begin(), ode_method_names().end());
    ode.method = parse_ode_method(s.choice("method", "rk8pd", names));
    ode.abs_tol = s.number("abs_tol", tol, 0.0, true, "absolute tolerance");
    ode.rel_tol = s.number("rel_tol", tol, 0.0, true, "relative tolerance");
}

// Rollers 1 and 2 of [model], each given by all of its keys or none.
void read_rollers(const std::string& path, const TomlKeys& k, AutobalancerParameters& p) {
    for (int i = 1; i <= 2; ++i) {
        const std::string n = std::to_string(i);
        const bool any = k.has("m" + n) || k.has("eps" + n) || k.has("R" + n) || k.has("r" + n) || k.has("mu" + n) ||
                         k.has("beta" + n);
        if (!any) continue;
        if (i == 2 && p.rollers.empty())
            throw InputError(fmt::format("{}: [model] roller 2 is given without roller 1; number rollers from 1", path));
        Roller r;
        r.m = k.number("m" + n, std::nullopt, 0.0, true, "kg");
        r.eps = k.number("eps" + n, std::nullopt, 0.0, true, "m");
        r.R = k.number("R" + n, std::nullopt, 0.0, true, "m");
        if (!(r.R > r.eps))
            throw InputError(fmt::format("{}: [model] R{} = {}: out of range; allowed: > eps{} = {} m (R = eps + r)", path,
                                         n, r.R, n, r.eps));
        if (k.has("r" + n)) {
            const double rr = k.number("r" + n, std::nullopt, 0.0, true, "m");
            if (std::fabs(r.R - r.eps - rr) > 1e-6 * r.R)
                throw InputError(fmt::format("{}: [model] r{} = {}: must equal R{} - eps{} = {} m", path, n, rr, n, n,
                                             r.R - r.eps));
        }
        r.mu = k.number("mu" + n, std::nullopt, 0.0, false, "J_S = mu m r^2; ball 0.4");
        if (r.mu > 1.0)
            throw InputError(fmt::format("{}: [model] mu{} = {}: out of range; allowed: 0 <= mu <= 1", path, n, r.mu));
        r.beta = k.number("beta" + n, std::nullopt, 0.0, true, "N m s; the rollers need viscous damping to settle");
        p.rollers.push_back(r);
    }
}

// The bearings' stiffness: isotropic (k or omega) or per axis (k_x or omega_x, k_y or omega_y),
// a natural frequency taken with the whole mass M.
void read_stiffness(const std::string& path, const TomlKeys& k, AutobalancerParameters& p) {
    const double M = p.M();
    const bool iso = k.has("k") || k.has("omega");
    if (iso && (k.has("k_x") || k.has("k_y") || k.has("omega_x") || k.has("omega_y")))
        throw InputError(fmt::format("{}: [model] give either k or omega (isotropic) or the per-axis k_x, k_y / "
                                     "omega_x, omega_y, not both", path));
    if (iso) {
        if (k.has("k") == k.has("omega"))
            throw InputError(fmt::format("{}: [model] give exactly one of k (N/m) and omega (rad/s)", path));
        p.k_x = p.k_y = k.has("k") ? k.number("k", std::nullopt, 0.0, true, "N/m")
                                   : M * std::pow(k.number("omega", std::nullopt, 0.0, true, "rad/s"), 2);
    }
    for (const char* ax : {"x", "y"}) {
        if (iso) break;
        const std::string kk = std::string("k_") + ax, ww = std::string("omega_") + ax;
        if (k.has(kk) == k.has(ww))
            throw InputError(fmt::format("{}: [model] give exactly one of {} (N/m) and {} (rad/s)", path, kk, ww));
        const double v = k.has(kk) ? k.number(kk, std::nullopt, 0.0, true, "N/m")
                                   : M * std::pow(k.number(ww, std::nullopt, 0.0, true, "rad/s"), 2);
        (ax[0] == 'x' ? p.k_x : p.k_y) = v;
    }
}

// The drive: a prescribed speed, or the motor's L0 and beta0 (which need J > 0).
void read_drive(const std::string& path, const TomlKeys& k, AutobalancerParameters& p) {
    const bool motor = k.has("L0") || k.has("beta0");
    if (motor == k.has("speed"))
        throw InputError(fmt::format("{}: [model] give either speed (rad/s) or the motor L0 and beta0", path));
    if (motor) {
        p.drive = Drive::Motor;
        p.L0 = k.number("L0", std::nullopt, 0.0, true, "N m");
        p.beta0 = k.number("beta0", std::nullopt, 0.0, true, "N m s; total beta0 of eq. (17)");
        if (!(p.J > 0.0))
            throw InputError(fmt::format("{}: [model] J = {}: out of range; allowed with a motor drive: > 0 kg m^2", path,
                                         p.J));
    } else {
        p.drive = Drive::PrescribedSpeed;
        p.speed = k.number("speed", std::nullopt, 0.0, true, "rad/s");
    }
}

// [simulation]: duration, start angles of the rollers, start offset, ODE settings.
SimulationSettings read_simulation(const std::string& path, const toml::table& sim, const AutobalancerParameters& p) {
    const TomlKeys s(path, "simulation", sim);
    s.only({"duration", "alpha1", "alpha2", "x", "y", "method", "abs_tol", "rel_tol", "average_revolutions",
            "max_steps"});
    SimulationSettings st;
    st.duration = s.number("duration", std::nullopt, 0.0, true, "s");
    for (std::size_t i = 1; i <= 2; ++i) {
        const std::string key = "alpha" + std::to_string(i);
        if (i <= p.rollers.size())
            st.alpha.push_back(s.any_number(key, "deg") * kPi / 180.0);
        else if (s.has(key))
            throw InputError(fmt::format("{}: [simulation] {} given, but the model has {} roller(s)", path, key,
                                         p.rollers.size()));
    }
    st.x = s.has("x") ? s.any_number("x", "m") : 0.0;
    st.y = s.has("y") ? s.any_number("y", "m") : 0.0;
    read_ode_method(s, 1e-10, st.ode);
    st.average_revolutions = s.number("average_revolutions", 20.0, 1.0, false, "revolutions");
    st.ode.max_steps = static_cast<unsigned long>(s.integer("max_steps", 100000000, 1000, 1000000000000LL));
    const double rev = 2.0 * kPi / p.reference_speed();
    if (st.duration < 2.0 * rev)
        throw InputError(fmt::format("{}: [simulation] duration = {}: out of range; allowed: >= two revolutions "
                                     "({:.6g} s)", path, st.duration, 2.0 * rev));
    return st;
}

// [runup]: the motor's run-up profile, start angles, ODE settings.
RunupSettings read_runup(const std::string& path, const toml::table& ru, const AutobalancerParameters& p) {
    const TomlKeys s(path, "runup", ru);
    s.only({"max_speed", "rise", "hold", "fall", "alpha1", "alpha2", "method", "abs_tol", "rel_tol", "max_steps"});
    if (p.drive != Drive::Motor)
        throw InputError(fmt::format("{}: [runup] needs the motor drive: give L0 and beta0 in [model] instead of "
                                     "speed", path));
    RunupSettings st;
    st.max_speed = s.number("max_speed", std::nullopt, 0.0, true, "rad/s");
    st.rise = s.number("rise", std::nullopt, 0.0, true, "s");
    st.hold = s.number("hold", std::nullopt, 0.0, true, "s");
    st.fall = s.number("fall", 0.0, 0.0, false, "s");
    for (std::size_t i = 1; i <= 2; ++i) {
        const std::string key = "alpha" + std::to_string(i);
        if (i <= p.rollers.size())
            st.alpha.push_back(s.has(key) ? s.any_number(key, "deg") * kPi / 180.0 : 0.0);
        else if (s.has(key))
            throw InputError(fmt::format("{}: [runup] {} given, but the model has {} roller(s)", path, key,
                                         p.rollers.size()));
    }
    read_ode_method(s, 1e-9, st.ode);
    st.ode.max_steps = static_cast<unsigned long>(s.integer("max_steps", 100000000, 1000, 1000000000000LL));
    try {
        st.validate();
    } catch (const InputError& e) {
        throw InputError(fmt::format("{}: [runup] {}", path, e.what()));
    }
    return st;
}

}  // namespace

BalancerScene load_balancer_scene(const std::string& path) {
    const toml::table root = parse(path);
    BalancerScene sc;
    sc.file = path;
    for (const auto& [k, v] : root) {
        const std::string key(k.str());
        if (key != "title" && key != "model" && key != "simulation" && key != "runup")
            throw InputError(fmt::format("{}: unknown top-level key '{}'; allowed: title, model, simulation, runup",
                                         path, key));
    }
    if (const toml::node* t = root.get("title")) {
        if (!t->is_string()) throw InputError(fmt::format("{}: title must be a string", path));
        sc.title = *t->value<std::string>();
    }
    const toml::table* model = root.get_as<toml::table>("model");
    if (!model) throw InputError(fmt::format("{}: missing table [model]", path));
    const TomlKeys k(path, "model", *model);
    k.only({"type", "m", "J", "m0", "eps0", "k_x", "k_y", "omega_x", "omega_y", "c_x", "c_y", "m1", "eps1", "R1", "r1",
            "mu1", "beta1", "m2", "eps2", "R2", "r2", "mu2", "beta2", "speed", "L0", "beta0", "k", "omega", "c"});
    if (!k.has("type")) throw InputError(fmt::format("{}: [model] key 'type' is missing; required: \"autobalancer\"", path));
    k.choice("type", "", {"autobalancer"});

    AutobalancerParameters& p = sc.params;
    p.m = k.number("m", std::nullopt, 0.0, true, "kg");
    p.J = k.number("J", 0.0, 0.0, false, "kg m^2");
    p.m0 = k.number("m0", std::nullopt, 0.0, false, "kg");
    p.eps0 = k.number("eps0", std::nullopt, 0.0, false, "m");
    // Isotropic bearings: c for both axes.
    if (k.has("c") && (k.has("c_x") || k.has("c_y")))
        throw InputError(fmt::format("{}: [model] give either c (isotropic) or c_x and c_y, not both", path));
    if (k.has("c")) {
        p.c_x = p.c_y = k.number("c", std::nullopt, 0.0, false, "N s/m");
    } else {
        p.c_x = k.number("c_x", 0.0, 0.0, false, "N s/m");
        p.c_y = k.number("c_y", 0.0, 0.0, false, "N s/m");
    }
    read_rollers(path, k, p);
    read_stiffness(path, k, p);
    read_drive(path, k, p);
    try {
        p.validate();
    } catch (const InputError& e) {
        throw InputError(fmt::format("{}: [model] {}", path, e.what()));
    }


    if (const toml::table* sim = root.get_as<toml::table>("simulation")) {
        sc.simulation = read_simulation(path, *sim, p);
        sc.has_simulation = true;
    }
    if (const toml::table* ru = root.get_as<toml::table>("runup")) {
        sc.runup = read_runup(path, *ru, p);
        sc.has_runup = true;
    }
    return sc;
}

}  // namespace gyrokit
