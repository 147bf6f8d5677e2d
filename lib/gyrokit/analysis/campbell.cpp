#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/campbell.hpp>

#include "gyrokit/analysis/detail/branch_tracker.hpp"
#include <gyrokit/solve/continuation.hpp>
#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyrokit {

using cd = std::complex<double>;

double match_cost(const Mode& a, cd predicted, const Mode& b) {
    const double scale = std::abs(predicted) + std::abs(b.lambda) + 1e-300;
    return (1.0 - mac(a.right, b.right)) + std::abs(predicted - b.lambda) / scale;
}

const Mode& continue_branch(const Branch& branch, size_t i, double w, const QuadraticSpectrum& spectrum) {
    if (spectrum.modes.empty()) throw SolverError("no finite eigenvalue to continue a branch");
    const BranchPoint& p0 = branch.points[i];
    const BranchPoint& p1 = branch.points[std::min(i + 1, branch.points.size() - 1)];
    const double t = (p1.speed > p0.speed) ? (w - p0.speed) / (p1.speed - p0.speed) : 0.0;
    const cd predicted = (1.0 - t) * p0.mode.lambda + t * p1.mode.lambda;
    const Mode& near = t < 0.5 ? p0.mode : p1.mode;
    size_t best = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < spectrum.modes.size(); ++j) {
        const double c = match_cost(near, predicted, spectrum.modes[j]);
        if (c < best_cost) { best_cost = c; best = j; }
    }
    return spectrum.modes[best];
}

using tracking::Tracker;

double excitation_band(const std::vector<double>& speeds, const std::vector<int>& harmonics) {
    double top = 0.0;
    for (double w : speeds) top = std::max(top, std::abs(w));
    int h = 1;
    for (int k : harmonics) h = std::max(h, k);
    return top > 0.0 && std::isfinite(top) ? kBandMargin * h * top : std::numeric_limits<double>::infinity();
}

namespace {

// A branch in the band: its frequency (a real eigenvalue's modulus) at or below it
// somewhere, or divergent (real and positive: judged whatever its size) anywhere.
bool mode_in_band(const Mode& m, double band) {
    const auto [rank, f] = frequency_rank(m);
    return f <= band || (rank == 1 && m.lambda.real() > 0.0);
}
bool in_band(const Branch& b, double band) {
    return std::any_of(b.points.begin(), b.points.end(), [&](const BranchPoint& p) { return mode_in_band(p.mode, band); });
}

// The K first branches shown, the others up to the band judged (untracked, with their
// vectors, ids K + 1 on); the out-of-range ones numbered after them. K = 0: all shown.
void show_k(CampbellDiagram& out, int k) {
    std::vector<Branch>& br = out.branches;
    if (k > 0 && static_cast<int>(br.size()) > k) {
        for (size_t i = static_cast<size_t>(k); i < br.size(); ++i) {
            br[i].id = static_cast<int>(i + 1);
            out.untracked.push_back(std::move(br[i]));
        }
        br.resize(static_cast<size_t>(k));
    }
    for (size_t i = 0; i < out.out_of_range.size(); ++i)
        out.out_of_range[i].id = static_cast<int>(br.size() + out.untracked.size() + i + 1);
}

}  // namespace

double judged_band(std::optional<double> f_cut, const std::vector<double>& speeds, const std::vector<int>& harmonics) {
    if (!f_cut) return excitation_band(speeds, harmonics);
    if (!(std::isfinite(*f_cut) && *f_cut > 0))
        throw InputError(fmt::format("{} {}: allowed: a finite frequency > 0 (rad/s; default {} times the highest "
                                     "excitation)",
                                     option_field("f_cut"), *f_cut, kBandMargin));
    return *f_cut;
}

CampbellOptions tracking_options(const SolverChoice& plan, int modes, const std::vector<double>& speeds,
                                 const std::vector<int>& harmonics, Workers threads, std::optional<double> f_cut) {
    CampbellOptions co;
    // K shown (0: every mode in range, or every mode); a sparse window's size is its own.
    co.modes = modes == kModesInRange ? 0 : plan.modes;
    if (plan.kind == SolverKind::Sparse) co.window = plan.modes;
    // A window centred away from zero (a target, or one moving with the speed) does not
    // hold the lowest modes, however wide: it is not widened, and judges its own modes.
    co.widen_window = !plan.shifted;
    if (f_cut) judged_band(f_cut, speeds, harmonics);   // refused where it is no frequency, whatever modes is
    // Every mode (modes = 0) is judged wherever it is; else the modes up to f_cut (a
    // sparse window is widened to hold them: track).
    if (modes != 0) co.band = judged_band(f_cut, speeds, harmonics), co.band_asked = f_cut.has_value();
    co.threads = threads;
    return co;
}

