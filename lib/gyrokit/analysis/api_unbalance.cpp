#include <gyrokit/analysis/api_unbalance.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

double rpm(double rad_s) { return rad_s * 60.0 / (2.0 * kPi); }

}  // namespace

double api_unbalance(double weight, double mcs) {
    if (!(std::isfinite(weight) && weight > 0) || !(std::isfinite(mcs) && mcs > 0))
        throw InputError(fmt::format("API unbalance: weight {} kg and speed {} rad/s; allowed: both finite and > 0",
                                     weight, mcs));
    return kApiUnbalanceMultiple * kApiUnbalanceConstant * weight / rpm(mcs) * 1e-6;   // g mm -> kg m
}

double api_allowable_vibration(double speed) {
    if (!(std::isfinite(speed) && speed > 0))
        throw InputError(fmt::format("API allowable vibration: speed {} rad/s; allowed: finite and > 0", speed));
    return std::min(25.4e-6, 25.4e-6 * std::sqrt(12000.0 / rpm(speed)));
}

double api_scale_factor(double allowable, double amplitude) {
    if (!(amplitude > 0) || !std::isfinite(amplitude)) return std::isfinite(amplitude) ? kApiScaleMax : kApiScaleMin;
    return std::clamp(allowable / amplitude, kApiScaleMin, kApiScaleMax);
}

double orbit_peak_to_peak(std::complex<double> zx, std::complex<double> zy) {
    const std::complex<double> i(0.0, 1.0);
    return std::abs(zx - i * zy) + std::abs(zx + i * zy);
}

const char* to_string(SeparationMargin::Side s) {
    switch (s) {
        case SeparationMargin::Side::below: return "below";
        case SeparationMargin::Side::above: return "above";
        default: return "inside";
    }
}

SeparationMargin separation_margin(double critical, double min_speed, double mcs) {
    SeparationMargin m;
    if (critical < min_speed) {
        m.side = SeparationMargin::Side::below;
        m.percent = 100.0 * (min_speed - critical) / min_speed;
    } else if (critical > mcs) {
        m.side = SeparationMargin::Side::above;
        m.percent = 100.0 * (critical - mcs) / mcs;
    }
    return m;
}

const char* to_string(UnbalanceLayout l) {
    switch (l) {
        case UnbalanceLayout::second_mode: return "second mode (two, out of phase)";
        case UnbalanceLayout::overhung: return "overhung (at the overhang)";
        default: return "first mode (mid-span)";
    }
}

UnbalancePlacement api_unbalance_placement(const std::vector<double>& z, const Eigen::VectorXcd& zx,
                                           const Eigen::VectorXcd& zy, double z0, double z1, bool overhung_below,
                                           bool overhung_above) {
    const Eigen::Index n = static_cast<Eigen::Index>(z.size());
    if (zx.size() != n || zy.size() != n || n == 0)
        throw InputError(fmt::format("API unbalance placement: {} positions, {} x and {} y deflections; allowed: as "
                                     "many of each, at least one",
                                     z.size(), zx.size(), zy.size()));
    const double tol = 1e-9 * std::max(1.0, std::fabs(z1 - z0));
    const auto inside = [&](Eigen::Index k) { return z[k] >= z0 - tol && z[k] <= z1 + tol; };
    const auto counts = [&](Eigen::Index k) {
        return inside(k) || (z[k] < z0 && overhung_below) || (z[k] > z1 && overhung_above);
    };
    // The largest orbit, and the direction (x or y) in which the shape is read.
    Eigen::Index peak = 0;
    double largest = -1.0;
    for (Eigen::Index k = 0; k < n; ++k) {
        if (!counts(k)) continue;
        const double a = orbit_peak_to_peak(zx(k), zy(k));
        if (a > largest) largest = a, peak = k;
    }
    if (!(largest > 0)) throw InputError("API unbalance placement: the mode shape is zero");
    UnbalancePlacement p;
    if (!inside(peak)) {
        p.layout = UnbalanceLayout::overhung;
        p.points.push_back({static_cast<int>(peak), 0.0});
        return p;
    }
    const bool along_x = std::abs(zx(peak)) >= std::abs(zy(peak));
    const Eigen::VectorXcd& d = along_x ? zx : zy;
    const std::complex<double> turn = std::conj(d(peak)) / std::abs(d(peak));
    Eigen::Index most = -1, least = -1, middle = -1;   // largest positive, largest negative, nearest mid-span
    double hi = 0.0, lo = 0.0;
    const double mid = 0.5 * (z0 + z1);
    for (Eigen::Index k = 0; k < n; ++k) {
        if (!inside(k)) continue;
        if (middle < 0 || std::fabs(z[k] - mid) < std::fabs(z[middle] - mid)) middle = k;
        const double s = (d(k) * turn).real();
        if (s > hi) hi = s, most = k;
        if (s < lo) lo = s, least = k;
    }
    if (middle < 0) throw InputError("API unbalance placement: no node lies in the bearing span");
    const double floor = 0.05 * std::abs(d(peak));
    if (least >= 0 && -lo > floor && hi > floor) {
        // 180 degrees apart; which of the two is at 0 is a turn of the whole loading, so the
        // point nearer z = 0 is (one case for every shape of this placement).
        p.layout = UnbalanceLayout::second_mode;
        p.points.push_back({static_cast<int>(std::min(most, least)), 0.0});
        p.points.push_back({static_cast<int>(std::max(most, least)), kPi});
        return p;
    }
    p.layout = UnbalanceLayout::first_mode;
    p.points.push_back({static_cast<int>(middle), 0.0});
    return p;
}

}  // namespace gyrokit
