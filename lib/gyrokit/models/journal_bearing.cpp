#include <gyrokit/models/journal_bearing.hpp>

#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/constants.hpp>
#include <gyrokit/models/reynolds_bearing.hpp>
#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

// eta R L^3 / (4 W c^2): S_s per unit speed.
double sommerfeld_per_speed(const JournalBearing& b) {
    return b.viscosity * 0.5 * b.diameter * std::pow(b.length, 3) / (4.0 * b.load * b.clearance * b.clearance);
}

// A band given in pairs around its nominal value: lo <= nominal <= hi, both > 0.
void validate_band(const std::string& origin, const char* key, double nominal, const std::optional<double>& lo,
                   const std::optional<double>& hi, double scale, const char* unit) {
    const std::string min_key = std::string(key) + "_min", max_key = std::string(key) + "_max";
    if (lo.has_value() != hi.has_value())
        throw InputError(fmt::format("{}: {} is given without {}; allowed: both ends of the band or neither", origin,
                                     lo ? min_key : max_key, lo ? max_key : min_key));
    if (!lo) return;
    if (!(std::isfinite(*lo) && std::isfinite(*hi) && *lo > 0.0 && *lo <= nominal && nominal <= *hi))
        throw InputError(fmt::format("{}: {} = {}, {} = {}, {} = {} ({}); allowed: 0 < {} <= {} <= {}", origin,
                                     min_key, *lo / scale, key, nominal / scale, max_key, *hi / scale, unit, min_key,
                                     key, max_key));
}

}  // namespace

const char* to_string(FilmExtreme e) {
    return e == FilmExtreme::minimum_clearance ? "minimum clearance" : "maximum clearance";
}

bool has_extremes(const JournalBearing& b) {
    return b.clearance_min || b.clearance_max || b.viscosity_min || b.viscosity_max;
}

JournalBearing film_extreme(const JournalBearing& b, FilmExtreme e) {
    JournalBearing j = b;
    const bool tight = e == FilmExtreme::minimum_clearance;
    j.clearance = (tight ? b.clearance_min : b.clearance_max).value_or(b.clearance);
    j.viscosity = (tight ? b.viscosity_max : b.viscosity_min).value_or(b.viscosity);
    j.clearance_min = j.clearance_max = j.viscosity_min = j.viscosity_max = std::nullopt;
    return j;
}

void JournalBearing::validate(const std::string& origin, double metres_per_unit, const char* unit) const {
    const auto positive = [&](const char* key, double v, double scale, const char* u) {
        if (!(v > 0.0) || !std::isfinite(v))
            throw InputError(fmt::format("{}: {} = {}; allowed: a finite number > 0 ({})", origin, key, v / scale, u));
    };
    const double mu = metres_per_unit;
    positive("diameter", diameter, mu, unit);
    positive("length", length, mu, unit);
    positive("clearance", clearance, mu, unit);
    positive("viscosity", viscosity, 1.0, "Pa s");
    positive("load", load, 1.0, "N");
    if (!(clearance < 0.5 * diameter))
        throw InputError(fmt::format("{}: clearance = {} {} with diameter = {} {}; allowed: 0 < clearance < diameter / 2",
                                     origin, clearance / mu, unit, diameter / mu, unit));
    if (!(std::fabs(load_angle) <= 2.0 * kPi))
        throw InputError(fmt::format("{}: load_angle = {} rad; allowed: -360 to 360 deg", origin, load_angle));
    if (!(max_eccentricity >= 0.01 && max_eccentricity <= 0.999))
        throw InputError(fmt::format("{}: max_eccentricity = {}; allowed: 0.01 to 0.999", origin, max_eccentricity));
    if (solution != FilmSolution::short_bearing && solution != FilmSolution::finite_difference)
        throw InputError(fmt::format("{}: solution = {}; allowed: short, finite_difference", origin,
                                     static_cast<int>(solution)));
    if (grid_circumferential < 16 || grid_circumferential > 2880 || grid_circumferential % 2 != 0)
        throw InputError(fmt::format("{}: grid_circumferential = {}; allowed: an even number from 16 to 2880", origin,
                                     grid_circumferential));
    if (grid_axial < 4 || grid_axial > 256 || grid_axial % 4 != 0)
        throw InputError(
            fmt::format("{}: grid_axial = {}; allowed: a multiple of 4 from 4 to 256", origin, grid_axial));
    // The film's scales must be numbers: S_s per unit speed, the speed where max_eccentricity is
    // reached, and the stiffness and damping scales W/c, W/(c w) there.
    const double per_speed = sommerfeld_per_speed(*this), w_min = short_bearing_sommerfeld(max_eccentricity) / per_speed;
    const double k_scale = load / clearance, c_scale = k_scale / w_min;
    for (const double v : {per_speed, w_min, k_scale, c_scale})
        if (!(std::isfinite(v) && v > 0.0 && v < 1e200 && v > 1e-200))
            throw InputError(fmt::format("{}: diameter = {} {}, length = {} {}, clearance = {} {}, viscosity = {} "
                                         "Pa s, load = {} N give no usable film (Sommerfeld number per rad/s {:g}, "
                                         "film stiffness scale {:g} N/m); allowed: values of a real bearing",
                                         origin, diameter / mu, unit, length / mu, unit, clearance / mu, unit, viscosity,
                                         load, per_speed, k_scale));
    validate_band(origin, "clearance", clearance, clearance_min, clearance_max, mu, unit);
    validate_band(origin, "viscosity", viscosity, viscosity_min, viscosity_max, 1.0, "Pa s");
    if (clearance_max && !(*clearance_max < 0.5 * diameter))
        throw InputError(fmt::format("{}: clearance_max = {} {} with diameter = {} {}; allowed: clearance_max < "
                                     "diameter / 2",
                                     origin, *clearance_max / mu, unit, diameter / mu, unit));
    // Each end must itself be a usable film (clearance_max below D / 2, its scales numbers).
    if (has_extremes(*this))
        for (const FilmExtreme e : {FilmExtreme::minimum_clearance, FilmExtreme::maximum_clearance})
            film_extreme(*this, e).validate(fmt::format("{} at its {}", origin, to_string(e)), mu, unit);
}

