// API 684 amplification factors of critical speeds: half-power on the unbalance
// response where it shows the peak, else 1/(2 zeta).
#include <gyrokit/analysis/critical_speeds.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <fmt/format.h>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

std::string to_string(AmplificationMethod m) { return m == AmplificationMethod::HalfPower ? "half-power" : "1/(2 zeta)"; }

double api684_required_margin(double af, bool above) {
    if (std::isnan(af) || af < kApi684CriticalAmplification) return 0.0;
    const double rise = 17.0 * (1.0 - 1.0 / (af - 1.5));   // 0 at AF 2.5, 17 as AF grows (1 for AF infinite)
    return above ? std::min(10.0 + rise, 26.0) : std::min(rise, 16.0);
}

namespace {

double from_damping(const Mode& m) {
    const double z = m.damping_ratio();
    return z > 0.0 ? 1.0 / (2.0 * z) : std::numeric_limits<double>::infinity();
}

// The DOF of the mode's largest translation (largest entry where units are unknown); of
// entries tied within kTieTolerance (x and y of a circular orbit), the first: no tie is
// broken by rounding.
int probe_dof(const GyroscopicSystem& sys, const Mode& m) {
    int best = -1;
    double largest = -1.0;
    for (int i = 0; i < static_cast<int>(m.right.size()); ++i) {
        if (!sys.dofs.units.empty() && sys.dofs.units[static_cast<size_t>(i)] != "m") continue;
        if (std::abs(m.right(i)) > largest * (1 + kTieTolerance)) largest = std::abs(m.right(i)), best = i;
    }
    return best;
}

// AF = N_peak / (N_2 - N_1) of the probe's response peak near the crossing, its
// peak searched on [lo, hi] (up to the midpoints to the neighbouring 1x crossings);
// nothing where the peak lies on the window's edge (no peak of this crossing) or a
// half-power point is not found within a factor 3 of the speed.
struct HalfPower {
    std::optional<double> af;
    std::string why;   // where af is unset
};
HalfPower half_power(const GyroscopicSystem& sys, const CriticalSpeed& c, int probe, double lo, double hi) {
    const auto amplitude = [&](double w) { return std::abs(unbalance_response(sys, w)(probe)); };
    const double wc = c.speed;
    const double zeta = std::max(c.mode.damping_ratio(), 1e-3);
    const double width = std::max(3.0 * zeta, 0.02) * wc;
    lo = std::max(lo, wc - width);
    hi = std::min(hi, wc + width);
    if (!(hi > lo) || lo <= 0.0) return {std::nullopt, "no speed window between the neighbouring crossings"};
    constexpr int samples = 40;
    std::vector<double> w(samples + 1), a(samples + 1);
    int k = 0;
    for (int i = 0; i <= samples; ++i) {
        w[static_cast<size_t>(i)] = lo + (hi - lo) * i / samples;
        a[static_cast<size_t>(i)] = amplitude(w[static_cast<size_t>(i)]);
        if (a[static_cast<size_t>(i)] > a[static_cast<size_t>(k)]) k = i;
    }
    if (k == 0 || k == samples) return {std::nullopt, "no response peak of this crossing"};
    const double wp = find_smooth_minimum([&](double v) { return -amplitude(v); }, w[static_cast<size_t>(k - 1)],
                                          w[static_cast<size_t>(k)], w[static_cast<size_t>(k + 1)]);
    const double target = amplitude(wp) / std::sqrt(2.0);
    // Walk away from the peak in steps of the window's sampling until the amplitude falls below the target.
    const double step = (hi - lo) / samples;
    const auto half_point = [&](double dir) -> std::optional<double> {
        double inner = wp;
        for (int i = 1; i <= 100000; ++i) {
            const double outer = wp + dir * step * i;
            if (outer <= wc / 3.0 || outer >= 3.0 * wc) return std::nullopt;
            if (amplitude(outer) < target)
                return find_root([&](double v) { return amplitude(v) - target; }, std::min(inner, outer),
                                 std::max(inner, outer), 1e-10);
            inner = outer;
        }
        return std::nullopt;
    };
    const std::optional<double> n1 = half_point(-1.0), n2 = half_point(1.0);
    if (!n1 || !n2 || !(*n2 > *n1)) return {std::nullopt, "no half-power point within a factor 3 of the speed"};
    return {wp / (*n2 - *n1), ""};
}

bool has_unbalance(const GyroscopicSystem& sys) { return sys.unbalance.size() > 0 && sys.unbalance.norm() > 0.0; }

}  // namespace

