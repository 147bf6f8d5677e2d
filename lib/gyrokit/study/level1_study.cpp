#include <gyrokit/study/level1_study.hpp>

#include <gyrokit/analysis/critical_speed_map.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/models/rotor_model.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace gyrokit {

namespace {

// The scene's [api] with the request's values on top, validated.
ApiMachine machine_of(const Scene& sc, const Level1Request& r, const SpeedUnit& u) {
    ApiMachine m = sc.api ? *sc.api : ApiMachine{};
    if (m.origin.empty()) m.origin = sc.path + ": [api]";
    if (r.machine) {
        if (*r.machine != "centrifugal" && *r.machine != "axial")
            throw InputError(fmt::format("{} '{}': allowed: centrifugal, axial", option_field("machine"), *r.machine));
        m.kind = *r.machine == "axial" ? MachineKind::axial : MachineKind::centrifugal;
    }
    if (r.mcs) m.mcs = to_rad_s(*r.mcs, "mcs", "speed", u, true);
    if (r.operating_speed) m.operating_speed = to_rad_s(*r.operating_speed, "operating_speed", "speed", u, true);
    if (r.qa) {
        if (!(std::isfinite(*r.qa) && *r.qa > 0))
            throw InputError(fmt::format("{} {}: allowed: a finite stiffness > 0 (N/m)", option_field("qa"), *r.qa));
        m.qa = *r.qa;   // in place of the stages' sum; the stages still say where Q acts
    }
    if (r.station) m.station = sc.length_unit().to_metres(*r.station);
    if (r.gas_density) {
        if (!(std::isfinite(*r.gas_density) && *r.gas_density > 0))
            throw InputError(fmt::format("{} {}: allowed: a finite density > 0 (kg/m^3)", option_field("gas_density"),
                                         *r.gas_density));
        m.gas_density = *r.gas_density;
    }
    if (r.q_ratio) {
        if (!(std::isfinite(*r.q_ratio) && *r.q_ratio >= 2 && *r.q_ratio <= 1000))
            throw InputError(fmt::format("{} {}: allowed: [2, 1000] (the Q range in multiples of QA)",
                                         option_field("q_ratio"), *r.q_ratio));
        m.q_ratio = *r.q_ratio;
    }
    if (!m.mcs)
        throw InputError(fmt::format("{}: the maximum continuous speed is missing; required: [api] mcs in the "
                                     "scene or {} (in {})",
                                     sc.path, option_field("mcs"), u.name));
    if (!m.qa && m.stages.empty())
        throw InputError(fmt::format("{}: the anticipated cross-coupling is unknown; required: [[api.stage]] "
                                     "entries (power, diameter, width, density_ratio) or [api] qa in the scene, or "
                                     "{} (N/m)",
                                     sc.path, option_field("qa")));
    validate(m);
    return m;
}

// Where Q acts, and how it is shared (docs/level1.md, "Where Q acts").
void place_stations(const Scene& sc, Level1Screen& s) {
    const GyroscopicSystem& sys = sc.system;
    const LengthUnit lu = sc.length_unit();
    const std::pair<double, double> span = bearing_span(*sc.rotor_model(), sc.path);
    const double z0 = span.first, z1 = span.second;   // named: a lambda captures them (C++17)
    const double tol = 1e-9 * std::max(1.0, std::fabs(z1 - z0));
    const bool overhung = std::any_of(s.machine.stages.begin(), s.machine.stages.end(),
                                      [&](const AeroStage& a) { return a.z < z0 - tol || a.z > z1 + tol; });
    // The node at z, an error naming the key that placed it.
    const auto node_at = [&](double z, const std::string& key) {
        int node = -1;
        try {
            node = sys.nearest_node(z, lu);
        } catch (const InputError& e) {
            throw InputError(fmt::format("{}: {} = {} {}: {}", sc.path, key, lu.in_unit(z), lu.name, e.what()));
        }
        if (sys.dofs.find(node, DofMotion::x) < 0 || sys.dofs.find(node, DofMotion::y) < 0)
            throw InputError(fmt::format("{}: {} = {} {}: its node {} does not move laterally (a rigid support holds "
                                         "it, or the model has no lateral DOFs); allowed: a position whose node has x "
                                         "and y",
                                         sc.path, key, lu.in_unit(z), lu.name, node));
        return node;
    };
    std::map<int, double> share;
    if (s.machine.station) {
        s.layout = "station given";
        share[node_at(*s.machine.station, option_field("station"))] = 1.0;
    } else if (!overhung) {
        s.layout = "between bearings";
        share[node_at(0.5 * (z0 + z1), "the middle of the bearing span")] = 1.0;
        if (s.machine.stages.empty())
            s.diagnostics.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict,
                                     "no stage is given: Q acts at the middle of the bearing span (a between-bearings "
                                     "rotor); an overhung rotor names its stages or " + option_field("station")});
    } else {
        s.layout = "overhung";
        double sum = 0.0;
        for (const double q : s.stage_qa) sum += q;
        for (std::size_t i = 0; i < s.machine.stages.size(); ++i)
            share[node_at(s.machine.stages[i].z, fmt::format("the z of stage {}", i))] += s.stage_qa[i] / sum;
    }
    for (const auto& [node, w] : share) {
        s.stations.push_back({node, w});
        s.station_z.push_back(sys.node_z.at(node));
    }
    // The shares sum to 1 up to rounding: make it exact, as level1_curve checks.
    double sum = 0.0;
    for (const CrossCouplingStation& c : s.stations) sum += c.share;
    for (CrossCouplingStation& c : s.stations) c.share /= sum;
}

