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

// A start of a correction: the predicted eigenvalue, a start vector (the mode's own
// or a Ritz vector) and the tracked mode it continues (-1: a Ritz pair of a cluster,
// whose modes may be one more or one fewer than before, at an exceptional point).
struct Seed {
    cd predicted;
    Mode start;
    long origin = -1;
};

// The modes of a failed step that move as a group: each mode that failed with its
// nearest neighbour (the distance between eigenvalues, a conjugate's included), or
// alone where its own conjugate is nearer (a complex pair about to meet on the real
// axis). A near-double pair splits along a hyperbola whose slope at the start is no
// guide, and two real eigenvalues that meet become a complex pair (and back) where
// the slopes are infinite: the Ritz pairs of the group's span follow both.
constexpr Eigen::Index kMaxClusterSize = 8;   // eigenvalues (conjugates counted)

double pair_distance(cd a, cd b) { return std::min(std::abs(a - b), std::abs(a - std::conj(b))); }

std::vector<std::vector<size_t>> clusters_of(const std::vector<Mode>& track, const std::vector<size_t>& failed,
                                             double real_tol) {
    std::vector<size_t> root(track.size());
    for (size_t i = 0; i < root.size(); ++i) root[i] = i;
    const auto find = [&](size_t i) {
        while (root[i] != i) i = root[i] = root[root[i]];
        return i;
    };
    std::vector<char> member(track.size(), 0);
    for (const size_t i : failed) {
        member[i] = 1;
        const cd a = track[i].lambda;
        double own = std::abs(a.imag()) > real_tol ? 2.0 * std::abs(a.imag()) : std::numeric_limits<double>::infinity();
        size_t best = track.size();
        double dist = std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < track.size(); ++j)
            if (j != i && pair_distance(a, track[j].lambda) < dist) dist = pair_distance(a, track[j].lambda), best = j;
        if (best < track.size() && dist < own) member[best] = 1, root[find(i)] = find(best);
    }
    std::map<size_t, std::vector<size_t>> groups;
    for (size_t i = 0; i < track.size(); ++i)
        if (member[i]) groups[find(i)].push_back(i);
    std::vector<std::vector<size_t>> out;
    for (auto& [r, g] : groups) out.push_back(std::move(g));
    return out;
}

