#include <gyrokit/study/api_unbalance_study.hpp>

#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/models/gravity_loads.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/reports/campbell_reports.hpp>
#include <gyrokit/study/request.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

namespace gyrokit {

const char* to_string(ApiVerdict v) {
    switch (v) {
        case ApiVerdict::pass: return "pass";
        case ApiVerdict::pass_scaled: return "pass (scaled clearances)";
        case ApiVerdict::fail: return "fail";
        default: return "not judged";
    }
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The speeds: the scene's [api] with the request's on top, validated.
void speeds_of(const Scene& sc, const ApiUnbalanceRequest& r, ApiUnbalanceStudy& s) {
    ApiMachine m = sc.api ? *sc.api : ApiMachine{};
    if (m.origin.empty()) m.origin = sc.path + ": [api]";
    const SpeedUnit& u = s.unit;
    if (r.mcs) m.mcs = to_rad_s(*r.mcs, "mcs", "speed", u, true);
    if (r.min_speed) m.min_speed = to_rad_s(*r.min_speed, "min_speed", "speed", u, true);
    if (r.trip_speed) m.trip_speed = to_rad_s(*r.trip_speed, "trip_speed", "speed", u, true);
    if (!m.mcs)
        throw InputError(fmt::format("{}: the maximum continuous speed is missing; required: [api] mcs in the scene or "
                                     "{} (in {})",
                                     sc.path, option_field("mcs"), u.name));
    // The order of the speeds, named where each came from and in the caller's unit.
    const auto named = [&](bool given, const char* key) {
        return given ? option_field(key) : fmt::format("{}: [api] {} =", sc.path, key);
    };
    const std::string mcs_text = fmt::format("{:.6g} {}", u.factor * *m.mcs, u.name);
    if (m.min_speed && *m.min_speed > *m.mcs)
        throw InputError(fmt::format("{} {:.6g}: allowed: (0, {}] (at most the mcs)", named(r.min_speed.has_value(),
                                     "min_speed"), u.factor * *m.min_speed, mcs_text));
    if (m.trip_speed && *m.trip_speed < *m.mcs)
        throw InputError(fmt::format("{} {:.6g}: allowed: at least the mcs, {}", named(r.trip_speed.has_value(),
                                     "trip_speed"), u.factor * *m.trip_speed, mcs_text));
    validate(m);
    s.mcs = *m.mcs;
    s.min_speed = m.min_speed.value_or(s.mcs);
    s.trip_speed = m.trip_speed.value_or(kApiTripRatio * s.mcs);
    s.search_to = std::max(kApiTripReach * s.trip_speed, kApiMarginReach * s.mcs);
    if (!m.min_speed)
        s.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict,
                                 "no minimum operating speed is given: the operating range is the mcs alone (" +
                                     option_field("min_speed") + ")"});
}

// A probe at each bearing; a close clearance at each fluid-film bearing (twice its
// radial clearance) and at each [[api.clearance]].
void locations_of(const Scene& sc, ApiUnbalanceStudy& s) {
    const GyroscopicSystem& sys = sc.system;
    const LengthUnit& lu = s.length_unit;
    const auto node_at = [&](double z, const std::string& what) {
        const int node = sys.nearest_node(z, lu);
        if (sys.dofs.find(node, DofMotion::x) < 0 || sys.dofs.find(node, DofMotion::y) < 0)
            throw InputError(fmt::format("{}: {} at z = {} {}: its node {} does not move laterally (a rigid support "
                                         "holds it); allowed: a position whose node has x and y",
                                         sc.path, what, lu.in_unit(z), lu.name, node));
        return node;
    };
    const auto at = [&](double z) { return fmt::format("z = {:.6g} {}", lu.in_unit(z), lu.name); };
    // A probe sits in the bearing housing and a film between journal and housing: on a
    // pedestal both read the shaft's motion relative to it.
    const auto on_pedestal = [&](int node) { return sys.dofs.find(node, DofMotion::x, true) >= 0; };
    for (const RotorBearing& b : sc.rotor_model()->bearings) {
        const int node = node_at(b.z, "a bearing");
        s.locations.push_back(
            {"probe at the bearing at " + at(b.z), true, node, sys.node_z.at(node), 0.0, on_pedestal(node)});
    }
    for (const RotorBearing& b : sc.rotor_model()->bearings)
        if (b.kind == RotorBearing::Kind::fluid_film) {
            const int node = node_at(b.z, "a bearing");
            s.locations.push_back({"fluid-film bearing at " + at(b.z), false, node, sys.node_z.at(node),
                                   2.0 * b.film.clearance, on_pedestal(node)});
        }
    if (sc.api)
        for (std::size_t i = 0; i < sc.api->clearances.size(); ++i) {
            const CloseClearance& c = sc.api->clearances[i];
            const int node = node_at(c.z, fmt::format("[api.clearance[{}]]", i));
            s.locations.push_back({c.name.empty() ? fmt::format("clearance at {}", at(c.z)) : c.name, false, node,
                                   sys.node_z.at(node), c.clearance, false});
        }
}

