// The steps along the branches: every mode predicted along its slope and corrected
// by inverse iteration on the full pencil, verified, in parts where a whole step
// fails; one mode followed alone (follow_mode), a sparse window continued
// (continue_window). docs/numerics.md ("Continuation").
#include <gyrokit/solve/detail/continuation_parts.hpp>

#include <gyrokit/core/parallel.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace gyrokit {
namespace continuation_detail {

PencilAction action_of(const SparsePencil& p) { return sparse_pencil_action(p); }

// Relative backward error of a left vector: |P(l)^H y| / ((|l|^2 |M| + |l| |C| + |K|) |y|).
double left_backward_error(const SparsePencil& p, const PencilAction& a, cd l, const Eigen::VectorXcd& y) {
    const cd c = std::conj(l);
    const Eigen::VectorXcd r = (c * c) * real_transpose_times(p.M, y) + c * real_transpose_times(p.C, y) +
                               real_transpose_times(p.K, y);
    const double s = std::norm(l) * a.norm_M + std::abs(l) * a.norm_C + a.norm_K;
    return r.norm() / (s * y.norm());
}

// The common end of the continued solves: whirl, rigid-body split, error bounds,
// order and (unless the caller sets them) slopes of the verified pairs.
QuadraticSpectrum finish(const Frame& fr, const SparsePencil& p, const PencilAction& action, QuadraticSpectrum out,
                         std::vector<Mode> modes, double w, bool slopes) {
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
               double scale, double real_tol, bool stepped) {
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

std::optional<Mode> joined_mode(const Frame& fr, const Solved& at, double w, cd lambda) {
    const SparsePencil p = fr.pencil(w);
    const PencilAction action = action_of(p);
    const QuadraticSpectrum frame = empty_spectrum(p, action, w);
    if (lambda.imag() < 0.0) lambda = std::conj(lambda);
    Mode m;
    m.right = fixed_random_vector(p.M.rows()).cast<cd>();
    // A double eigenvalue's second mode: the start orthogonal to the vectors already
    // followed there (from one start both would come out as one).
    for (const Mode& o : at.track)
        if (std::abs(o.lambda - lambda) <= 1e-6 * std::abs(lambda) && o.right.size() == m.right.size())
            m.right -= (o.right.dot(m.right) / o.right.squaredNorm()) * o.right;
    if (!corrected(p, action, m, lambda, fr.tolerance, frame.scale, frame.real_tol, true)) return std::nullopt;
    if (!(std::abs(m.lambda - lambda) <= 1e-6 * std::max(std::abs(lambda), frame.real_tol)) ||
        lands_on_another(at.track, m))
        return std::nullopt;
    m.whirl = classify_whirl(m.lambda, m.right, *fr.whirl_pairs, frame.real_tol);
    std::vector<Mode> one{std::move(m)};
    set_slopes(one, fr.pencil, w, frame.scale, 1, &p);
    return std::move(one[0]);
}

namespace {

// Each mode's start at w: its slope's prediction (second order where the slope at
// the speed before is known: the branch's curvature from the change of slope, so the
// correction's first round lands closer), or, for the modes of the clusters of
// `cluster_failed`, the Ritz pairs of their span. None where a cluster gives no Ritz
// pairs, or a mode has no slope and the caller keeps no list of failures.
std::optional<std::vector<Seed>> step_seeds(const Frame& fr, const Solved& from, const SparsePencil& p, double w,
                                            double real_tol, const std::vector<size_t>* cluster_failed,
                                            std::vector<size_t>* failed) {
    const double h = w - from.w;
    const bool curved = fr.second_order && std::isfinite(from.before) && from.slope_before.size() == from.track.size();
    std::vector<Seed> seeds;
    std::vector<char> in_cluster(from.track.size(), 0);
    if (cluster_failed) {
        const std::vector<std::vector<size_t>> groups = clusters_of(from.track, *cluster_failed, real_tol);
        if (groups.empty()) return std::nullopt;   // nothing the plain step did not try
        for (const std::vector<size_t>& g : groups) {
            std::optional<std::vector<Seed>> s = cluster_seeds(p, from.track, g, real_tol);
            if (!s) return std::nullopt;
            for (Seed& sd : *s) seeds.push_back(std::move(sd));
            for (size_t i : g) in_cluster[i] = 1;
        }
    }
    for (size_t i = 0; i < from.track.size(); ++i) {
        if (in_cluster[i]) continue;
        const Mode& m = from.track[i];
        // A mode without a slope (a double eigenvalue whose split its vectors do not
        // give) fails a plain step; the others are still corrected and checked, so
        // that its retry groups every mode that needs it.
        if (!finite(m.slope)) {
            if (!failed) return std::nullopt;
            failed->push_back(i);
            continue;
        }
        cd pr = m.lambda + h * m.slope;
        if (curved && finite(from.slope_before[i]))
            pr += (0.5 * h * h / (from.w - from.before)) * (m.slope - from.slope_before[i]);
        seeds.push_back({pr, m, static_cast<long>(i)});
    }
    return seeds;
}

// Whether the rigid-body pairs stay where they are: they still verify and the damping
// and gyroscopic terms do not act on them (C x = 0), so the zero eigenvalue keeps its
// multiplicity. A free rotor's tilt, which gyroscopic coupling turns into a nutation
// mode leaving zero, fails this and goes to the next path. Backward errors updated.
bool rigid_stays(const Frame& fr, const PencilAction& action, std::vector<Mode>& rigid, double scale) {
    for (Mode& r : rigid) {
        r.backward_error = backward_error(action, r.lambda, r.right);
        Eigen::VectorXcd Mx, Cx, Kx;
        action.apply(r.right, Mx, Cx, Kx);
        const double c_scale = (action.norm_C + scale * action.norm_M) * r.right.norm();
        if (!(r.backward_error <= fr.tolerance) || !(Cx.norm() <= fr.tolerance * c_scale)) return false;
    }
    return true;
}

// The seeds corrected (each on its own, in parallel), then checked in order: a
// corrected mode stays within 0.3 of the gap to its nearest neighbour, lands on no
// other and (min_mac) keeps its shape. The tracked modes, with each one's slope at
// the speed before (NaN: a cluster's Ritz pair). None where a check fails (the
// failed origins listed in `failed`, where given, and the rest checked still).
struct CorrectedStep {
    std::vector<Mode> track;
    std::vector<cd> slope_before;
};

std::optional<CorrectedStep> correct_seeds(const Frame& fr, const Solved& from, const SparsePencil& p,
                                           const PencilAction& action, const std::vector<Seed>& seeds, double scale,
                                           double real_tol, std::vector<size_t>* failed) {
    std::vector<Mode> fixed(seeds.size());
    for (size_t i = 0; i < seeds.size(); ++i) fixed[i] = seeds[i].start;
    std::vector<char> ok(fixed.size(), 0);
    for_each_index(fixed.size(), fr.threads, [&](size_t i) {
        ok[i] = corrected(p, action, fixed[i], seeds[i].predicted, fr.tolerance, scale, real_tol);
    });
    CorrectedStep c;
    for (size_t i = 0; i < fixed.size(); ++i) {
        const cd pi = seeds[i].predicted;
        // The distance to the nearest other eigenvalue expected at w (the conjugate included).
        double gap = std::abs(pi.imag()) > real_tol ? 2.0 * std::abs(pi.imag()) : std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < seeds.size(); ++j)
            if (j != i) gap = std::min(gap, pair_distance(pi, seeds[j].predicted));
        if (std::isfinite(from.beyond)) gap = std::min(gap, std::abs(from.beyond - std::abs(pi)));
        Mode& m = fixed[i];
        const long o = seeds[i].origin;
        // A failed mode of a plain step is noted (its cluster is tried next), the rest checked still.
        if (!ok[i] || !(std::abs(m.lambda - pi) <= 0.3 * gap) || lands_on_another(c.track, m) ||
            (o >= 0 && fr.min_mac > 0.0 && !(mac(m.right, from.track[static_cast<size_t>(o)].right) >= fr.min_mac))) {
            if (!failed || o < 0) return std::nullopt;
            failed->push_back(static_cast<size_t>(o));
            continue;
        }
        c.slope_before.push_back(o >= 0 ? from.track[static_cast<size_t>(o)].slope
                                        : cd(std::numeric_limits<double>::quiet_NaN(), 0.0));
        c.track.push_back(std::move(m));
    }
    if (failed && !failed->empty()) return std::nullopt;
    return c;
}

// Eigenvalues counted with their conjugates (a complex mode stands for its pair).
long eigenvalue_count(const std::vector<Mode>& modes, double real_tol) {
    long c = 0;
    for (const Mode& m : modes) c += std::abs(m.lambda.imag()) > real_tol ? 2 : 1;
    return c;
}

// The verified step reported (the modes in the band through finish()) and `next`
// made ready to continue from: the reported modes as finish() left them (a double
// pair's vectors turned to its whirl directions) and the tracked ones beyond the
// band, with slopes computed once for all; where the rigid-body split took a
// reported mode, the tracked ones as corrected get slopes of their own.
QuadraticSpectrum report_step(const Frame& fr, const SparsePencil& p, const PencilAction& action, QuadraticSpectrum out,
                              CorrectedStep c, std::vector<Mode> rigid, const Solved& from, double w, Solved& next) {
    next.w = w;
    next.rigid = rigid;
    next.beyond = from.beyond;
    next.before = from.w;
    next.slope_before.clear();
    std::vector<cd> corrected_at(c.track.size());   // track[i] as corrected, before finish()
    for (size_t i = 0; i < c.track.size(); ++i) corrected_at[i] = c.track[i].lambda;
    std::vector<Mode> modes;
    for (const Mode& m : c.track)
        if (within_band(m, fr.band, out.real_tol)) modes.push_back(m);
    out.rigid_body = std::move(rigid);
    const size_t rigid_before = out.rigid_body.size();
    const size_t reported = modes.size();
    out = finish(fr, p, action, std::move(out), std::move(modes), w, false);
    if (out.modes.size() == reported && out.rigid_body.size() == rigid_before) {
        next.track = out.modes;
        for (const Mode& m : c.track)
            if (!within_band(m, fr.band, out.real_tol)) next.track.push_back(m);
        set_slopes(next.track, fr.pencil, w, out.scale, fr.threads, &p);
        for (size_t i = 0; i < out.modes.size(); ++i) out.modes[i].slope = next.track[i].slope;
    } else {
        set_slopes(out.modes, fr.pencil, w, out.scale, fr.threads, &p);
        next.track = std::move(c.track);
        set_slopes(next.track, fr.pencil, w, out.scale, fr.threads, &p);
    }
    // Each tracked mode's slope at the speed before: that of the mode it was corrected
    // from (the same eigenvalue, bit for bit: finish() sorts and may take some away).
    for (const Mode& m : next.track) {
        const auto k = std::find(corrected_at.begin(), corrected_at.end(), m.lambda);
        next.slope_before.push_back(k == corrected_at.end()
                                        ? cd(std::numeric_limits<double>::quiet_NaN(), 0.0)
                                        : c.slope_before[static_cast<size_t>(k - corrected_at.begin())]);
    }
    if (!fr.keep_left)
        for (Mode& m : out.modes) m.left.resize(0);
    out.method = "continuation (along the branches, verified)";
    return out;
}

}  // namespace

// Step 1, stage by stage: seeds, the rigid-body pairs, corrections and checks, the report.
std::optional<QuadraticSpectrum> branch_solve(const Frame& fr, const Solved& from, double w, Solved& next,
                                              const std::vector<size_t>* cluster_failed, std::vector<size_t>* failed) {
    if (from.track.empty() || w == from.w) return std::nullopt;
    const SparsePencil p = fr.pencil(w);
    const PencilAction action = action_of(p);
    QuadraticSpectrum out = empty_spectrum(p, action, w);
    const std::optional<std::vector<Seed>> seeds = step_seeds(fr, from, p, w, out.real_tol, cluster_failed, failed);
    if (!seeds) return std::nullopt;
    std::vector<Mode> rigid = from.rigid;
    if (!rigid_stays(fr, action, rigid, out.scale)) return std::nullopt;
    std::optional<CorrectedStep> c = correct_seeds(fr, from, p, action, *seeds, out.scale, out.real_tol, failed);
    if (!c) return std::nullopt;
    // As many eigenvalues as before: a group whose Ritz pairs turned two real
    // eigenvalues into one complex mode, or back, must not lose one to a pair refined as real.
    if (cluster_failed) {
        if (eigenvalue_count(c->track, out.real_tol) != eigenvalue_count(from.track, out.real_tol)) return std::nullopt;
        if (fr.work) ++fr.work->cluster_steps;
    }
    return report_step(fr, p, action, std::move(out), std::move(*c), std::move(rigid), from, w, next);
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

namespace {

// The step whole, then with the modes that failed moving as groups (clusters_of).
std::optional<QuadraticSpectrum> whole_step(const Frame& fr, const Solved& from, double w, Solved& next) {
    std::vector<size_t> failed;
    if (std::optional<QuadraticSpectrum> s = branch_solve(fr, from, w, next, nullptr, &failed)) return s;
    if (failed.empty() || !fr.clusters) return std::nullopt;
    return branch_solve(fr, from, w, next, &failed, nullptr);
}

// The step in halves, each halved again where it fails, `halvings` levels down.
std::optional<QuadraticSpectrum> in_parts(const Frame& fr, const Solved& from, double w, Solved& next, int halvings) {
    if (std::optional<QuadraticSpectrum> s = whole_step(fr, from, w, next)) return s;
    if (halvings == 0 || from.track.empty() || w == from.w) return std::nullopt;
    Solved mid;
    if (!in_parts(fr, from, 0.5 * (from.w + w), mid, halvings - 1)) return std::nullopt;
    std::optional<QuadraticSpectrum> s = in_parts(fr, mid, w, next, halvings - 1);
    if (s && fr.min_mac > 0.0 && !keeps_shapes(from, next, fr.min_mac)) return std::nullopt;
    return s;
}

}  // namespace

std::optional<QuadraticSpectrum> branch_steps(const Frame& fr, const Solved& from, double w, Solved& next,
                                              int halvings) {
    if (std::optional<QuadraticSpectrum> s = whole_step(fr, from, w, next)) return s;
    if (halvings == 0 || from.track.empty() || w == from.w) return std::nullopt;
    Solved mid;   // the whole step failed: its halves, each in parts where it fails
    if (!in_parts(fr, from, 0.5 * (from.w + w), mid, halvings - 1)) return std::nullopt;
    std::optional<QuadraticSpectrum> s = in_parts(fr, mid, w, next, halvings - 1);
    if (s && fr.min_mac > 0.0 && !keeps_shapes(from, next, fr.min_mac)) return std::nullopt;
    if (s && fr.work) ++fr.work->split_steps;   // once per step, however deep it was split
    return s;
}

}  // namespace continuation_detail

using namespace continuation_detail;

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
    // No slope: its callers (the root searches, the loss searches) measure the mode at
    // the speeds they choose; the slope's two pencils cost as much as the correction.
    one[0].slope = {std::numeric_limits<double>::quiet_NaN(), 0.0};
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