// The Ritz pairs of a cluster at w: the pencil projected on the real span of its
// modes' right vectors (Galerkin: M stays definite), the eigenvalues nearest the
// cluster's own (as many as it has, conjugates counted, closed under conjugation),
// each with its Ritz vector; none where the span or the choice fails.
std::optional<std::vector<Seed>> cluster_seeds(const SparsePencil& p, const std::vector<Mode>& track,
                                               const std::vector<size_t>& members, double real_tol) {
    std::vector<Eigen::VectorXd> columns;
    std::vector<cd> own;   // the cluster's eigenvalues, conjugates included
    for (size_t i : members) {
        const Mode& m = track[i];
        const Eigen::VectorXcd x = unit_vector(m.right);
        for (const Eigen::VectorXd& c : {Eigen::VectorXd(x.real()), Eigen::VectorXd(x.imag())})
            if (c.norm() > 1e-8) columns.push_back(c);
        own.push_back(m.lambda);
        if (std::abs(m.lambda.imag()) > real_tol) own.push_back(std::conj(m.lambda));
    }
    const Eigen::Index d = static_cast<Eigen::Index>(own.size());
    if (d > kMaxClusterSize) return std::nullopt;
    Eigen::MatrixXd A(p.M.rows(), static_cast<Eigen::Index>(columns.size()));
    for (size_t j = 0; j < columns.size(); ++j) A.col(static_cast<Eigen::Index>(j)) = columns[j];
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU);
    Eigen::Index r = 0;
    while (r < svd.singularValues().size() && svd.singularValues()(r) > 1e-8 * svd.singularValues()(0)) ++r;
    // A projected pencil of r directions has 2 r eigenvalues: enough where 2 r >= d (two
    // real eigenvalues of one direction, as next to an exceptional point, share a vector).
    if (r == 0 || 2 * r < d) return std::nullopt;
    const Eigen::MatrixXd V = svd.matrixU().leftCols(r);
    const Eigen::MatrixXd Mr = V.transpose() * (p.M * V), Cr = V.transpose() * (p.C * V),
                          Kr = V.transpose() * (p.K * V);
    const Eigen::LDLT<Eigen::MatrixXd> mass(Mr);
    if (mass.info() != Eigen::Success || !(mass.rcond() > 1e-12)) return std::nullopt;
    Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(2 * r, 2 * r);
    companion.topRightCorner(r, r).setIdentity();
    companion.bottomLeftCorner(r, r) = -mass.solve(Kr);
    companion.bottomRightCorner(r, r) = -mass.solve(Cr);
    const Eigen::EigenSolver<Eigen::MatrixXd> es(companion, false);
    if (es.info() != Eigen::Success) return std::nullopt;
    const Eigen::VectorXcd mu = es.eigenvalues();
    std::vector<char> taken(static_cast<size_t>(2 * r), 0);
    std::vector<cd> chosen;
    for (const cd l : own) {
        Eigen::Index best = -1;
        double dist = std::numeric_limits<double>::infinity();
        for (Eigen::Index k = 0; k < 2 * r; ++k)
            if (!taken[static_cast<size_t>(k)] && std::abs(mu(k) - l) < dist) dist = std::abs(mu(k) - l), best = k;
        if (best < 0) return std::nullopt;
        taken[static_cast<size_t>(best)] = 1;
        chosen.push_back(mu(best));
    }
    // Closed under conjugation: a real pencil's eigenvalues near the real axis come
    // in conjugate pairs or are real.
    // Each value above the axis takes a distinct partner below it.
    std::vector<char> partnered(chosen.size(), 0);
    for (size_t a = 0; a < chosen.size(); ++a) {
        if (!(chosen[a].imag() > real_tol)) continue;
        size_t b = chosen.size();
        for (size_t o = 0; o < chosen.size() && b == chosen.size(); ++o)
            if (!partnered[o] && chosen[o].imag() < -real_tol &&
                std::abs(chosen[o] - std::conj(chosen[a])) <= 1e-6 * std::abs(chosen[a]))
                b = o;
        if (b == chosen.size()) return std::nullopt;
        partnered[a] = partnered[b] = 1;
    }
    for (size_t a = 0; a < chosen.size(); ++a)
        if (std::abs(chosen[a].imag()) > real_tol && !partnered[a]) return std::nullopt;
    std::vector<Seed> out;
    for (const cd c : chosen) {
        if (c.imag() < -real_tol) continue;   // its conjugate stands for it
        const cd l = std::abs(c.imag()) <= real_tol ? cd(c.real(), 0.0) : c;
        const Eigen::MatrixXcd P = (l * l) * Mr.cast<cd>() + l * Cr.cast<cd>() + Kr.cast<cd>();
        const Eigen::JacobiSVD<Eigen::MatrixXcd> null(P, Eigen::ComputeFullV);
        Seed sd;
        sd.predicted = l;
        sd.start.right = V.cast<cd>() * null.matrixV().col(r - 1);
        sd.start.lambda = l;
        out.push_back(std::move(sd));
    }
    return out;
}

}  // namespace