// The shaft's nodes that move in x and y: their positions and DOFs.
struct ShaftNodes {
    std::vector<int> nodes, x, y;
    std::vector<double> z;
};
ShaftNodes shaft_nodes(const GyroscopicSystem& sys) {
    ShaftNodes n;
    for (std::size_t k = 0; k < sys.node_z.size(); ++k) {
        const int x = sys.dofs.find(static_cast<int>(k), DofMotion::x);
        const int y = sys.dofs.find(static_cast<int>(k), DofMotion::y);
        if (x < 0 || y < 0) continue;
        n.nodes.push_back(static_cast<int>(k));
        n.x.push_back(x);
        n.y.push_back(y);
        n.z.push_back(sys.node_z[k]);
    }
    return n;
}

// The weights of U's formula (kg).
struct Weights {
    std::vector<double> bearing_z, journal;   // each bearing's position and static load
    double total = 0.0;                        // the journals' sum
};
Weights weights_of(const Scene& sc) {
    Weights w;
    std::vector<int> nodes;
    for (const RotorBearing& b : sc.rotor_model()->bearings) {
        w.bearing_z.push_back(b.z);
        nodes.push_back(sc.system.nearest_node(b.z, sc.length_unit()));
    }
    if (nodes.empty())
        throw InputError(sc.path + ": the rotor has no bearing; the API unbalance is sized by the journals' static "
                                   "loads");
    for (const double r : fe_gravity_reactions(*sc.fe_rotor(), nodes)) {
        w.journal.push_back(r / kStandardGravity);
        w.total += r / kStandardGravity;
    }
    return w;
}

// The mass (kg) of the shaft and disks outboard of the bearing at z_b, on the side of z;
// positions compared to 1e-9 of the shaft's length (node positions are sums of element
// lengths, the bearing's as written).
double overhang_mass(const FeRotor& rotor, const std::vector<double>& node_z, double z_b, double z) {
    const bool left = z < z_b;
    const double tol = 1e-9 * std::max(1.0, node_z.back() - node_z.front());
    double m = 0.0;
    for (std::size_t e = 0; e < rotor.elements.size(); ++e) {
        const double a = node_z.at(e), b = node_z.at(e + 1);
        if (left ? b <= z_b + tol : a >= z_b - tol) m += fe_element_mass(rotor.elements[e]);
    }
    for (const FeDisk& d : rotor.disks) {
        const double zd = node_z.at(static_cast<std::size_t>(d.node));
        if (left ? zd < z_b - tol : zd > z_b + tol) m += d.mass;
    }
    return m;
}