void set_amplification_factors(std::vector<CriticalSpeed>& cs, const GyroscopicSystem& sys, std::size_t only) {
    std::vector<double> ones;   // the 1x crossings, for the neighbours' midpoints
    for (const auto& c : cs)
        if (c.harmonic == 1) ones.push_back(c.speed);
    std::sort(ones.begin(), ones.end());
    for (std::size_t i = 0; i < cs.size(); ++i) {
        if (only < cs.size() && i != only) continue;
        CriticalSpeed& c = cs[i];
        c.amplification = from_damping(c.mode);
        c.amplification_method = AmplificationMethod::DampingRatio;
        c.probe = -1;
        c.amplification_dof.clear();
        c.amplification_note.clear();
        std::string& why = c.amplification_note;
        if (c.harmonic != 1) why = fmt::format("harmonic {}: the unbalance excites 1x", c.harmonic);
        else if (!has_unbalance(sys)) why = "the model has no unbalance";
        else if (sys.size() > kHalfPowerDofs) why = fmt::format("over {} DOFs", kHalfPowerDofs);
        else if (c.mode.right.size() != sys.size()) why = "no mode shape";
        else if (!(c.mode.damping_ratio() > 0.0)) why = "undamped or unstable";
        if (!why.empty()) continue;
        double lo = 0.0, hi = std::numeric_limits<double>::infinity();
        for (double o : ones) {
            if (o < c.speed) lo = std::max(lo, 0.5 * (o + c.speed));
            if (o > c.speed) hi = std::min(hi, 0.5 * (o + c.speed));
        }
        const int probe = probe_dof(sys, c.mode);
        if (probe < 0) {
            why = "no translation to measure";
            continue;
        }
        // The largest translation, then its whirl partner at the same node.
        std::vector<int> probes{probe};
        for (const auto& [u, v] : sys.whirl_pairs)
            if (u == probe || v == probe) probes.push_back(u == probe ? v : u);
        std::vector<std::pair<std::string, std::string>> failed;   // (why, DOF) of each probe tried
        for (const int p : probes) {
            const std::string name = p < sys.dofs.size() ? sys.dofs.names[static_cast<std::size_t>(p)]
                                                         : std::to_string(p);
            try {
                const HalfPower h = half_power(sys, c, p, lo, hi);
                if (h.af) {
                    c.amplification = *h.af;
                    c.amplification_method = AmplificationMethod::HalfPower;
                    c.probe = p;
                    c.amplification_dof = name;
                    failed.clear();
                    break;
                }
                failed.emplace_back(h.why, name);
            } catch (const SolverError&) {
                // A singular dynamic stiffness on the way (an undamped resonance): the damping ratio's AF stays.
                failed.emplace_back("a singular dynamic stiffness", name);
            }
        }
        std::stable_sort(failed.begin(), failed.end(), [&](const auto& a, const auto& b) {   // DOF order
            return sys.dofs.find(a.second) < sys.dofs.find(b.second);
        });
        // "no response peak of this crossing at y12 or x12": one reason names every DOF it held for.
        for (std::size_t k = 0; k < failed.size(); ++k) {
            const bool same = k > 0 && failed[k].first == failed[k - 1].first;
            why += same ? " or " + failed[k].second
                        : (why.empty() ? "" : "; ") + failed[k].first + " at " + failed[k].second;
        }
    }
}

}  // namespace gyrokit