// Step 1: every mode of `from` predicted along its slope and corrected at w; with
// `cluster_failed` (the modes a plain step failed on), the modes of each cluster
// (clusters_of) from the Ritz pairs of their span instead. `failed`: the modes that
// fail are listed there (the others still checked).
std::optional<QuadraticSpectrum> branch_solve(const Frame& fr, const Solved& from, double w, Solved& next,
                                              const std::vector<size_t>* cluster_failed, std::vector<size_t>* failed) {
    const bool clustered = cluster_failed != nullptr;
    if (from.track.empty() || w == from.w) return std::nullopt;
    const SparsePencil p = fr.pencil(w);
    const PencilAction action = action_of(p);
    QuadraticSpectrum out = empty_spectrum(p, action, w);
    const double h = w - from.w;
    // Second order where the slope at the speed before is known: the branch's
    // curvature from the change of slope (the correction's first round then lands
    // closer, often close enough to stop there).
    const bool curved = fr.second_order && std::isfinite(from.before) && from.slope_before.size() == from.track.size();
    std::vector<Seed> seeds;
    std::vector<char> in_cluster(from.track.size(), 0);
    if (clustered) {
        const std::vector<std::vector<size_t>> groups = clusters_of(from.track, *cluster_failed, out.real_tol);
        if (groups.empty()) return std::nullopt;   // nothing the plain step did not try
        for (const std::vector<size_t>& g : groups) {
            std::optional<std::vector<Seed>> s = cluster_seeds(p, from.track, g, out.real_tol);
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
    std::vector<Mode> fixed(seeds.size());
    for (size_t i = 0; i < seeds.size(); ++i) fixed[i] = seeds[i].start;
    std::vector<char> ok(fixed.size(), 0);
    for_each_index(fixed.size(), fr.threads, [&](size_t i) {
        ok[i] = corrected(p, action, fixed[i], seeds[i].predicted, fr.tolerance, out.scale, out.real_tol);
    });
    std::vector<Mode> track;
    std::vector<cd> slope_before;   // of each tracked mode: its origin's slope (NaN: a cluster's)
    for (size_t i = 0; i < fixed.size(); ++i) {
        const cd pi = seeds[i].predicted;
        // The distance to the nearest other eigenvalue expected at w (the conjugate included).
        double gap = std::abs(pi.imag()) > out.real_tol ? 2.0 * std::abs(pi.imag()) : std::numeric_limits<double>::infinity();
        for (size_t j = 0; j < seeds.size(); ++j)
            if (j != i) gap = std::min(gap, pair_distance(pi, seeds[j].predicted));
        if (std::isfinite(from.beyond)) gap = std::min(gap, std::abs(from.beyond - std::abs(pi)));
        Mode& m = fixed[i];
        const long o = seeds[i].origin;
        // A failed mode of a plain step is noted (its cluster is tried next), the rest checked still.
        if (!ok[i] || !(std::abs(m.lambda - pi) <= 0.3 * gap) || lands_on_another(track, m) ||
            (o >= 0 && fr.min_mac > 0.0 && !(mac(m.right, from.track[static_cast<size_t>(o)].right) >= fr.min_mac))) {
            if (!failed || o < 0) return std::nullopt;
            failed->push_back(static_cast<size_t>(o));
            continue;
        }
        slope_before.push_back(o >= 0 ? from.track[static_cast<size_t>(o)].slope
                                      : cd(std::numeric_limits<double>::quiet_NaN(), 0.0));
        track.push_back(std::move(m));
    }
    if (failed && !failed->empty()) return std::nullopt;
    // As many eigenvalues as before (a complex mode stands for its pair): a group whose
    // Ritz pairs turned two real eigenvalues into one complex mode, or back, must not
    // lose one to a pair refined as real.
    const auto count = [&](const std::vector<Mode>& ms) {
        long c = 0;
        for (const Mode& m : ms) c += std::abs(m.lambda.imag()) > out.real_tol ? 2 : 1;
        return c;
    };
    if (clustered && count(track) != count(from.track)) return std::nullopt;
    if (clustered && fr.work) ++fr.work->cluster_steps;
    next.w = w;
    next.rigid = rigid;
    next.beyond = from.beyond;
    next.before = from.w;
    next.slope_before.clear();
    std::vector<cd> corrected_at(track.size());   // track[i] as corrected, before finish()
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
                                                            : slope_before[static_cast<size_t>(k - corrected_at.begin())]);
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