std::vector<ApiUnbalanceLoad> loads_of(const Scene& sc, const ApiUnbalanceStudy& s, const UnbalancePlacement& p,
                                       const ShaftNodes& nodes, const Weights& w) {
    const LengthUnit& lu = s.length_unit;
    const auto at = [&](double z) { return fmt::format("z = {:.6g} {}", lu.in_unit(z), lu.name); };
    std::vector<ApiUnbalanceLoad> loads;
    for (const UnbalancePoint& pt : p.points) {
        ApiUnbalanceLoad l;
        l.node = nodes.nodes[static_cast<std::size_t>(pt.index)];
        l.z = nodes.z[static_cast<std::size_t>(pt.index)];
        l.phase = pt.phase;
        // The bearing nearest the point; of two as near (to 1e-9 of the span), the heavier
        // load (no tie is broken by rounding).
        std::size_t near = 0;
        const double tie = 1e-9 * std::max(1.0, w.bearing_z.back() - w.bearing_z.front());
        for (std::size_t b = 1; b < w.bearing_z.size(); ++b) {
            const double db = std::fabs(w.bearing_z[b] - l.z), dn = std::fabs(w.bearing_z[near] - l.z);
            if (db < dn - tie || (std::fabs(db - dn) <= tie && w.journal[b] > w.journal[near])) near = b;
        }
        if (p.layout == UnbalanceLayout::first_mode) {
            l.weight = w.total;
            l.weight_of = "the journals' static loads (sum)";
        } else if (p.layout == UnbalanceLayout::second_mode) {
            l.weight = w.journal[near];
            l.weight_of = "the static load of the journal at " + at(w.bearing_z[near]);
        } else {
            const double z_b = l.z < w.bearing_z[near] ? *std::min_element(w.bearing_z.begin(), w.bearing_z.end())
                                                      : *std::max_element(w.bearing_z.begin(), w.bearing_z.end());
            l.weight = overhang_mass(*sc.fe_rotor(), sc.system.node_z, z_b, l.z);
            l.weight_of = "the overhang outboard of the bearing at " + at(z_b);
        }
        if (!(l.weight > 0))
            throw InputError(fmt::format("{}: the API unbalance at {} is sized by {}, which is {} kg; allowed: a weight "
                                         "> 0 (the rotor must rest on its bearings)",
                                         sc.path, at(l.z), l.weight_of, l.weight));
        l.unbalance = api_unbalance(l.weight, s.mcs);
        loads.push_back(l);
    }
    return loads;
}

GyroscopicSystem with_unbalance(const GyroscopicSystem& sys, const std::vector<ApiUnbalanceLoad>& loads) {
    GyroscopicSystem c = sys;
    c.unbalance = Eigen::VectorXcd::Zero(sys.size());
    for (const ApiUnbalanceLoad& l : loads) {
        const std::complex<double> f = l.unbalance * std::polar(1.0, l.phase);
        c.unbalance(sys.dofs.find(l.node, DofMotion::x)) += f;
        c.unbalance(sys.dofs.find(l.node, DofMotion::y)) += std::complex<double>(0, -1) * f;
    }
    return c;
}

