// The continuation over a grid of speeds: its shared state, the walk from an
// anchor over the grid speeds, and the factory (continuation_solver). The parts:
// detail/continuation_parts.hpp. docs/numerics.md ("Continuation").
#include <gyrokit/solve/detail/continuation_parts.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <limits>
#include <map>
#include <optional>

namespace gyrokit {

using cd = std::complex<double>;
using namespace continuation_detail;

bool within_band(const Mode& m, double band, double real_tol) {
    // A divergent (real, positive) eigenvalue is kept whatever its size: it is an
    // instability, and there is at most one per negative stiffness.
    return std::abs(m.lambda.imag()) <= real_tol ? std::abs(m.lambda) <= band || m.lambda.real() > 0.0
                                                 : m.lambda.imag() <= band;
}

namespace continuation_detail {

// What a full solve (with the slopes of its modes) leaves to continue from.
Solved track_of(const QuadraticSpectrum& s, const Shared& sh, double w) {
    Solved t;
    t.w = w;
    for (const Mode& m : s.modes)
        if (within_band(m, 2.0 * sh.opt.band, s.real_tol))
            t.track.push_back(m);
        else
            t.beyond = std::min(t.beyond, std::abs(m.lambda));
    t.rigid = s.rigid_body;
    return t;
}

// The modes of a full solve (with their slopes) within the band.
QuadraticSpectrum keep_band(QuadraticSpectrum s, const Shared& sh) {
    std::vector<Mode> kept;
    for (Mode& m : s.modes)
        if (within_band(m, sh.opt.band, s.real_tol)) kept.push_back(std::move(m));
    s.modes = std::move(kept);
    // Every mode within the band, as a full solve cut at the band: not a sparse
    // window whose edge moves (the tracker's stricter window rules do not apply).
    s.partial = false;
    if (!sh.opt.eig.left_vectors)
        for (Mode& m : s.modes) m.left.resize(0);
    return s;
}

QuadraticSpectrum full_solve(const Shared& sh, double w, Solved* track) {
    EigenOptions o = sh.opt.eig;
    o.left_vectors = true;
    QuadraticSpectrum s = solve_at_speed(*sh.model, w, o);
    set_slopes(s.modes, [&](double v) { return sh.model->sparse_at_speed(v); }, w, s.scale);
    if (track) *track = track_of(s, sh, w);
    return keep_band(std::move(s), sh);
}

Frame frame_of(const Shared& sh, int threads) {
    Frame f;
    f.threads = threads;
    const GyroscopicSystem* sys = sh.model.get();
    f.pencil = [sys](double v) { return sys->sparse_at_speed(v); };
    f.whirl_pairs = &sys->whirl_pairs;
    f.tolerance = sh.opt.tolerance;
    f.band = sh.opt.band;
    f.keep_left = sh.opt.eig.left_vectors;
    f.second_order = true;
    f.clusters = true;
    f.work = sh.work.get();
    return f;
}

}  // namespace continuation_detail

namespace {

// One solver's position on the grid: its walk's state at the grid speed `at`.
// Speeds off the grid are stepped to from there and do not move it.
struct Walk {
    std::optional<Solved> last;
    double at = std::numeric_limits<double>::quiet_NaN();
    int threads = 1;   // the modes of a step corrected in parallel
};

QuadraticSpectrum solve_one(const Shared& sh, Walk& state, double w);

// Brings the walk to grid speed `base`: on from where it is if that is at or after
// the anchor at or below `base`, else from that anchor, over every grid speed between.
void walk_to(const Shared& sh, Walk& state, double base) {
    const auto a = std::prev(sh.anchor_tracks.upper_bound(base));   // the first speed is an anchor
    if (!(state.last && state.at >= a->first && state.at <= base)) {
        state.last = a->second;
        state.at = a->first;
    }
    for (auto k = std::upper_bound(sh.grid.begin(), sh.grid.end(), state.at); k != sh.grid.end() && *k <= base; ++k)
        (void)solve_one(sh, state, *k);
}

QuadraticSpectrum solve_one(const Shared& sh, Walk& state, double w) {
    throw_if_interrupted();
    // Every speed is reached from the grid speed below it (a speed below the grid from
    // the first), and each grid speed from the anchor at or below it over the grid
    // speeds between: the answers do not depend on what the solver was asked before
    // or on how the grid is shared among workers.
    const auto g = std::lower_bound(sh.grid.begin(), sh.grid.end(), w);
    const bool on_grid = g != sh.grid.end() && *g == w;
    if (on_grid)
        if (const auto it = sh.anchors.find(w); it != sh.anchors.end()) {
            state.last = sh.anchor_tracks.at(w);
            state.at = w;
            return it->second;
        }
    const double base = g == sh.grid.begin() ? sh.grid.front() : *std::prev(g);
    if (!(state.at == base)) walk_to(sh, state, base);
    const auto keep = [&](Solved& next) {
        if (!on_grid) return;
        state.last = std::move(next);
        state.at = w;
    };
    Solved next;
    // At a check speed the continued modes must account for every eigenvalue near the
    // band; where they do not (or the step fails), the speed is solved in full.
    const auto check = on_grid ? sh.checks.find(w) : sh.checks.end();
    if (state.last && sh.opt.along_branches)
        if (std::optional<QuadraticSpectrum> s = branch_steps(frame_of(sh, state.threads), *state.last, w, next))
            if (check == sh.checks.end() || accounts(next, check->second, sh.opt.band, frame_of(sh, state.threads))) {
                ++sh.work->steps;
                keep(next);
                return std::move(*s);
            }
    // The projected pencil only finds modes its basis holds: one that came into the band
    // since the anchor would be missed, so after a failed step the speed is solved in
    // full (which the next steps continue from); the projection serves on its own.
    if (sh.Q.cols() > 0 && !sh.opt.along_branches && check == sh.checks.end())
        if (std::optional<QuadraticSpectrum> s = reduced_solve(sh, w)) {
            if (on_grid) state.at = w;   // no steps along the branches to continue
            return std::move(*s);
        }
    // Verified by the full solve itself (a step near a crossing, a double eigenvalue splitting).
    ++sh.work->full_solves;
    ++sh.work->local_solves;
    QuadraticSpectrum s = full_solve(sh, w, &next);
    keep(next);
    return s;
}

}  // namespace

SolverFactory continuation_solver(std::shared_ptr<const GyroscopicSystem> model, const std::vector<double>& speeds,
                                  const ContinuationOptions& opt, ContinuationReport* report) {
    if (opt.lowest < 0) throw InputError(fmt::format("continuation lowest {}: allowed: 0 or more modes", opt.lowest));
    if (opt.lowest > 0 ? !(opt.band_margin >= 1.0) || !std::isfinite(opt.band_margin) || !(opt.band >= 0.0) ||
                             !std::isfinite(opt.band)
                       : !(opt.band > 0.0) || !std::isfinite(opt.band))
        throw InputError(fmt::format("continuation band {} (margin {}): allowed: a finite frequency > 0 (rad/s), a "
                                     "margin >= 1",
                                     opt.band, opt.band_margin));
    if (opt.anchor_stride < 0)
        throw InputError(fmt::format("anchor_stride {}: allowed: 0 (the first speed only) or more", opt.anchor_stride));
    if (opt.check_stride < 1)
        throw InputError(fmt::format("check_stride {}: allowed: 1 or more", opt.check_stride));
    if (speeds.empty()) throw InputError("continuation: no speeds; allowed: one or more speeds >= 0");
    for (size_t k = 1; k < speeds.size(); ++k)
        if (!(speeds[k] > speeds[k - 1]))
            throw InputError("continuation: speeds not increasing; allowed: distinct speeds in increasing order");
    auto sh = std::make_shared<Shared>();
    sh->model = model;
    sh->opt = opt;
    sh->grid = speeds;
    sh->work = std::make_shared<WorkCounter>();
    const int n = model->size();
    ContinuationReport rep;
    rep.dofs = n;
    solve_anchors(*sh, rep);
    if (report) *report = rep;

    SolverFactory f([sh]() -> SpectrumSolver {
        auto state = std::make_shared<Walk>();
        return [sh, state](double w) { return solve_one(*sh, *state, w); };
    }, n, sh->work);
    f.with_pencil([model](double w) { return model->sparse_at_speed(w); });
    // A root search follows its branch's mode alone (a few factorizations of the full
    // pencil) rather than stepping every mode of the band.
    f.with_follow([model, tol = opt.tolerance, work = sh->work](const Mode& from, double w, cd predicted, double reach) {
        ++work->followed;
        return follow_mode([&model](double v) { return model->sparse_at_speed(v); }, model->whirl_pairs, from, w,
                           predicted, reach, tol);
    });
    // A grid solved in order by one solver whose steps correct their modes on
    // `threads` threads: every grid speed is reached from the first anchor anyway,
    // so workers sharing the grid would each walk from there (the same bits).
    f.with_walk([sh](int threads) -> SpectrumSolver {
        auto state = std::make_shared<Walk>();
        state->threads = threads;
        return [sh, state](double w) { return solve_one(*sh, *state, w); };
    });
    return f;
}

}  // namespace gyrokit
