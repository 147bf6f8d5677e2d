#include "gyrokit/analysis/detail/branch_tracker.hpp"

#include <gyrokit/numerics/assignment.hpp>

#include <algorithm>
#include <cmath>

namespace gyrokit::tracking {

namespace {

// How far mode b at speed w0 + h lies from the continuation of mode a at w0:
// from the trapezoid (Hermite) prediction a + h (a' + b') / 2 where both slopes
// are known (error O(h^3)), from a + h a' where only a's is, else from
// `predicted` (the branch's linear extrapolation).
double step_residual(const Mode& a, const Mode& b, double h, cd predicted) {
    const bool sa = std::isfinite(a.slope.real()), sb = std::isfinite(b.slope.real());
    if (sa && sb) return std::abs(b.lambda - a.lambda - 0.5 * h * (a.slope + b.slope));
    if (sa) return std::abs(b.lambda - a.lambda - h * a.slope);
    return std::abs(b.lambda - predicted);
}

bool has_slope(const Mode& m) { return std::isfinite(m.slope.real()) && std::isfinite(m.slope.imag()); }

}  // namespace

std::vector<int> Tracker::match(const std::vector<Mode>& prev, const std::vector<cd>& predicted,
                       const std::vector<Mode>& next, double h, bool& ambiguous) const {
    std::vector<size_t> rows, cols, far_rows, far_cols;
    for (size_t i = 0; i < prev.size(); ++i) (far(prev[i]) ? far_rows : rows).push_back(i);
    for (size_t j = 0; j < next.size(); ++j) (far(next[j]) ? far_cols : cols).push_back(j);
    std::vector<int> a(prev.size(), -1);
    ambiguous = false;
    const int edge = opt.window > 0 ? opt.window : opt.modes;
    // The far modes in frequency order, pair by pair.
    const auto by_freq = [](const std::vector<Mode>& m, std::vector<size_t>& idx) {
        std::stable_sort(idx.begin(), idx.end(), [&](size_t x, size_t y) { return m[x].frequency() < m[y].frequency(); });
    };
    by_freq(prev, far_rows);
    by_freq(next, far_cols);
    const size_t nr = rows.size(), nc = cols.size();
    Eigen::MatrixXd res(nr, nc), cost(nr, nc);
    for (size_t r = 0; r < nr; ++r)
        for (size_t c = 0; c < nc; ++c) {
            const Mode& p = prev[rows[r]];
            const Mode& q = next[cols[c]];
            res(r, c) = step_residual(p, q, h, predicted[rows[r]]);
            cost(r, c) = res(r, c) / (std::abs(p.lambda) + std::abs(q.lambda) + 1e-300);
        }
    // The shapes weigh in where eigenvalues leave a choice: MAC of each row's three nearest.
    for (size_t r = 0; r < nr; ++r) {
        std::vector<size_t> near(nc);
        for (size_t c = 0; c < nc; ++c) near[c] = c;
        const size_t k = std::min<size_t>(3, nc);
        std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(k), near.end(),
                          [&](size_t x, size_t y) { return cost(r, x) < cost(r, y); });
        for (size_t c = 0; c < nc; ++c) cost(r, c) += 0.01;
        for (size_t t = 0; t < k; ++t)
            cost(r, near[t]) += 0.01 * (-mac(prev[rows[r]].right, next[cols[near[t]]].right));
    }
    const std::vector<int> sub = solve_assignment(cost);
    for (size_t r = 0; r < nr; ++r)
        if (sub[r] >= 0) a[rows[r]] = static_cast<int>(cols[static_cast<size_t>(sub[r])]);
    for (size_t t = 0; t < std::min(far_rows.size(), far_cols.size()); ++t)
        a[far_rows[t]] = static_cast<int>(far_cols[t]);

