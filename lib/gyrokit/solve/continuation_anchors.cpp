// The continuation's anchors (full solves) and checks (the eigenvalues alone),
// solved before any step, in one parallel loop; the band of the lowest modes and
// the projection basis from them. docs/numerics.md ("Continuation").
#include <gyrokit/solve/detail/continuation_parts.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/core/parallel.hpp>

#include <Eigen/SVD>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit::continuation_detail {

namespace {

// Where the continuation solves before any step: full solves at the first speed
// (and every anchor_stride-th and the last, if set); the eigenvalues alone at every
// check_stride-th and the last where there is no anchor.
struct AnchorPlan {
    std::vector<double> anchors, checks;
};

AnchorPlan plan_anchors(const std::vector<double>& speeds, const ContinuationOptions& opt) {
    AnchorPlan p;
    p.anchors.push_back(speeds.front());
    if (opt.anchor_stride > 0) {
        for (size_t k = static_cast<size_t>(opt.anchor_stride); k < speeds.size(); k += static_cast<size_t>(opt.anchor_stride))
            p.anchors.push_back(speeds[k]);
        if (p.anchors.back() != speeds.back()) p.anchors.push_back(speeds.back());
    }
    const auto is_anchor = [&](double w) { return std::find(p.anchors.begin(), p.anchors.end(), w) != p.anchors.end(); };
    for (size_t k = static_cast<size_t>(opt.check_stride); k < speeds.size(); k += static_cast<size_t>(opt.check_stride))
        if (!is_anchor(speeds[k])) p.checks.push_back(speeds[k]);
    if (!is_anchor(speeds.back()) && (p.checks.empty() || p.checks.back() != speeds.back()))
        p.checks.push_back(speeds.back());
    return p;
}

// The anchors' full solves (with left vectors) and the checks' eigenvalues.
void solve_plan(const std::shared_ptr<const GyroscopicSystem>& model, const ContinuationOptions& opt,
                const AnchorPlan& plan, std::vector<QuadraticSpectrum>& solved,
                std::vector<QuadraticSpectrum>& checked) {
    const std::vector<double>& anchors = plan.anchors;
    const std::vector<double>& checks = plan.checks;
    EigenOptions full = opt.eig;
    full.left_vectors = true;
    const SolverFactory dense = dense_solver(*model, full);
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
        return;
    }
    solved = solve_speeds(dense, anchors, opt.workers);
    const SolverFactory values([model]() -> SpectrumSolver {
        return [model](double w) { return eigenvalues_only(*model, w); };
    }, model->size());
    if (!checks.empty()) checked = solve_speeds(values, checks, opt.workers);
}

// The band that holds the `lowest` lowest modes at every anchor and check, times the
// margin (never below the band given).
double lowest_modes_band(const std::vector<QuadraticSpectrum>& solved, const std::vector<QuadraticSpectrum>& checked,
                         const ContinuationOptions& opt) {
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
            for (size_t i = 0; i < std::min(m.size(), static_cast<size_t>(opt.lowest)); ++i)
                top = std::max(top, frequency_rank(m[i]).second);
        }
    if (!(top > 0.0) || !std::isfinite(top))
        throw SolverError(fmt::format("continuation: no band holds the {} lowest modes (largest frequency {})",
                                      opt.lowest, top));
    return std::max(opt.band, opt.band_margin * top);
}

// The projection basis: real and imaginary parts of the right and left vectors of
// every mode within twice the band (modes that enter the band between anchors are
// near it at an anchor) and of the rigid-body eigenvalues, orthonormalised by an SVD
// (rank cut at 1e-12). Empty where there is nothing to span.
Eigen::MatrixXd projection_basis(const std::vector<QuadraticSpectrum>& solved, double band, int n) {
    std::vector<Eigen::VectorXd> columns;
    const auto add = [&](const Eigen::VectorXcd& v) {
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
    if (V.cols() == 0) return {};
    Eigen::BDCSVD<Eigen::MatrixXd> svd(V, Eigen::ComputeThinU);
    const Eigen::VectorXd& sv = svd.singularValues();
    Eigen::Index r = 0;
    while (r < sv.size() && sv(r) > 1e-12 * sv(0)) ++r;
    return svd.matrixU().leftCols(r);
}

}  // namespace

// The anchors, stage by stage: plan, solve, band, basis, then the anchors' tracks.
void solve_anchors(Shared& sh, ContinuationReport& rep) {
    const ContinuationOptions opt = sh.opt;   // as given (the band may widen below)
    const int n = sh.model->size();
    const AnchorPlan plan = plan_anchors(sh.grid, opt);
    rep.anchors = plan.anchors;
    rep.checks = plan.checks;
    sh.work->full_solves += static_cast<long>(plan.anchors.size());
    sh.work->eigenvalue_checks += static_cast<long>(plan.checks.size());
    std::vector<QuadraticSpectrum> solved, checked;
    solve_plan(sh.model, opt, plan, solved, checked);
    if (opt.lowest > 0) sh.opt.band = lowest_modes_band(solved, checked, opt);
    rep.band = sh.opt.band;
    // The projected pencil precedes the steps; a continuation along branches has none.
    Eigen::MatrixXd Q = opt.along_branches ? Eigen::MatrixXd() : projection_basis(solved, sh.opt.band, n);
    rep.basis = static_cast<int>(Q.cols());
    rep.used = rep.basis > 0 && rep.basis <= opt.max_basis_fraction * n;
    if (rep.used) sh.Q = std::move(Q);
    for (size_t k = 0; k < plan.anchors.size(); ++k) {
        sh.anchor_tracks[plan.anchors[k]] = track_of(solved[k], sh, plan.anchors[k]);
        sh.anchors[plan.anchors[k]] = keep_band(std::move(solved[k]), sh);
    }
    for (size_t k = 0; k < plan.checks.size(); ++k) sh.checks[plan.checks[k]] = std::move(checked[k]);
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
// twice the band since the last full solve or check would not be there: where it
// lies beyond the band (followed, not reported) it joins the continued modes by
// inverse iteration at its eigenvalue (joined_mode); inside the band the speed is
// solved in full. The unmatched eigenvalues' smallest modulus becomes `at.beyond`.
bool accounts(Solved& at, const QuadraticSpectrum& check, double band, const Frame& fr) {
    std::vector<char> used(at.track.size(), 0);
    double beyond = std::numeric_limits<double>::infinity();
    std::vector<cd> join;
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
        if (within_band(e, band, check.real_tol)) return false;
        if (within_band(e, 2.0 * band, check.real_tol))
            join.push_back(e.lambda);
        else
            beyond = std::min(beyond, std::abs(e.lambda));
    }
    if (!join.empty()) {
        Solved grown = at;
        for (const cd l : join) {
            std::optional<Mode> m = joined_mode(fr, grown, check.speed, l);
            if (!m) return false;
            grown.track.push_back(std::move(*m));
            if (grown.slope_before.size() + 1 == grown.track.size())
                grown.slope_before.push_back(cd(std::numeric_limits<double>::quiet_NaN(), 0.0));
        }
        at = std::move(grown);
        if (fr.work) fr.work->joined += static_cast<long>(join.size());
    }
    at.beyond = beyond;
    return true;
}

}  // namespace gyrokit::continuation_detail