// The first forward critical speed on rigid supports, and the critical speed ratio.
void critical_speed_ratio(const Scene& sc, Level1Screen& s) {
    try {
        CriticalSpeedMapOptions o;
        o.stiffness = {1e6};
        o.modes = 1;
        const CriticalSpeedMap map = critical_speed_map(*sc.rotor_model(), o);
        for (const MapPoint& p : map.rigid)
            if (p.whirl == "forward" && (!s.rigid_critical || p.speed < *s.rigid_critical)) s.rigid_critical = p.speed;
    } catch (const Error& e) {
        s.diagnostics.push_back({Diagnostic::Level::Warning, Diagnostic::Topic::Verdict,
                                 std::string("no critical speed on rigid supports: ") + e.what()});
    }
    if (s.rigid_critical) s.csr = *s.machine.mcs / *s.rigid_critical;
    if (s.machine.gas_density) s.region_boundary = region_b_boundary(*s.machine.gas_density);
}

std::string ratio_text(const Level1Screen& s) {
    return s.curve.q0 ? fmt::format("Q0/QA = {:.3g}", *s.curve.q0 / s.qa)
                      : fmt::format("Q0/QA > {:.3g} (the log decrement stays positive up to {:.3g} QA)",
                                    s.machine.q_ratio, s.machine.q_ratio);
}

// API 617's Level I criteria (docs/level1.md, "The verdict").
void verdict(Level1Screen& s) {
    std::vector<std::string>& why = s.reasons;
    const bool centrifugal = s.machine.kind == MachineKind::centrifugal;
    const std::optional<double> ratio = s.curve.q0 ? std::optional<double>(*s.curve.q0 / s.qa) : std::nullopt;
    if (s.curve.q0 && *s.curve.q0 == 0.0)
        why.push_back("the first forward mode is not stable at Q = 0 (Q0 = 0)");
    else if (ratio && *ratio < kLevel1MinRatio)
        why.push_back(fmt::format("{} < {}", ratio_text(s), kLevel1MinRatio));
    if (s.at_qa.log_decrement < kLevel1MinLogDecrement)
        why.push_back(fmt::format("the log decrement at QA, {:.3g}, is below {}", s.at_qa.log_decrement,
                                  kLevel1MinLogDecrement));
    // A lower forward mode Q does not load keeps its damping at QA (to first order): it
    // must meet the same floor (unstable or neutral at Q = 0 included).
    for (const PassedMode& m : s.curve.passed)
        if (m.lambda.real() >= -m.error_bound || m.log_decrement < kLevel1MinLogDecrement)
            why.push_back(fmt::format("the forward mode at {:.6g} {}, passed over (Q does not load it), has a log "
                                      "decrement of {:.3g} at Q = 0 and so at QA, below {}",
                                      s.unit.factor * m.lambda.imag(), s.unit.name, m.log_decrement,
                                      kLevel1MinLogDecrement));
    // Without Q0 in the range, a range below 10 QA leaves the ratio possibly below 10.
    const bool below_ten = ratio ? *ratio < kLevel1RegionRatio : s.machine.q_ratio < kLevel1RegionRatio;
    const char* lies = ratio ? "lies" : "may lie";
    if (centrifugal && below_ten && !(ratio && *ratio < kLevel1MinRatio) && !(s.curve.q0 && *s.curve.q0 == 0.0)) {
        if (!s.region_boundary)
            why.push_back(fmt::format("{} {} in [{}, {}) and the region of the critical speed ratio is unknown: "
                                      "give the average gas density ({})",
                                      ratio_text(s), lies, kLevel1MinRatio, kLevel1RegionRatio,
                                      option_field("gas_density")));
        else if (!s.csr)
            why.push_back(fmt::format("{} {} in [{}, {}) and the critical speed ratio is unknown (no critical speed "
                                      "on rigid supports)",
                                      ratio_text(s), lies, kLevel1MinRatio, kLevel1RegionRatio));
        else if (*s.csr > *s.region_boundary)
            why.push_back(fmt::format("{} {} in [{}, {}) and the critical speed ratio {:.3g} lies in region B "
                                      "(above {:.3g} at {:.3g} kg/m^3)",
                                      ratio_text(s), lies, kLevel1MinRatio, kLevel1RegionRatio, *s.csr,
                                      *s.region_boundary, *s.machine.gas_density));
    }
    s.level2_required = !why.empty();
    if (!s.level2_required)
        why.push_back(fmt::format("{}, log decrement at QA {:.3g} >= {}{}", ratio_text(s), s.at_qa.log_decrement,
                                  kLevel1MinLogDecrement,
                                  centrifugal && below_ten ? fmt::format(", critical speed ratio {:.3g} in region A",
                                                                         s.csr.value_or(0.0))
                                                           : std::string()));
}