// The case's peak-to-peak orbits at the locations over the response speeds, and each
// location's largest, refined between grid speeds.
void respond(const GyroscopicSystem& sys, ApiUnbalanceStudy& s, ApiUnbalanceCase& c) {
    const std::size_t nl = s.locations.size(), ns = s.response_speeds.size();
    // Each location's x and y, and its pedestal's (-1: read absolutely).
    struct Reading {
        int x, y, px = -1, py = -1;
    };
    std::vector<Reading> dofs;
    for (const ApiLocation& l : s.locations) {
        Reading r{sys.dofs.find(l.node, DofMotion::x), sys.dofs.find(l.node, DofMotion::y)};
        if (l.relative) {
            r.px = sys.dofs.find(l.node, DofMotion::x, true);
            r.py = sys.dofs.find(l.node, DofMotion::y, true);
        }
        dofs.push_back(r);
    }
    const auto orbits = [&](double w) {
        Eigen::VectorXd pp(nl);
        ++s.solves;
        try {
            const Eigen::VectorXcd z = unbalance_response(sys, w);
            for (std::size_t k = 0; k < nl; ++k) {
                const Reading& r = dofs[k];
                const std::complex<double> zero(0.0, 0.0);
                pp(k) = orbit_peak_to_peak(z(r.x) - (r.px >= 0 ? z(r.px) : zero),
                                           z(r.y) - (r.py >= 0 ? z(r.py) : zero));
            }
        } catch (const SolverError&) {
            pp.setConstant(kInf);   // a singular dynamic stiffness: an undamped resonance
        }
        return pp;
    };
    c.curves.resize(ns, nl);
    for (std::size_t i = 0; i < ns; ++i) {
        throw_if_interrupted();
        c.curves.row(i) = orbits(s.response_speeds[i]).transpose();
    }
    c.amplitudes.assign(nl, {});
    // A1: the probes' largest refined peak near the critical speed of concern.
    const double window = kApiPeakWindow * c.concern;
    bool near = false;
    c.a1 = 0.0;
    for (std::size_t k = 0; k < nl; ++k) {
        ApiAmplitude& a = c.amplitudes[k];
        for (std::size_t i = 0; i < ns; ++i)
            if (!(c.curves(i, k) <= a.peak_to_peak)) a.peak_to_peak = c.curves(i, k), a.speed = s.response_speeds[i];
        for (std::size_t i = 1; i + 1 < ns; ++i) {
            const double v = c.curves(i, k);
            if (!(v > c.curves(i - 1, k) && v >= c.curves(i + 1, k)) || !std::isfinite(v)) continue;
            const auto f = [&](double w) { return -orbits(w)(k); };
            const double w = find_smooth_minimum(f, s.response_speeds[i - 1], s.response_speeds[i],
                                                 s.response_speeds[i + 1]);
            const double peak = -f(w);
            if (!(peak <= a.peak_to_peak)) a.peak_to_peak = peak, a.speed = w;
            if (s.locations[k].probe && std::fabs(w - c.concern) <= window) {
                near = true;
                if (!(peak <= c.a1)) c.a1 = peak;
            }
        }
    }
    // No probe peaks there (a heavily damped mode, or one beyond the trip speed): the
    // readings at the critical speed itself.
    if (!near) {
        const Eigen::VectorXd at = orbits(c.concern);
        for (std::size_t k = 0; k < nl; ++k)
            if (s.locations[k].probe && !(at(k) <= c.a1)) c.a1 = at(k);
    }
}

// Each critical speed's margins, and the critical speed of concern (docs/api_unbalance.md).
void margins(const ApiUnbalanceStudy& s, ApiUnbalanceCase& c) {
    const SpeedUnit& u = s.unit;
    const auto speed = [&](double w) { return fmt::format("{:.6g} {}", u.factor * w, u.name); };
    std::vector<std::string>& why = c.reasons;
    for (ApiCritical& k : c.criticals) {
        k.margin = separation_margin(k.critical.speed, s.min_speed, s.mcs);
        k.required = api684_required_margin(k.critical.amplification, k.margin.side == SeparationMargin::Side::above);
        k.met = k.required == 0.0 || (k.margin.side != SeparationMargin::Side::inside && k.margin.percent >= k.required);
        if (!k.met) {
            c.margins_met = false;
            why.push_back(k.margin.side == SeparationMargin::Side::inside
                              ? fmt::format("the critical speed {} (AF {:.3g}) lies in the operating range",
                                            speed(k.critical.speed), k.critical.amplification)
                              : fmt::format("the critical speed {} (AF {:.3g}) is {:.3g} % {} the operating range; it "
                                            "needs {:.3g} %",
                                            speed(k.critical.speed), k.critical.amplification, k.margin.percent,
                                            to_string(k.margin.side), k.required));
        }
    }
    // The critical speed of concern: the first whose margin is not met, else the one of
    // the largest AF.
    const ApiCritical* concern = &c.criticals.front();
    for (const ApiCritical& k : c.criticals)
        if (concern->met && (!k.met || k.critical.amplification > concern->critical.amplification)) concern = &k;
    c.concern = concern->critical.speed;
}

