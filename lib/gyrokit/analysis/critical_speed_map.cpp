#include <gyrokit/analysis/critical_speed_map.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/mode.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

// The model with every bearing an isotropic spring k and no damping anywhere.
RotorModel undamped_on_springs(const RotorModel& model, double k) {
    RotorModel m = model;
    m.motion = FeMotion::lateral;   // the map is of the lateral critical speeds
    for (RotorBearing& b : m.bearings) {
        const double kzz = b.kind == RotorBearing::Kind::constant ? b.constant.kzz : 0.0;
        b.kind = RotorBearing::Kind::constant;
        b.constant = FeBearing{};
        b.constant.kxx = b.constant.kyy = k;
        b.constant.kzz = kzz;
        b.auto_load = false;
    }
    for (RotorPedestal& p : m.pedestals) p.pedestal.cxx = p.pedestal.cyy = 0.0;
    for (RotorSection& s : m.sections)
        if (s.shape.coupling) {
            FeCoupling& c = *s.shape.coupling;
            c.c_lateral = c.c_bending = c.c_axial = c.c_torsion = 0.0;
        }
    return m;
}

// The bearings as rigid supports: pinned at each bearing's position.
RotorModel on_rigid_supports(const RotorModel& model) {
    RotorModel m = undamped_on_springs(model, 0.0);
    for (const RotorBearing& b : model.bearings) {
        RotorSupport s;
        s.z = b.z;
        s.origin = b.origin;
        m.supports.push_back(s);
    }
    m.bearings.clear();
    m.pedestals.clear();   // a rigid support holds the shaft itself
    return m;
}

// The synchronous critical speeds of an undamped rotor, `modes` of each whirl.
std::vector<MapPoint> synchronous_criticals(const RotorModel& model, double k, int modes) {
    const GyroscopicSystem sys = build(model).system;
    const Eigen::MatrixXd M(sys.M), K(sys.K);
    const Eigen::MatrixXd G = sys.G.size() ? Eigen::MatrixXd(sys.G) : Eigen::MatrixXd::Zero(M.rows(), M.cols());
    const std::complex<double> I(0.0, 1.0);
    const Eigen::MatrixXcd A = M.cast<std::complex<double>>() - I * G.cast<std::complex<double>>();
    const Eigen::MatrixXcd B = K.cast<std::complex<double>>();
    // The solver factors K by Cholesky without telling when it fails: check it first.
    const Eigen::LLT<Eigen::MatrixXd> held(K);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> es;
    if (held.info() == Eigen::Success) es.compute(A, B, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (held.info() != Eigen::Success || es.info() != Eigen::Success || !es.eigenvalues().allFinite())
        throw InputError(fmt::format("critical speed map: at bearing stiffness {:.6g} N/m the rotor is not held (its "
                                     "stiffness matrix is not positive definite); allowed: bearings or supports that "
                                     "hold it in both planes",
                                     k));
    const QuadraticPencil pencil{M, Eigen::MatrixXd::Zero(M.rows(), M.cols()), K};
    std::vector<MapPoint> found;
    // The largest nu = 1 / w^2 first: the lowest speeds.
    for (Eigen::Index j = es.eigenvalues().size() - 1; j >= 0; --j) {
        const double nu = es.eigenvalues()(j);
        if (!(nu > 0.0)) break;   // gyroscopically stiffened: never meets the 1x line
        const double w = 1.0 / std::sqrt(nu);
        const Eigen::VectorXcd x = es.eigenvectors().col(j).normalized();
        const Whirl whirl = classify_whirl(I * w, x, sys.whirl_pairs, 0.0);
        if (whirl == Whirl::None) continue;   // axial or torsional: not a whirl
        QuadraticPencil at = pencil;
        at.C = w * G;
        MapPoint p{k, 0, to_string(whirl), w, backward_error(at, I * w, x)};
        const int same = static_cast<int>(std::count_if(found.begin(), found.end(), [&](const MapPoint& q) {
            return q.whirl == p.whirl;
        }));
        if (same >= modes) continue;
        p.number = same + 1;
        found.push_back(p);
    }
    std::stable_sort(found.begin(), found.end(), [](const MapPoint& a, const MapPoint& b) {
        return a.whirl != b.whirl ? a.whirl > b.whirl : a.number < b.number;   // forward first
    });
    return found;
}

// The bearings' own stiffness: constant ones at kxx and kyy over the map's span of
// speeds, tables and fluid films over speed.
std::vector<BearingCurve> bearing_curves(const RotorModel& model, double top_speed) {
    std::vector<BearingCurve> out;
    const GyroscopicSystem sys = build(model).system;
    const BearingNumbers numbers = bearing_numbers(model);
    for (std::size_t i = 0; i < model.bearings.size(); ++i) {
        const RotorBearing& b = model.bearings[i];
        if (b.kind != RotorBearing::Kind::constant) continue;
        const std::string name = bearing_name(static_cast<int>(i) + 1);
        out.push_back({"kxx " + name, {b.constant.kxx, b.constant.kxx}, {0.0, top_speed}});
        if (b.constant.kyy != b.constant.kxx) out.push_back({"kyy " + name, {b.constant.kyy, b.constant.kyy}, {0.0, top_speed}});
    }
    for (std::size_t j = 0; j < sys.bearings.size(); ++j) {
        const BearingTable& t = sys.bearings[j];
        const std::string name = bearing_name(numbers.speed_dependent.at(j));
        BearingCurve kxx{"kxx " + name, {}, {}}, kyy{"kyy " + name, {}, {}};
        const double from = t.speeds.front(), to = t.model ? std::max(top_speed, from) : t.speeds.back();
        for (int s = 0; s <= 60; ++s) {
            const double w = from + (to - from) * s / 60.0;
            const BearingCoefficients c = t.at(w);
            kxx.stiffness.push_back(c.K(0, 0)), kxx.speed.push_back(w);
            kyy.stiffness.push_back(c.K(1, 1)), kyy.speed.push_back(w);
        }
        out.push_back(kxx);
        out.push_back(kyy);
    }
    return out;
}

}  // namespace