    for (size_t r = 0; r < nr && !ambiguous; ++r) {
        const size_t i = rows[r];
        if (sub[r] < 0 || degenerate(prev, i)) continue;   // a double eigenvalue: either match is right
        if (!watched[static_cast<size_t>(active[i])]) continue;
        if (window && edge > 0 && static_cast<int>(i) >= edge) continue;   // the window's edge
        const size_t c = static_cast<size_t>(sub[r]);
        const Mode& p = prev[i];
        const Mode& q = next[cols[c]];
        if (std::isfinite(opt.band) && p.frequency() > opt.band && q.frequency() > opt.band) continue;
        // Real (overdamped) eigenvalues are kept apart: a pair that turns overdamped
        // splits at an exceptional point, where no slope exists; not a matter of step size.
        if (frequency_rank(p).first != 0 || frequency_rank(q).first != 0) continue;
        if (has_slope(p) && has_slope(q) && std::isfinite(p.error_bound) && std::isfinite(q.error_bound)) {
            const double noise = 4.0 * (p.error_bound + q.error_bound) + 1e-12 * (std::abs(p.lambda) + std::abs(q.lambda));
            const double change = std::max({std::abs(q.lambda - p.lambda), std::abs(h * p.slope), std::abs(h * q.slope)});
            // In a complete spectrum the continuation is among the candidates, so a clear best
            // suffices (a bearing table's kink bends a branch by O(h) and no bisection straightens
            // it); a window may have lost it, so there the step must also be consistent, or
            // keep the mode's shape (at a kink the slope is the average of both sides, and
            // the residual stays O(h) at any step size).
            if (window && res(r, c) > 0.1 * change + noise && mac(p.right, q.right) < opt.mac_min) ambiguous = true;
            for (size_t k = 0; k < nc; ++k)
                if (k != c && std::abs(next[cols[k]].lambda - q.lambda) > 1e-8 * std::abs(q.lambda) &&
                    res(r, k) < std::max(4.0 * res(r, c), noise))
                    ambiguous = true;
        } else {
            const double own = 1.0 - mac(p.right, q.right) + res(r, c) / (std::abs(p.lambda) + std::abs(q.lambda) + 1e-300);
            if (mac(p.right, q.right) < opt.mac_min) ambiguous = true;
            for (size_t k = 0; k < nc && !ambiguous; ++k)
                if (k != c && 1.0 - mac(p.right, next[cols[k]].right) +
                                      res(r, k) / (std::abs(p.lambda) + std::abs(next[cols[k]].lambda) + 1e-300) <
                                  own + 0.05)
                    ambiguous = true;
        }
    }
    return a;
}

bool Tracker::degenerate(const std::vector<Mode>& modes, size_t i) {
    for (size_t k = 0; k < modes.size(); ++k)
        if (k != i && std::abs(modes[k].lambda - modes[i].lambda) <= 1e-8 * std::abs(modes[i].lambda))
            return true;
    return false;
}

std::vector<cd> Tracker::predictions(const std::vector<Mode>& modes, double w) const {
    std::vector<cd> p;
    for (size_t i = 0; i < modes.size(); ++i) {
        const auto& pts = out.branches[static_cast<size_t>(active[i])].points;
        if (pts.size() >= 2 && pts.back().speed > pts[pts.size() - 2].speed) {
            const auto& a = pts[pts.size() - 2];
            const auto& b = pts.back();
            p.push_back(b.mode.lambda + (b.mode.lambda - a.mode.lambda) * (w - b.speed) / (b.speed - a.speed));
        } else {
            p.push_back(modes[i].lambda);
        }
    }
    return p;
}

void Tracker::append(double w, QuadraticSpectrum&& s, const std::vector<int>& assign) {
    out.rigid_body = std::max(out.rigid_body, static_cast<int>(s.rigid_body.size()));
    for (auto& note : s.notes)
        if (std::find(out.notes.begin(), out.notes.end(), note) == out.notes.end()) out.notes.push_back(note);
    std::vector<int> next_active(s.modes.size(), -1);
    for (size_t i = 0; i < assign.size(); ++i)
        if (assign[i] >= 0) next_active[static_cast<size_t>(assign[i])] = active[i];
    for (size_t j = 0; j < s.modes.size(); ++j) {
        if (next_active[j] < 0) {   // a mode without predecessor starts a new branch
            next_active[j] = static_cast<int>(out.branches.size());
            out.branches.push_back({});
            watched.push_back(watch_new);
        }
        out.max_backward_error = std::max(out.max_backward_error, s.modes[j].backward_error);
        out.branches[static_cast<size_t>(next_active[j])].points.push_back({w, std::move(s.modes[j])});
    }
    active = std::move(next_active);
    out.speeds.push_back(w);
}

const std::vector<Mode>& Tracker::last_modes(std::vector<Mode>& buf) const {
    buf.clear();
    for (int b : active) buf.push_back(out.branches[static_cast<size_t>(b)].points.back().mode);
    return buf;
}

void Tracker::step(double w1, QuadraticSpectrum s1, int depth) {
    std::vector<Mode> prev;
    last_modes(prev);
    bool ambiguous = false;
    const double w0 = out.speeds.back();
    std::vector<int> a = match(prev, predictions(prev, w1), s1.modes, w1 - w0, ambiguous);
    const double wm = 0.5 * (w0 + w1);
    // No bisection below the resolution of the speeds (wm equal to an end).
    if (ambiguous && depth < opt.max_refine && wm > w0 && wm < w1) {
        ++out.inserted_speeds;
        step(wm, solve(wm), depth + 1);
        step(w1, std::move(s1), depth + 1);
        return;
    }
    if (ambiguous) ++out.ambiguous_steps;
    if (ambiguous && window)   // a mode that left the window ends its branch; its successor starts one
        for (size_t i = 0; i < a.size(); ++i)
            if (a[i] >= 0 && mac(prev[i].right, s1.modes[static_cast<size_t>(a[i])].right) < opt.mac_min) a[i] = -1;
    append(w1, std::move(s1), a);
}

}  // namespace gyrokit::tracking