// Avl at the operating speed nearest the critical speed of concern, Scc, the clearance
// check and the verdict of a case (docs/api_unbalance.md).
void judge(ApiUnbalanceStudy& s, ApiUnbalanceCase& c) {
    const SpeedUnit& u = s.unit;
    const auto speed = [&](double w) { return fmt::format("{:.6g} {}", u.factor * w, u.name); };
    std::vector<std::string>& why = c.reasons;
    c.avl = api_allowable_vibration(std::clamp(c.concern, s.min_speed, s.mcs));
    c.scale = api_scale_factor(c.avl, c.a1);
    bool any_clearance = false, clear = true;
    for (std::size_t k = 0; k < s.locations.size(); ++k) {
        ApiAmplitude& a = c.amplitudes[k];
        const ApiLocation& l = s.locations[k];
        if (l.probe) {
            a.limit = c.avl;
            a.scaled = a.peak_to_peak;
        } else {
            any_clearance = true;
            a.limit = kApiClearanceFraction * l.clearance;
            a.scaled = c.margins_met ? a.peak_to_peak : c.scale * a.peak_to_peak;
        }
        a.ratio = a.scaled / a.limit;
        if (!l.probe && !(a.ratio <= 1.0)) {
            clear = false;
            why.push_back(fmt::format("{}: {}{:.4g} um peak-to-peak at {} exceeds 75 % of the clearance, {:.4g} um",
                                      l.name, c.margins_met ? "" : fmt::format("Scc {:.3g} x ", c.scale),
                                      a.peak_to_peak * 1e6, speed(a.speed), a.limit * 1e6));
        }
    }
    if (!any_clearance) {
        c.verdict = c.margins_met ? ApiVerdict::not_judged : ApiVerdict::fail;
        why.push_back("no close clearance is given ([[api.clearance]] entries, or fluid-film bearings): the clearance "
                      "check is not made");
    } else if (!clear) {
        c.verdict = ApiVerdict::fail;
    } else if (c.margins_met) {
        c.verdict = ApiVerdict::pass;
        why.push_back("every critical speed has its separation margin (or needs none) and every close clearance keeps "
                      "its orbit below 75 %");
    } else {
        c.verdict = ApiVerdict::pass_scaled;
        why.push_back(fmt::format("the orbits scaled by Scc = {:.3g} stay below 75 % of every close clearance: "
                                  "acceptable where the purchaser agrees (API 617 2.6.2.10)",
                                  c.scale));
    }
}

ApiVerdict worst(ApiVerdict a, ApiVerdict b) {
    const auto rank = [](ApiVerdict v) {
        switch (v) {
            case ApiVerdict::fail: return 3;
            case ApiVerdict::not_judged: return 2;
            case ApiVerdict::pass_scaled: return 1;
            default: return 0;
        }
    };
    return rank(a) >= rank(b) ? a : b;
}

}  // namespace