std::vector<double> default_map_stiffness(const RotorModel& model) {
    double length = 0.0, EI = 0.0;
    for (const RotorSection& s : model.sections) {
        length += s.shape.length;
        if (!s.shape.coupling) EI += s.shape.length * s.shape.youngs_modulus * fe_section(s.shape).second_moment;
    }
    if (!(length > 0.0 && EI > 0.0))
        throw InputError("critical speed map: the shaft has no beam section; allowed: a rotor with shaft sections");
    EI /= length;
    const double k_shaft = 48.0 * EI / (length * length * length);
    std::vector<double> k;
    const double from = std::log10(kMapStiffnessFrom), to = std::log10(kMapStiffnessTo);
    for (int i = 0; i < kMapStiffnessPoints; ++i)
        k.push_back(k_shaft * std::pow(10.0, from + (to - from) * i / (kMapStiffnessPoints - 1)));
    return k;
}

CriticalSpeedMap critical_speed_map(const RotorModel& model, const CriticalSpeedMapOptions& o) {
    if (model.bearings.empty())
        throw InputError("critical speed map: the model has no bearings; allowed: a rotor on bearings (the map varies "
                         "their stiffness)");
    if (o.modes < 1) throw InputError(fmt::format("critical speed map: modes = {}; allowed: >= 1", o.modes));
    if (model.motion == FeMotion::axial || model.motion == FeMotion::torsional)
        throw InputError(fmt::format("critical speed map: the model's motion is {}; allowed: lateral or all",
                                     to_string(model.motion)));
    CriticalSpeedMap map;
    map.stiffness = o.stiffness.empty() ? default_map_stiffness(model) : o.stiffness;
    for (std::size_t i = 0; i < map.stiffness.size(); ++i)
        if (!(std::isfinite(map.stiffness[i]) && map.stiffness[i] > 0 && (i == 0 || map.stiffness[i] > map.stiffness[i - 1])))
            throw InputError(fmt::format("critical speed map: stiffness entry {} = {}; allowed: finite numbers > 0 "
                                         "(N/m), increasing",
                                         i, map.stiffness[i]));
    for (const double k : map.stiffness)
        for (const MapPoint& p : synchronous_criticals(undamped_on_springs(model, k), k, o.modes))
            map.points.push_back(p);
    map.rigid = synchronous_criticals(on_rigid_supports(model), std::numeric_limits<double>::infinity(), o.modes);
    double top = 0.0;
    for (const auto* list : {&map.points, &map.rigid})
        for (const MapPoint& p : *list) {
            top = std::max(top, p.speed);
            map.max_backward_error = std::max(map.max_backward_error, p.backward_error);
        }
    map.bearings = bearing_curves(model, 1.2 * top);
    return map;
}

}  // namespace gyrokit