// The curve on one bearing set's system and its verdict; `s` holds what the sets share.
// The screen's own notes go to `own` (and to s.diagnostics after the shared ones).
void screen(const GyroscopicSystem& sys, const Level1Request& r, const SolverOptions& solver, Level1Screen& s,
            Diagnostics& own) {
    Level1Options o;
    o.stations = s.stations;
    o.speed = *s.machine.mcs;
    o.q_max = s.machine.q_ratio * s.qa;
    o.intervals = r.intervals.value_or(kLevel1Intervals);
    o.marks = {s.qa};
    o.solver = solver;
    if (r.method) o.solver.eig.method = parse_eigen_method(*r.method);
    s.curve = level1_curve(sys, o);
    s.at_zero = s.curve.points.front();
    const auto at = std::find_if(s.curve.points.begin(), s.curve.points.end(),
                                 [&](const Level1Point& p) { return p.q == s.qa; });
    if (at == s.curve.points.end()) throw Error("level1: QA is not on the curve");   // marks are kept exactly
    s.at_qa = *at;
    for (const PassedMode& m : s.curve.passed)
        own.push_back({Diagnostic::Level::Note, Diagnostic::Topic::Verdict, passed_text(m, s.unit)});
    add_notes(own, Diagnostic::Topic::Ambiguity, s.curve.notes);
    s.diagnostics.insert(s.diagnostics.end(), own.begin(), own.end());
    verdict(s);
}

}  // namespace

Level1Study level1_study(const Scene& sc, const Level1Request& r) {
    if (!sc.rotor_model())
        throw InputError(fmt::format("{}: Level I needs an FE rotor (its nodes and bearings); this [model] is of type "
                                     "{}; allowed: fe_rotor",
                                     sc.path, sc.model_type()));
    Level1Screen base;
    base.unit = resolve_unit(sc, r.unit);
    base.length_unit = sc.length_unit();
    base.machine = machine_of(sc, r, base.unit);
    const double n = base.machine.operating_speed.value_or(*base.machine.mcs);
    for (const AeroStage& a : base.machine.stages)
        base.stage_qa.push_back(anticipated_cross_coupling(a, base.machine.kind, n));
    for (const double q : base.stage_qa) base.qa += q;
    if (base.machine.qa) base.qa = *base.machine.qa;
    place_stations(sc, base);
    critical_speed_ratio(sc, base);   // on rigid supports: the same for every bearing set

    Level1Study study;
    study.diagnostics = base.diagnostics;
    const std::vector<BearingSet> sets = bearing_extremes(*sc.rotor_model());
    const auto run = [&](const GyroscopicSystem& sys, const std::string& name) {
        Level1Screen s = base;
        s.bearing_set = name;
        Diagnostics own;
        screen(sys, r, sc.solver, s, own);
        for (Diagnostic& d : own) {
            if (!name.empty()) d.text = name + ": " + d.text;
            study.diagnostics.push_back(d);
        }
        study.screens.push_back(std::move(s));
    };
    if (sets.empty()) run(sc.system, "");
    for (const BearingSet& set : sets) run(build(set.model).system, set.name);   // the same mesh: the nodes hold
    study.governing = governing_screen(study.screens);
    return study;
}

}  // namespace gyrokit