ApiUnbalanceStudy api_unbalance_study(const Scene& sc, const ApiUnbalanceRequest& r) {
    if (!sc.rotor_model() || !sc.fe_rotor())
        throw InputError(fmt::format("{}: the API unbalance cases need an FE rotor (its nodes, bearings and weight); "
                                     "this [model] is of type {}; allowed: fe_rotor",
                                     sc.path, sc.model_type()));
    ApiUnbalanceStudy s;
    s.unit = resolve_unit(sc, r.unit);
    s.length_unit = sc.length_unit();
    speeds_of(sc, r, s);
    const int count = r.speeds.value_or(kApiResponseSpeeds);
    if (count < 11 || count > 100000)
        throw InputError(fmt::format("{} {}: allowed: [11, 100000]", option_field("speeds"), count));
    locations_of(sc, s);
    const std::pair<double, double> span = bearing_span(*sc.rotor_model(), sc.path);

    // The critical speeds from 0 to the highest speed sought, on the scene's solver.
    StudyOptions opt = study_options(sc);
    opt.unit = s.unit;
    opt.harmonics = {1};
    opt.amplification_factors = false;
    opt.speeds.clear();
    for (int i = 0; i < count; ++i) opt.speeds.push_back(s.search_to * i / (count - 1));
    for (const double w : opt.speeds)
        if (w <= s.trip_speed) s.response_speeds.push_back(w);
    if (s.response_speeds.back() < s.trip_speed) s.response_speeds.push_back(s.trip_speed);
    CriticalSpeedStudy cs = critical_speed_study(sc.system, opt);
    for (const Diagnostic& d : cs.tracked.diagnostics) s.diagnostics.push_back(d);
    // An unstable mode below the trip speed: the steady response there is no state the
    // rotor reaches, and no case can pass.
    for (const UnstableRange& u : cs.tracked.unstable)
        if (u.from <= s.trip_speed)
            s.reasons.push_back(fmt::format("mode {} is unstable {}: the unbalance response there is no steady state",
                                            u.branch, unstable_span(u, s.unit)));
    std::vector<CriticalSpeed> all;
    for (const CriticalSpeed& c : cs.critical)
        if (c.harmonic == 1 && c.speed > 0) all.push_back(c);
    if (all.empty()) {
        s.verdict = s.reasons.empty() ? ApiVerdict::pass : ApiVerdict::fail;
        s.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict,
                                 fmt::format("no critical speed from 0 to {:.6g} {}: no API unbalance case",
                                             s.unit.factor * s.search_to, s.unit.name)});
        return s;
    }

    // One case per placement: the critical speeds whose shapes place the unbalance alike.
    const ShaftNodes nodes = shaft_nodes(sc.system);
    const Weights weights = weights_of(sc);
    // Overhung where a disk lies outboard of the bearing span.
    bool below = false, above = false;
    const double tol = 1e-9 * std::max(1.0, span.second - span.first);
    for (const FeDisk& d : sc.fe_rotor()->disks) {
        const double zd = sc.system.node_z.at(static_cast<std::size_t>(d.node));
        below = below || zd < span.first - tol;
        above = above || zd > span.second + tol;
    }
    std::map<std::vector<std::pair<int, double>>, std::size_t> case_of;
    std::vector<std::vector<std::size_t>> members;
    for (std::size_t j = 0; j < all.size(); ++j) {
        const Eigen::VectorXcd& v = all[j].mode.right;
        Eigen::VectorXcd zx(static_cast<Eigen::Index>(nodes.nodes.size())), zy(zx.size());
        for (std::size_t k = 0; k < nodes.nodes.size(); ++k) zx(k) = v(nodes.x[k]), zy(k) = v(nodes.y[k]);
        const UnbalancePlacement p = api_unbalance_placement(nodes.z, zx, zy, span.first, span.second, below, above);
        std::vector<std::pair<int, double>> key;
        for (const UnbalancePoint& pt : p.points) key.emplace_back(pt.index, pt.phase);
        const auto [it, fresh] = case_of.emplace(key, s.cases.size());
        if (fresh) {
            ApiUnbalanceCase c;
            c.placement = p;
            c.loads = loads_of(sc, s, p, nodes, weights);
            s.cases.push_back(c);
            members.emplace_back();
        }
        members[it->second].push_back(j);
    }
    for (std::size_t i = 0; i < s.cases.size(); ++i) {
        ApiUnbalanceCase& c = s.cases[i];
        const GyroscopicSystem sys = with_unbalance(sc.system, c.loads);
        for (const std::size_t j : members[i]) {
            std::vector<CriticalSpeed> af = all;
            set_amplification_factors(af, sys, j);
            c.criticals.push_back({af[j], {}, 0.0, true});
        }
        margins(s, c);
        respond(sys, s, c);
        judge(s, c);
        s.verdict = i == 0 ? c.verdict : worst(s.verdict, c.verdict);
    }
    if (!s.reasons.empty()) s.verdict = ApiVerdict::fail;
    return s;
}

}  // namespace gyrokit