namespace {

// The continuation's options for a tracking with `co`: the band f_cut, widened to
// hold the K shown modes where K is given.
ContinuationOptions continuation_options(const CampbellOptions& co) {
    ContinuationOptions o;
    o.band = co.band;
    o.lowest = std::max(0, co.modes);
    o.workers = co.threads;
    return o;
}

}  // namespace

SolverFactory tracking_solver(const SolverFactory& make, const CampbellOptions& co, const std::vector<double>& speeds) {
    if (!std::isfinite(co.band) || !make.can_continue() || speeds.empty()) return make;
    return make.continued(speeds, continuation_options(co), nullptr);
}

namespace {

// A window of modes (sparse) doubled until, at the first, middle and last speed, it
// reaches beyond 1.5 times the band (by modulus: a heavily damped mode crossing a line
// lies farther from the target than its frequency) or holds every mode there is. Its
// cost grows with the window times the model's size: at most kWindowBudget / DOFs
// modes (and at most 64, half the DOFs), never fewer than asked. On
// data/fe_rotor_100k.toml (hundreds of nearly equal spans) a window of 8 in place of
// 4 cuts a cluster of hundreds of modes, where ARPACK took minutes instead of
// seconds: it stays at 4. Doubling only: a window grown by one or two modes would cut
// such a cluster as well.
constexpr double kWindowBudget = 5e5;
constexpr int kMaxBandWindow = 64;
// The speeds a window is checked at: the first, the middle and the last.
std::vector<double> probe_speeds(const std::vector<double>& speeds) {
    std::vector<double> at{speeds.front()};
    if (speeds.size() > 2) at.push_back(speeds[speeds.size() / 2]);
    if (speeds.size() > 1) at.push_back(speeds.back());
    return at;
}

// A window's modes at one speed: whether it holds the band there (fewer modes than the
// window: every mode there is; else reaching 1.5 times the band by modulus), how far
// it reaches, and how many of its modes lie in the band.
struct WindowReach {
    bool holds = true;
    double reach = 0.0;
    int in_band = 0;
};
WindowReach window_reach(const std::vector<const Mode*>& modes, int window, double band) {
    WindowReach r;
    for (const Mode* m : modes) {
        r.reach = std::max(r.reach, std::abs(m->lambda));
        r.in_band += mode_in_band(*m, band);
    }
    r.holds = static_cast<int>(modes.size()) < window || r.reach >= 1.5 * band;
    return r;
}

// The window doubled until, at the probe speeds, a fresh window solve holds the band
// (window_reach), within the budget; the in-band counts of the last probes per speed
// (empty where no probe was solved: the budget allows no wider window).
SolverFactory window_for_band(const SolverFactory& make, double band, const std::vector<double>& speeds,
                              std::vector<int>& probed) {
    probed.clear();
    if (make.dofs() <= 0) return make;
    const int budget = static_cast<int>(kWindowBudget / make.dofs());
    const int cap = std::max(make.window(), std::min({kMaxBandWindow, make.dofs() / 2, budget}));
    if (2 * make.window() > cap) return make;
    SolverFactory use = make;
    for (;;) {
        bool holds = true;
        probed.clear();
        for (const double w : probe_speeds(speeds)) {
            const QuadraticSpectrum s = use()(w);
            std::vector<const Mode*> m;
            for (const Mode& x : s.modes) m.push_back(&x);
            const WindowReach r = window_reach(m, use.window(), band);
            holds = holds && r.holds;
            probed.push_back(r.in_band);
        }
        if (holds || 2 * use.window() > cap) return use;
        use = make.resized(2 * use.window());
    }
}

}  // namespace

double eigenvalue_gap(const CampbellDiagram& cd, const Branch& own, const BranchPoint& at) {
    const std::complex<double> l = at.mode.lambda;
    double gap = std::abs(l.imag()) > 0.0 ? 2.0 * std::abs(l.imag()) : std::numeric_limits<double>::infinity();
    for (const auto* list : {&cd.branches, &cd.untracked, &cd.out_of_range})
        for (const Branch& o : *list) {
            if (&o == &own) continue;
            for (const BranchPoint& q : o.points)
                if (q.speed == at.speed)
                    gap = std::min({gap, std::abs(q.mode.lambda - l), std::abs(std::conj(q.mode.lambda) - l)});
        }
    return gap;
}

