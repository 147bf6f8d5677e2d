#include <gyrokit/analysis/continuation.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/core/parallel.hpp>

#include <Eigen/SVD>
#include <atomic>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <limits>
#include <map>
#include <optional>

namespace gyrokit {

using cd = std::complex<double>;

bool within_band(const Mode& m, double band, double real_tol) {
    // A divergent (real, positive) eigenvalue is kept whatever its size: it is an
    // instability, and there is at most one per negative stiffness.
    return std::abs(m.lambda.imag()) <= real_tol ? std::abs(m.lambda) <= band || m.lambda.real() > 0.0
                                                 : m.lambda.imag() <= band;
}

namespace {

PencilAction action_of(const SparsePencil& p) { return sparse_pencil_action(p); }

// Relative backward error of a left vector: |P(l)^H y| / ((|l|^2 |M| + |l| |C| + |K|) |y|).
double left_backward_error(const SparsePencil& p, const PencilAction& a, cd l, const Eigen::VectorXcd& y) {
    const cd c = std::conj(l);
    const Eigen::VectorXcd r = (c * c) * real_transpose_times(p.M, y) + c * real_transpose_times(p.C, y) +
                               real_transpose_times(p.K, y);
    const double s = std::norm(l) * a.norm_M + std::abs(l) * a.norm_C + a.norm_K;
    return r.norm() / (s * y.norm());
}

// A solved speed to continue from: the modes within twice the band (with their
// slopes) and the rigid-body eigenpairs.
struct Solved {
    double w = 0.0;
    std::vector<Mode> track;
    std::vector<Mode> rigid;
    // The smallest modulus of the modes beyond the tracked ones at the last full
    // solve: a corrected mode must not slide onto one of them either.
    double beyond = std::numeric_limits<double>::infinity();
    // Where w was reached by a step: the speed before and each tracked mode's slope
    // there (NaN: unknown), whose change gives its branch's curvature.
    double before = std::numeric_limits<double>::quiet_NaN();
    std::vector<cd> slope_before;
};

struct Shared {
    std::shared_ptr<const GyroscopicSystem> model;
    ContinuationOptions opt;
    std::vector<double> grid;                       // the speeds, increasing
    Eigen::MatrixXd Q;                              // n x r, orthonormal columns (empty: not used)
    std::map<double, QuadraticSpectrum> anchors;   // the full solves, kept to the band
    std::map<double, Solved> anchor_tracks;
    std::map<double, QuadraticSpectrum> checks;    // eigenvalues alone (modes without vectors)
    std::shared_ptr<WorkCounter> work;              // the factory's
};

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

QuadraticSpectrum full_solve(const Shared& sh, double w, Solved* track = nullptr) {
    EigenOptions o = sh.opt.eig;
    o.left_vectors = true;
    QuadraticSpectrum s = solve_at_speed(*sh.model, w, o);
    set_slopes(s.modes, [&](double v) { return sh.model->sparse_at_speed(v); }, w, s.scale);
    if (track) *track = track_of(s, sh, w);
    return keep_band(std::move(s), sh);
}

// What a continued solve needs of the model and the options: the continuation's
// own (frame_of) or a window solver's (continue_window).
struct Frame {
    std::function<SparsePencil(double)> pencil;
    const std::vector<std::pair<int, int>>* whirl_pairs = nullptr;
    double tolerance = 1e-10;
    double band = std::numeric_limits<double>::infinity();
    bool keep_left = true;
    double min_mac = 0.0;   // > 0: each corrected mode keeps at least this MAC with its shape before the step
    int threads = 1;        // the modes of a step are corrected in parallel
    // Second-order predictions (Solved::slope_before): the continuation's own steps. A
    // window's (continue_window) stay first order: their modes feed the Hautus test,
    // which measures the left vectors against the right ones' backward error, and a
    // first round that already reaches the right's target leaves the left vector one
    // plain round from its start.
    bool second_order = false;
    WorkCounter* work = nullptr;   // counts the steps taken in parts (the continuation's)
};

Frame frame_of(const Shared& sh, int threads = 1) {
    Frame f;
    f.threads = threads;
    const GyroscopicSystem* sys = sh.model.get();
    f.pencil = [sys](double v) { return sys->sparse_at_speed(v); };
    f.whirl_pairs = &sys->whirl_pairs;
    f.tolerance = sh.opt.tolerance;
    f.band = sh.opt.band;
    f.keep_left = sh.opt.eig.left_vectors;
    f.second_order = true;
    f.work = sh.work.get();
    return f;
}

// The common end of the continued solves: whirl, rigid-body split, error bounds,
// order and (unless the caller sets them) slopes of the verified pairs.
QuadraticSpectrum finish(const Frame& fr, const SparsePencil& p, const PencilAction& action, QuadraticSpectrum out,
                         std::vector<Mode> modes, double w, bool slopes = true) {
    for (Mode& m : modes) m.whirl = classify_whirl(m.lambda, m.right, *fr.whirl_pairs, out.real_tol);
    split_rigid_body(modes, out.rigid_body, action, out.scale);
    separate_double_whirl(modes, *fr.whirl_pairs, out.real_tol, action);
    const Eigen::VectorXd t = sparse_dof_scaling(p, out.scale);
    set_error_bounds(modes, action, scaled_norms(p, t), t, fr.threads);
    sort_by_frequency(modes);
    if (slopes) set_slopes(modes, fr.pencil, w, out.scale, fr.threads, &p);
    out.modes = std::move(modes);
    return out;
}

QuadraticSpectrum empty_spectrum(const SparsePencil& p, const PencilAction& action, double w) {
    QuadraticSpectrum out;
    out.scale = natural_frequency_scale(p.M.diagonal(), p.K.diagonal(), action.norm_M, action.norm_K);
    out.real_tol = 1e-7 * out.scale;
    out.partial = false;   // as keep_band
    out.speed = w;
    return out;
}

// A pair refined on the full model: verified right and left vectors, conjugated
// into the upper half plane, exactly real where it is real to the tolerance.
bool verified(const SparsePencil& p, const PencilAction& action, Mode& m, double tolerance, double real_tol) {
    if (!(m.backward_error <= tolerance) || m.left.size() == 0 ||
        !(left_backward_error(p, action, m.lambda, m.left) <= tolerance))
        return false;
    if (m.lambda.imag() < 0.0) m.lambda = std::conj(m.lambda), m.right = m.right.conjugate(), m.left = m.left.conjugate();
    if (std::abs(m.lambda.imag()) <= real_tol) m.lambda = cd(m.lambda.real(), 0.0);
    return true;
}

// Mode m started at `predicted` and corrected on the full pencil: refined to 1e-3
// of the tolerance where three factorizations get there (the error bounds then
// stay near the full solve's), then verified.
bool corrected(const SparsePencil& p, const PencilAction& action, Mode& m, cd predicted, double tolerance,
               double scale, double real_tol, bool stepped = true) {
    m.lambda = predicted;
    m.backward_error = std::numeric_limits<double>::infinity();   // the left vector: a start (refine_eigenpair)
    for (int k = 0; k < 3 && !(m.backward_error <= 1e-3 * tolerance); ++k)
        refine_eigenpair(p, action, m, 1e-3 * tolerance, scale, stepped && k == 0);
    return verified(p, action, m, tolerance, real_tol);
}

bool finite(cd z) { return std::isfinite(z.real()) && std::isfinite(z.imag()); }

// Two refined pairs on one mode: a mode is missing.
bool lands_on_another(const std::vector<Mode>& modes, const Mode& m) {
    for (const Mode& o : modes)
        if (std::abs(o.lambda - m.lambda) <= 1e-8 * std::abs(m.lambda) && mac(o.right, m.right) > 0.99) return true;
    return false;
}

// Step 1: every mode of `from` predicted along its slope and corrected at w.
std::optional<QuadraticSpectrum> branch_solve(const Frame& fr, const Solved& from, double w, Solved& next) {
    if (from.track.empty() || w == from.w) return std::nullopt;
    const SparsePencil p = fr.pencil(w);
    const PencilAction action = action_of(p);
    QuadraticSpectrum out = empty_spectrum(p, action, w);
    const double h = w - from.w;
    // Second order where the slope at the speed before is known: the branch's
    // curvature from the change of slope (the correction's first round then lands
    // closer, often close enough to stop there).
    const bool curved = fr.second_order && std::isfinite(from.before) && from.slope_before.size() == from.track.size();
    std::vector<cd> pred;
    for (size_t i = 0; i < from.track.size(); ++i) {
        const Mode& m = from.track[i];
        if (!finite(m.slope)) return std::nullopt;
        cd p = m.lambda + h * m.slope;
        if (curved && finite(from.slope_before[i]))
            p += (0.5 * h * h / (from.w - from.before)) * (m.slope - from.slope_before[i]);
        pred.push_back(p);
    }
    // The rigid-body pairs stay where they are if they still verify and the damping
    // and gyroscopic terms do not act on them (C x = 0): then the zero eigenvalue keeps
    // its multiplicity. A free rotor's tilt, which gyroscopic coupling turns into a
    // nutation mode leaving zero, fails this and goes to the next path.
    std::vector<Mode> rigid = from.rigid;
    for (Mode& r : rigid) {
        r.backward_error = backward_error(action, r.lambda, r.right);
        Eigen::VectorXcd Mx, Cx, Kx;
        action.apply(r.right, Mx, Cx, Kx);
        const double c_scale = (action.norm_C + out.scale * action.norm_M) * r.right.norm();
        if (!(r.backward_error <= fr.tolerance) || !(Cx.norm() <= fr.tolerance * c_scale)) return std::nullopt;
    }
    // Each mode corrected on its own (in parallel), then the checks in order.
    std::vector<Mode> fixed(from.track);
    std::vector<char> ok(fixed.size(), 0);
    for_each_index(fixed.size(), fr.threads, [&](size_t i) {
        ok[i] = corrected(p, action, fixed[i], pred[i], fr.tolerance, out.scale, out.real_tol);
    });
    std::vector<Mode> track;
    for (size_t i = 0; i < fixed.size(); ++i) {
        // The distance to the nearest other eigenvalue expected at w (the conjugate included).
        double gap = std::abs(pred[i].imag()) > out.real_tol ? 2.0 * std::abs(pred[i].imag())
                                                             : std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < pred.size(); ++j)
            if (j != i) gap = std::min({gap, std::abs(pred[i] - pred[j]), std::abs(pred[i] - std::conj(pred[j]))});
        if (std::isfinite(from.beyond)) gap = std::min(gap, std::abs(from.beyond - std::abs(pred[i])));
        Mode& m = fixed[i];
        if (!ok[i]) return std::nullopt;
        if (!(std::abs(m.lambda - pred[i]) <= 0.3 * gap) || lands_on_another(track, m)) return std::nullopt;
        if (fr.min_mac > 0.0 && !(mac(m.right, from.track[i].right) >= fr.min_mac)) return std::nullopt;
        track.push_back(std::move(m));
    }
    next.w = w;
    next.rigid = rigid;
    next.beyond = from.beyond;
    next.before = from.w;
    next.slope_before.clear();
    std::vector<cd> corrected_at(track.size());   // track[i] is from.track[i] corrected
    for (size_t i = 0; i < track.size(); ++i) corrected_at[i] = track[i].lambda;
    std::vector<Mode> modes;
    for (const Mode& m : track)
        if (within_band(m, fr.band, out.real_tol)) modes.push_back(m);
    out.rigid_body = std::move(rigid);
    const size_t rigid_before = out.rigid_body.size();
    const size_t reported = modes.size();
    out = finish(fr, p, action, std::move(out), std::move(modes), w, false);
    // The next step continues from the reported modes as finish() left them (a double
    // pair's vectors turned to its whirl directions) and the tracked ones beyond the
    // band, with slopes computed once for all of them. Where the rigid-body split took
    // a reported mode, the tracked ones as corrected get slopes of their own.
    if (out.modes.size() == reported && out.rigid_body.size() == rigid_before) {
        next.track = out.modes;
        for (const Mode& m : track)
            if (!within_band(m, fr.band, out.real_tol)) next.track.push_back(m);
        set_slopes(next.track, fr.pencil, w, out.scale, fr.threads, &p);
        for (size_t i = 0; i < out.modes.size(); ++i) out.modes[i].slope = next.track[i].slope;
    } else {
        set_slopes(out.modes, fr.pencil, w, out.scale, fr.threads, &p);
        next.track = std::move(track);
        set_slopes(next.track, fr.pencil, w, out.scale, fr.threads, &p);
    }
    // Each tracked mode's slope at the speed before: that of the mode it was corrected
    // from (the same eigenvalue, bit for bit: finish() sorts and may take some away).
    for (const Mode& m : next.track) {
        const auto k = std::find(corrected_at.begin(), corrected_at.end(), m.lambda);
        next.slope_before.push_back(k == corrected_at.end() ? cd(std::numeric_limits<double>::quiet_NaN(), 0.0)
                                                            : from.track[static_cast<size_t>(k - corrected_at.begin())].slope);
    }
    if (!fr.keep_left)
        for (Mode& m : out.modes) m.left.resize(0);
    out.method = "continuation (along the branches, verified)";
    return out;
}

// Step 1 with the step halved where it fails, up to `halvings` times: near a
// crossing the predictions come too close for the step's length, and a double
// eigenvalue splits faster than its first-order slopes tell; a shorter step costs a
// few corrections instead of a full solve. The speeds between are not reported.
// A step taken in parts keeps each shape over the whole step (Frame::min_mac): every
// mode at its end has at least that MAC with a distinct mode of its start. Each part
// checks the shapes against its own start only, and small turns would add up.
bool keeps_shapes(const Solved& from, const Solved& to, double min_mac) {
    if (to.track.size() != from.track.size()) return false;
    std::vector<char> taken(from.track.size(), 0);
    for (const Mode& m : to.track) {
        size_t best = from.track.size();
        double best_mac = -1.0;
        for (size_t j = 0; j < from.track.size(); ++j)
            if (!taken[j])
                if (const double v = mac(m.right, from.track[j].right); v > best_mac) best_mac = v, best = j;
        if (best == from.track.size() || !(best_mac >= min_mac)) return false;
        taken[best] = 1;
    }
    return true;
}

std::optional<QuadraticSpectrum> branch_steps(const Frame& fr, const Solved& from, double w, Solved& next,
                                              int halvings = 2) {
    if (std::optional<QuadraticSpectrum> s = branch_solve(fr, from, w, next)) return s;
    if (halvings == 0 || from.track.empty() || w == from.w) return std::nullopt;
    Solved mid;
    if (!branch_steps(fr, from, 0.5 * (from.w + w), mid, halvings - 1)) return std::nullopt;
    std::optional<QuadraticSpectrum> s = branch_steps(fr, mid, w, next, halvings - 1);
    if (s && fr.min_mac > 0.0 && !keeps_shapes(from, next, fr.min_mac)) return std::nullopt;
    if (s && fr.work) ++fr.work->split_steps;
    return s;
}

// The reduced solve at w, or nothing where a pair fails verification.
std::optional<QuadraticSpectrum> reduced_solve(const Shared& sh, double w) {
    const GyroscopicSystem& sys = *sh.model;
    const SparsePencil p = sys.sparse_at_speed(w);
    const PencilAction action = action_of(p);
    QuadraticSpectrum out = empty_spectrum(p, action, w);
    const Eigen::MatrixXd& Q = sh.Q;
    const QuadraticPencil reduced{Q.transpose() * (p.M * Q), Q.transpose() * (p.C * Q), Q.transpose() * (p.K * Q)};
    QuadraticSpectrum r = solve_quadratic(reduced, {sh.opt.eig.method, false}, {});
    std::vector<Mode> candidates;
    for (auto* list : {&r.modes, &r.rigid_body})
        for (Mode& m : *list)
            // A margin for the reduced eigenvalue's error: the band is applied again after refinement.
            if (within_band(m, 1.05 * sh.opt.band, out.real_tol)) candidates.push_back(std::move(m));
    std::vector<Mode> modes;
    for (Mode& m : candidates) {
        m.right = Q * m.right;
        m.left.resize(0);
        refine_eigenpair(p, action, m, sh.opt.tolerance, out.scale);
        if (!verified(p, action, m, sh.opt.tolerance, out.real_tol)) return std::nullopt;
        // Two reduced eigenvalues refined onto one mode: the basis misses a mode there.
        if (lands_on_another(modes, m)) return std::nullopt;
        if (!within_band(m, sh.opt.band, out.real_tol)) continue;
        modes.push_back(std::move(m));
    }
    out = finish(frame_of(sh), p, action, std::move(out), std::move(modes), w);
    if (!sh.opt.eig.left_vectors)
        for (Mode& m : out.modes) m.left.resize(0);
    out.method = fmt::format("continuation (reduced basis of {} vectors, verified)", Q.cols());
    return out;
}

// The eigenvalues at speed w alone, as a spectrum of modes without vectors (a
// check of the continuation): real within real_tol made real (whirl Real), those
// within the rigid-body tolerance of zero listed as rigid-body.
QuadraticSpectrum eigenvalues_only(const GyroscopicSystem& sys, double w) {
    const EigenvalueSet e = quadratic_eigenvalues(sys.at_speed(w));
    QuadraticSpectrum s;
    s.scale = e.scale;
    s.real_tol = e.real_tol;
    s.speed = w;
    s.method = "eigenvalues alone (no vectors)";
    for (const cd l : e.values) {
        Mode m;
        m.lambda = l;
        m.whirl = Whirl::Undefined;
        if (std::abs(l.imag()) <= e.real_tol) m.lambda = cd(l.real(), 0.0), m.whirl = Whirl::Real;
        (std::abs(l) <= kRigidBodyTolerance * e.scale ? s.rigid_body : s.modes).push_back(std::move(m));
    }
    return s;
}

// Whether the modes continued to a check speed account for its eigenvalues within
// twice the band: each in turn takes the nearest continued mode not yet taken, which
// must lie within 1e-6 of its modulus (the eigenvalues alone are good to about
// cond * 1e-16; a near miss costs only a full solve). A mode that came from beyond
// twice the band since the last full solve or check would not be there.
// The unmatched eigenvalues' smallest modulus becomes `at.beyond`.
bool accounts(Solved& at, const QuadraticSpectrum& check, double band) {
    std::vector<char> used(at.track.size(), 0);
    double beyond = std::numeric_limits<double>::infinity();
    for (const Mode& e : check.modes) {
        size_t best = at.track.size();
        double distance = std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < at.track.size(); ++j)
            if (const double d = std::min(std::abs(at.track[j].lambda - e.lambda),
                                          std::abs(at.track[j].lambda - std::conj(e.lambda)));
                !used[j] && d < distance)
                distance = d, best = j;
        if (best < at.track.size() && distance <= 1e-6 * std::max(std::abs(e.lambda), check.real_tol)) {
            used[best] = 1;
            continue;
        }
        if (within_band(e, 2.0 * band, check.real_tol)) return false;
        beyond = std::min(beyond, std::abs(e.lambda));
    }
    at.beyond = beyond;
    return true;
}

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
            if (check == sh.checks.end() || accounts(next, check->second, sh.opt.band)) {
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
    // Full solves at the first speed (and every anchor_stride-th and the last, if set);
    // the eigenvalues alone at every check_stride-th and the last where there is none.
    std::vector<double> anchors{speeds.front()}, checks;
    if (opt.anchor_stride > 0) {
        for (size_t k = static_cast<size_t>(opt.anchor_stride); k < speeds.size(); k += static_cast<size_t>(opt.anchor_stride))
            anchors.push_back(speeds[k]);
        if (anchors.back() != speeds.back()) anchors.push_back(speeds.back());
    }
    const auto is_anchor = [&](double w) { return std::find(anchors.begin(), anchors.end(), w) != anchors.end(); };
    for (size_t k = static_cast<size_t>(opt.check_stride); k < speeds.size(); k += static_cast<size_t>(opt.check_stride))
        if (!is_anchor(speeds[k])) checks.push_back(speeds[k]);
    if (!is_anchor(speeds.back()) && (checks.empty() || checks.back() != speeds.back())) checks.push_back(speeds.back());
    rep.anchors = anchors;
    rep.checks = checks;
    sh->work->full_solves += static_cast<long>(anchors.size());
    sh->work->eigenvalue_checks += static_cast<long>(checks.size());
    EigenOptions full = opt.eig;
    full.left_vectors = true;
    const SolverFactory dense = dense_solver(*model, full);
    std::vector<QuadraticSpectrum> solved, checked;
    if (opt.workers.count > 1 && opt.workers.kind != WorkerKind::Processes && dense.thread_safe()) {
        // One loop on threads, the anchors (the longest) first: a thread done with
        // its anchor takes the checks.
        solved.resize(anchors.size());
        checked.resize(checks.size());
        std::atomic<bool> failed{false};   // the first failure ends the loop (rethrown after it)
        for_each_index(anchors.size() + checks.size(), opt.workers.count, [&](size_t i) {
            if (failed) return;
            try {
                throw_if_interrupted();
                if (i < anchors.size()) {
                    solved[i] = dense()(anchors[i]);
                    solved[i].speed = anchors[i];   // as solve_speeds sets it
                } else {
                    checked[i - anchors.size()] = eigenvalues_only(*model, checks[i - anchors.size()]);
                }
            } catch (...) {
                failed = true;
                throw;
            }
        });
    } else {
        solved = solve_speeds(dense, anchors, opt.workers);
        const SolverFactory values([model]() -> SpectrumSolver {
            return [model](double w) { return eigenvalues_only(*model, w); };
        }, n);
        if (!checks.empty()) checked = solve_speeds(values, checks, opt.workers);
    }

    if (opt.lowest > 0) {   // the band of the lowest modes, from the anchors and checks
        double top = 0.0;
        for (const auto* list : {&solved, &checked})
            for (const QuadraticSpectrum& s : *list) {
                std::vector<Mode> m = s.modes;
                sort_by_frequency(m);
                // A divergent eigenvalue is kept whatever its size (within_band): it does not widen the band.
                m.erase(std::remove_if(m.begin(), m.end(),
                                       [&](const Mode& x) {
                                           return std::abs(x.lambda.imag()) <= s.real_tol && x.lambda.real() > 0.0;
                                       }),
                        m.end());
                for (size_t i = 0; i < std::min(m.size(), static_cast<size_t>(opt.lowest) + 2); ++i)
                    top = std::max(top, frequency_rank(m[i]).second);
            }
        if (!(top > 0.0) || !std::isfinite(top))
            throw SolverError(fmt::format("continuation: no band holds the {} lowest modes (largest frequency {})",
                                          opt.lowest, top));
        sh->opt.band = std::max(opt.band, opt.band_margin * top);
    }
    const double band = sh->opt.band;
    rep.band = band;

    // The basis: real and imaginary parts of the right and left vectors of every
    // mode within twice the band (modes that enter the band between anchors are
    // near it at an anchor), and of the rigid-body eigenvalues.
    std::vector<Eigen::VectorXd> columns;   // only for the projected pencil, which the steps precede
    const auto add = [&](const Eigen::VectorXcd& v) {
        if (opt.along_branches) return;
        if (v.size() != n) return;
        for (const Eigen::VectorXd& c : {Eigen::VectorXd(v.real()), Eigen::VectorXd(v.imag())})
            if (c.norm() > 1e-8 * v.norm()) columns.push_back(c / c.norm());
    };
    for (const QuadraticSpectrum& s : solved) {
        for (const Mode& m : s.modes)
            if (within_band(m, 2.0 * band, s.real_tol)) add(m.right), add(m.left);
        for (const Mode& m : s.rigid_body) add(m.right), add(m.left);
    }
    Eigen::MatrixXd V(n, static_cast<Eigen::Index>(columns.size()));
    for (size_t j = 0; j < columns.size(); ++j) V.col(static_cast<Eigen::Index>(j)) = columns[j];
    int r = 0;
    Eigen::MatrixXd Q;
    if (V.cols() > 0) {
        Eigen::BDCSVD<Eigen::MatrixXd> svd(V, Eigen::ComputeThinU);
        const Eigen::VectorXd& sv = svd.singularValues();
        while (r < sv.size() && sv(r) > 1e-12 * sv(0)) ++r;
        Q = svd.matrixU().leftCols(r);
    }
    rep.basis = r;
    rep.used = r > 0 && r <= opt.max_basis_fraction * n;
    if (rep.used) sh->Q = std::move(Q);
    if (report) *report = rep;
    for (size_t k = 0; k < anchors.size(); ++k) {
        sh->anchor_tracks[anchors[k]] = track_of(solved[k], *sh, anchors[k]);
        sh->anchors[anchors[k]] = keep_band(std::move(solved[k]), *sh);
    }
    for (size_t k = 0; k < checks.size(); ++k) sh->checks[checks[k]] = std::move(checked[k]);

    SolverFactory f([sh]() -> SpectrumSolver {
        auto state = std::make_shared<Walk>();
        return [sh, state](double w) { return solve_one(*sh, *state, w); };
    }, n, sh->work);
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

std::optional<Mode> follow_mode(const std::function<SparsePencil(double)>& pencil,
                                const std::vector<std::pair<int, int>>& whirl_pairs, const Mode& from, double w,
                                cd predicted, double reach, double tolerance) {
    if (!(reach > 0.0) || from.right.size() == 0) return std::nullopt;
    const SparsePencil p = pencil(w);
    const PencilAction action = action_of(p);
    const QuadraticSpectrum frame = empty_spectrum(p, action, w);
    Mode m = from;
    // Not as a prediction known to be off: a root search also asks for the speed of
    // `from` itself, where the pair is already accurate and must stay as it is (a
    // double pair's vectors would turn in its plane and its eigenvalue move by more
    // than the reach).
    if (!corrected(p, action, m, predicted, tolerance, frame.scale, frame.real_tol, false)) return std::nullopt;
    // The same mode: near its prediction, with (nearly) the same shape.
    if (!(std::abs(m.lambda - predicted) <= reach) || !(mac(m.right, from.right) >= 0.9)) return std::nullopt;
    std::vector<Mode> one{std::move(m)};
    one[0].whirl = classify_whirl(one[0].lambda, one[0].right, whirl_pairs, frame.real_tol);
    const Eigen::VectorXd t = sparse_dof_scaling(p, frame.scale);
    set_error_bounds(one, action, scaled_norms(p, t), t);
    set_slopes(one, pencil, w, frame.scale, 1, &p);
    return std::move(one[0]);
}

std::optional<QuadraticSpectrum> continue_window(const std::function<SparsePencil(double)>& pencil,
                                                 const std::vector<std::pair<int, int>>& whirl_pairs,
                                                 const QuadraticSpectrum& from, double w, double tolerance,
                                                 int threads) {
    Frame fr;
    fr.threads = threads;
    fr.pencil = pencil;
    fr.whirl_pairs = &whirl_pairs;
    fr.tolerance = tolerance;
    fr.min_mac = 0.9;
    Solved start;
    start.w = from.speed;
    start.track = from.modes;
    start.rigid = from.rigid_body;
    for (const Mode& m : start.track)
        if (m.left.size() != m.right.size()) return std::nullopt;
    Solved next;
    std::optional<QuadraticSpectrum> out = branch_steps(fr, start, w, next);
    if (!out) return std::nullopt;
    out->partial = from.partial;   // the window's modes, as the solve it continues
    out->speed = w;
    out->notes.clear();
    out->method = "continuation of the window (along the branches, verified)";
    return out;
}

}  // namespace gyrokit