double short_bearing_sommerfeld(double e) {
    const double s = 1.0 - e * e;
    return s * s / (e * std::sqrt(16.0 * e * e + kPi * kPi * s));
}

double journal_bearing_speed_at(const JournalBearing& b, double e) {
    return short_bearing_sommerfeld(e) / sommerfeld_per_speed(b);
}

JournalBearingState short_bearing(const JournalBearing& b, double w) {
    JournalBearingState st;
    st.sommerfeld = sommerfeld_per_speed(b) * w;
    // S_s falls monotonically from infinity (e -> 0) to 0 (e -> 1): one root, in logarithms
    // so that both ends keep their digits.
    const double target = std::log(st.sommerfeld);
    const auto f = [&](double e) { return std::log(short_bearing_sommerfeld(e)) - target; };
    const double lo = 1e-300, hi = 1.0 - 1e-12;
    if (!(w > 0.0) || !std::isfinite(target) || f(hi) > 0.0 || f(lo) < 0.0)
        throw InputError(fmt::format("fluid-film bearing at {} rad/s: Sommerfeld number {} outside the range the "
                                     "short-bearing solution covers (eccentricity 1e-300 to 1 - 1e-12)",
                                     w, st.sommerfeld));
    const double e = find_root(f, lo, hi, 1e-15);
    st.eccentricity = e;
    const double s = 1.0 - e * e, rs = std::sqrt(s), pi2 = kPi * kPi;
    st.attitude_angle = std::atan2(kPi * rs, 4.0 * e);
    const double h0 = 1.0 / std::pow(pi2 * s + 16.0 * e * e, 1.5);
    st.a << h0 * 4.0 * (pi2 * (2.0 - e * e) + 16.0 * e * e),
        h0 * kPi * (pi2 * s * s - 16.0 * std::pow(e, 4)) / (e * rs),
        -h0 * kPi * (pi2 * s * (1.0 + 2.0 * e * e) + 32.0 * e * e * (1.0 + e * e)) / (e * rs),
        h0 * 4.0 * (pi2 * (1.0 + 2.0 * e * e) + 32.0 * e * e * (1.0 + e * e) / s);
    const double buv = -h0 * 8.0 * (pi2 * (1.0 + 2.0 * e * e) - 16.0 * e * e);
    st.b << h0 * 2.0 * kPi * rs * (pi2 * (1.0 + 2.0 * e * e) - 16.0 * e * e) / e, buv,
        buv, h0 * 2.0 * kPi * (pi2 * s * s + 48.0 * e * e) / (e * rs);
    st.coefficients = journal_bearing_coefficients(b, w, st.a, st.b);
    return st;
}

BearingCoefficients journal_bearing_coefficients(const JournalBearing& bearing, double w, const Eigen::Matrix2d& a,
                                                 const Eigen::Matrix2d& b) {
    // The closed forms hold in axes (u, v) where the load acts along -v and the spin
    // turns u into v (for a load along -y: u = x, v = y). (u, v) = T (x, y), K_xy = T^T K_uv T.
    const double ca = std::cos(bearing.load_angle), sa = std::sin(bearing.load_angle);
    Eigen::Matrix2d T;
    T << -sa, ca, -ca, -sa;
    const double kscale = bearing.load / bearing.clearance, cscale = bearing.load / (bearing.clearance * w);
    BearingCoefficients c;
    c.K = T.transpose() * (kscale * a) * T;
    c.C = T.transpose() * (cscale * b) * T;
    return c;
}

BearingTable journal_bearing_table(const JournalBearing& b, const std::string& name, int dof_x, int dof_y) {
    b.validate(name);
    BearingTable t;
    t.name = name;
    t.dof_x = dof_x;
    t.dof_y = dof_y;
    const bool fd = b.solution == FilmSolution::finite_difference;
    try {
        t.speeds = {fd ? reynolds_bearing_speed_at(b, b.max_eccentricity)
                       : journal_bearing_speed_at(b, b.max_eccentricity)};
    } catch (const Error& e) {
        throw SolverError(fmt::format("bearing {}: {}", name, e.what()));
    }
    t.model = [b, name, fd](double w) {
        try {
            return fd ? reynolds_bearing(b, w).coefficients : short_bearing(b, w).coefficients;
        } catch (const Error& e) {
            throw SolverError(fmt::format("bearing {}: {}", name, e.what()));
        }
    };
    return t;
}

}  // namespace gyrokit