Tracking track(const SolverFactory& make, CampbellOptions co, const std::vector<double>& speeds) {
    if (!make.can_continue() && std::isfinite(co.band) && co.widen_window && make.can_resize() && make.window() > 0 &&
        !speeds.empty()) {
        // A window: widened to hold the modes up to f_cut, K of them shown.
        std::vector<int> probed;
        const SolverFactory use = window_for_band(make, co.band, speeds, probed);
        co.window = use.window();
        Tracking t{use, campbell(use, speeds, co)};
        // The tracked window holds the band where, at each probe speed, it reaches 1.5
        // times the band (or holds every mode) and has every in-band mode a fresh
        // window solve found there (a mode that entered the band later would be missing).
        const std::vector<double> at = probe_speeds(speeds);
        double reach = std::numeric_limits<double>::infinity();
        bool holds = true;
        for (size_t k = 0; k < at.size(); ++k) {
            std::vector<const Mode*> m;
            for (const auto* list : {&t.diagram.branches, &t.diagram.untracked, &t.diagram.out_of_range})
                for (const Branch& b : *list)
                    for (const BranchPoint& p : b.points)
                        if (p.speed == at[k]) m.push_back(&p.mode);
            const WindowReach r = window_reach(m, use.window(), co.band);
            if (!r.holds || (k < probed.size() && r.in_band < probed[k])) holds = false, reach = std::min(reach, r.reach);
        }
        t.diagram.window_holds_band = holds;
        if (!holds)
            t.diagram.notes.push_back(fmt::format(
                "the sparse window of {} modes (as wide as its cost budget for this model's size allows) reaches "
                "{:.6g} rad/s, short of 1.5 times f_cut ({:.6g} rad/s), or lost a mode that entered the band: "
                "modes up to f_cut may be missed; set {} for a wider window",
                use.window(), reach, 1.5 * co.band, option_field("modes")));
        return t;
    }
    if (!std::isfinite(co.band) || !make.can_continue() || speeds.empty()) return {make, campbell(make, speeds, co)};
    // The modes up to f_cut and, where K is given, up to the band that holds the K
    // lowest: one continuation, whatever K is (a shown branch that rises out of the
    // band ends there; it is then above f_cut, where no excitation line runs).
    ContinuationReport rep;
    Tracking t{make.continued(speeds, continuation_options(co), &rep), {}};
    co.band_of_modes = rep.band > co.band;
    co.band = rep.band;
    t.diagram = campbell(t.solver, speeds, co);
    return t;
}

std::optional<LeastDamped> least_damped(const CampbellDiagram& cd) {
    std::optional<LeastDamped> out;
    for (const Branch& b : cd.branches)
        for (const BranchPoint& p : b.points)
            if (p.mode.frequency() > 0 && (!out || p.mode.damping_ratio() < out->point.mode.damping_ratio()))
                out = LeastDamped{b.id, p};
    return out;
}

CampbellDiagram campbell(const GyroscopicSystem& sys, const std::vector<double>& speeds, const CampbellOptions& opt) {
    return campbell(dense_solver(sys), speeds, opt);
}

CampbellDiagram campbell(const SolverFactory& make, const std::vector<double>& speeds, const CampbellOptions& opt) {
    CampbellDiagram out;
    if (speeds.empty()) return out;
    for (size_t k = 0; k < speeds.size(); ++k) {
        if (!std::isfinite(speeds[k]) || speeds[k] < 0.0)
            throw InputError(fmt::format("speed {} at position {} is not allowed; allowed: finite speeds >= 0",
                                         speeds[k], k + 1));
        if (k > 0 && !(speeds[k] > speeds[k - 1]))
            throw InputError(fmt::format("speeds {} and {} at positions {} and {} do not increase; allowed: "
                                         "distinct speeds in increasing order",
                                         speeds[k - 1], speeds[k], k, k + 1));
    }
    // Grid speeds in parallel; tracking and refinement (few solves) in order.
    std::vector<QuadraticSpectrum> grid = solve_speeds(make, speeds, opt.threads, opt.progress);
    SpectrumSolver refine = make();
    Tracker t{refine, opt, out, {}, grid.front().partial, {}, 1};
    t.append(speeds.front(), std::move(grid.front()), {});
    if (opt.modes > 0 && !t.window && !std::isfinite(opt.band)) {   // watch the K lowest at the first speed, two more for ties at the edge
        std::vector<size_t> order(t.watched.size());
        for (size_t b = 0; b < order.size(); ++b) order[b] = b;
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
            return frequency_rank(out.branches[a].points.front().mode) < frequency_rank(out.branches[b].points.front().mode);
        });
        std::fill(t.watched.begin(), t.watched.end(), 0);
        t.watch_new = 0;   // a branch that starts later is never among the K reported
        for (size_t r = 0; r < std::min(order.size(), static_cast<size_t>(opt.modes) + 2); ++r) t.watched[order[r]] = 1;
    }
    for (size_t k = 1; k < speeds.size(); ++k) t.step(speeds[k], std::move(grid[k]), 0);

    // Number the branches by frequency at their first point; keep the K lowest
    // among those present at the first speed.
    std::vector<Branch>& br = out.branches;
    if (opt.modes == 0 || t.window || std::isfinite(opt.band)) out.band = opt.band;
    out.band_of_modes = opt.band_of_modes && std::isfinite(opt.band);
    out.band_asked = opt.band_asked && std::isfinite(opt.band);
    out.partial = t.window;
    std::stable_sort(br.begin(), br.end(), [&](const Branch& a, const Branch& b) {
        const bool a0 = a.points.front().speed == speeds.front(), b0 = b.points.front().speed == speeds.front();
        if (a0 != b0) return a0;
        // Equal frequencies (a double eigenvalue at standstill): the order just after decides.
        for (size_t k = 0; k < std::min({a.points.size(), b.points.size(), size_t(2)}); ++k) {
            const auto [ra, fa] = frequency_rank(a.points[k].mode);
            const auto [rb, fb] = frequency_rank(b.points[k].mode);
            if (ra != rb) return ra < rb;
            if (std::abs(fa - fb) > 1e-9 * std::max(std::abs(fa), std::abs(fb))) return fa < fb;
        }
        return false;
    });
    if (std::isfinite(opt.band) && !t.window) {
        // The modes up to the band are judged: the K lowest at the first speed shown
        // (branches), the others kept with their vectors (untracked: their crossings and
        // stability changes are found too); those above the band at every speed are out
        // of range, named and not judged.
        const auto split =
            std::stable_partition(br.begin(), br.end(), [&](const Branch& b) { return in_band(b, opt.band); });
        for (auto it = split; it != br.end(); ++it) {
            for (auto& p : it->points) p.mode.right.resize(0), p.mode.left.resize(0);
            out.out_of_range.push_back(std::move(*it));
        }
        br.erase(split, br.end());
        show_k(out, opt.modes);
    } else if (opt.modes > 0 && !t.window && static_cast<int>(br.size()) > opt.modes) {
        // The others were tracked too (a dense spectrum is complete): kept by eigenvalue for a
        // stability verdict over every mode, numbered on from K + 1.
        for (size_t i = static_cast<size_t>(opt.modes); i < br.size(); ++i) {
            for (auto& p : br[i].points) p.mode.right.resize(0), p.mode.left.resize(0);
            br[i].id = static_cast<int>(i + 1);
            out.untracked.push_back(std::move(br[i]));
        }
        br.resize(static_cast<size_t>(opt.modes));
    } else if (std::isfinite(opt.band) && (opt.modes == 0 || t.window)) {
        // Out of range: above the band at every speed. Named, not judged. A window keeps
        // the K asked for (the first at the first speed) as the dense band does.
        std::vector<Branch> kept;
        for (size_t i = 0; i < br.size(); ++i) {
            if (in_band(br[i], opt.band) || static_cast<int>(i) < opt.modes) {
                kept.push_back(std::move(br[i]));
                continue;
            }
            for (auto& p : br[i].points) p.mode.right.resize(0), p.mode.left.resize(0);
            out.out_of_range.push_back(std::move(br[i]));
        }
        br = std::move(kept);
        for (size_t i = 0; i < out.out_of_range.size(); ++i)
            out.out_of_range[i].id = static_cast<int>(br.size() + i + 1);
    }
    if (t.window) {   // the window's branches: those of the first speed, then the ones that entered later
        const auto first = std::stable_partition(br.begin(), br.end(), [&](const Branch& b) {
            return b.points.front().speed == speeds.front();
        });
        std::stable_sort(first, br.end(), [](const Branch& a, const Branch& b) {
            return a.points.front().speed < b.points.front().speed;
        });
        if (std::isfinite(opt.band)) show_k(out, opt.modes);   // a window widened for the band
    }
    for (size_t i = 0; i < br.size(); ++i) br[i].id = static_cast<int>(i + 1);
    return out;
}

}  // namespace gyrokit
