#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <limits>

namespace gyrokit {

double pervasion_residual(const QuadraticPencil& p, const Eigen::MatrixXd& D, std::complex<double> lambda) {
    const Eigen::Index n = p.M.rows();
    const double np = std::norm(lambda) * p.M.norm() + std::abs(lambda) * p.C.norm() + p.K.norm();
    Eigen::MatrixXcd S(2 * n, n);
    S.topRows(n) = p.evaluate(lambda).transpose() / np;
    if (D.norm() == 0.0) return 0.0;   // no damping at this speed reaches anything
    S.bottomRows(n) = D.transpose().cast<std::complex<double>>() / D.norm();   // z^T D = 0: D^T z = 0
    return Eigen::BDCSVD<Eigen::MatrixXcd>(S).singularValues()(n - 1);
}

namespace {

// The left vectors of `m` and of every mode of `modes` within 1e-6 of its
// eigenvalue (a double eigenvalue's left plane).
Eigen::MatrixXcd left_plane(const Mode& m, const std::vector<const Mode*>& modes) {
    std::vector<const Mode*> near{&m};
    for (const Mode* o : modes)
        if (o != &m && o->left.size() == m.left.size() && std::abs(o->lambda - m.lambda) <= 1e-6 * std::abs(m.lambda))
            near.push_back(o);
    Eigen::MatrixXcd Y(m.left.size(), static_cast<Eigen::Index>(near.size()));
    for (size_t c = 0; c < near.size(); ++c) Y.col(static_cast<Eigen::Index>(c)) = near[c]->left;
    return Y;
}

// Whether three samples (a, ra), (b, rb), (c, rc) with rb the smallest fit a V
// that reaches zero between them: a line through the two samples on one side,
// continued to zero and mirrored, predicts the third within half its value.
// A bowl whose floor stays above zero fails both fits.
bool reaches_zero(double a, double ra, double b, double rb, double c, double rc) {
    const double right = (rc - rb) / (c - b);   // kink between a and b
    if (right > 0.0) {
        const double kink = b - rb / right;
        if (kink >= a && std::abs(ra - right * (kink - a)) <= 0.5 * ra) return true;
    }
    const double left = (ra - rb) / (b - a);   // kink between b and c
    if (left > 0.0) {
        const double kink = b + rb / left;
        if (kink <= c && std::abs(rc - left * (c - kink)) <= 0.5 * rc) return true;
    }
    return false;
}

// The undamped system's tracking that every damping set is tested on: z^T P_D(lambda)
// = 0 with z^T D = 0 holds exactly where z^T P_0(lambda) = 0 with z^T D = 0 (P_D =
// P_0 + lambda D), so a set's losses are the undamped modes whose left vectors it
// does not see. One continuation serves every set.
struct Undamped {
    const GyroscopicSystem& sys;
    SolverFactory solver;               // the tracking's: follows a mode, or solves a speed
    const CampbellDiagram& diagram;
    bool dense = true;
    std::vector<const Branch*> branches;   // the judged ones (shown and up to f_cut)
    std::map<double, std::vector<const Mode*>> at;   // the modes at each speed, for double eigenvalues
};

// The residual over a mode's left plane for the set `set` (its damping at w).
double plane_at(const Undamped& u, const GyroscopicSystem& set, double w, const Mode& m, const Eigen::MatrixXcd& Y) {
    return u.dense ? pervasion_residual(u.sys.at_speed(w), Eigen::MatrixXd(set.damping_matrix(w)), m.lambda, Y)
                   : pervasion_residual(u.sys.sparse_at_speed(w), set.damping_matrix(w), m.lambda, Y);
}

// The residual of a branch point whose vectors are polished first: inverse
// iteration at its converged eigenvalue (refine_eigenpair, a factorization of the
// sparse pencil), so that what is left of the other modes in its left vector drops
// to rounding. The point's left vector alone (a double eigenvalue's plane is kept
// as tracked).
double polished(const Undamped& u, const GyroscopicSystem& set, const BranchPoint& q) {
    Mode m = q.mode;
    const SparsePencil p = u.sys.sparse_at_speed(q.speed);
    (void)refine_eigenpair(p, sparse_pencil_action(p), m, 0.0, std::abs(m.lambda));
    if (m.left.size() == 0 || !m.left.allFinite()) return std::numeric_limits<double>::infinity();
    return plane_at(u, set, q.speed, m, Eigen::MatrixXcd(m.left));
}

// Branch b's mode at w (between its points i and i + 1): followed from the nearer
// point (a few factorizations) and polished at its eigenvalue (a followed pair is
// verified to the step's tolerance only, and the residual follows the eigenvalue's
// error), else the speed solved by `solve` (made on first use) and the branch
// continued into it.
struct BranchAt {
    QuadraticSpectrum spectrum;
    size_t index = 0;
    const Mode& mode() const { return spectrum.modes[index]; }
    std::vector<const Mode*> all() const {
        std::vector<const Mode*> m;
        for (const Mode& x : spectrum.modes) m.push_back(&x);
        return m;
    }
};
BranchAt branch_at(const Undamped& u, const Branch& b, size_t i, double w, SpectrumSolver& solve) {
    BranchAt at;
    if (u.solver.can_follow()) {
        const BranchPoint& p0 = b.points[i];
        const BranchPoint& p1 = b.points[i + 1];
        const double t = p1.speed > p0.speed ? (w - p0.speed) / (p1.speed - p0.speed) : 0.0;
        const BranchPoint& near = t < 0.5 ? p0 : p1;
        std::optional<Mode> m = u.solver.follow(near.mode, w, (1.0 - t) * p0.mode.lambda + t * p1.mode.lambda,
                                                0.3 * eigenvalue_gap(u.diagram, b, near));
        if (m && m->left.size() > 0) {
            const SparsePencil p = u.sys.sparse_at_speed(w);
            (void)refine_eigenpair(p, sparse_pencil_action(p), *m, 0.0, std::abs(m->lambda));
            at.spectrum.modes = {std::move(*m)};
            return at;
        }
    }
    if (!solve) solve = u.solver();
    at.spectrum = solve(w);
    at.index = static_cast<size_t>(&continue_branch(b, i, w, at.spectrum) - at.spectrum.modes.data());
    return at;
}

// Losses of one damping set: per tracked branch, the residual along speed, on
// the grid from the left eigenvectors (a 2n x k SVD per mode); minima shaped
// like a V reaching zero are refined by golden section on the continued branch
// with the full SVD. A loss leaves a residual at the level of the eigenpair's
// own accuracy: r <= min(tolerance, 1e3 max(eta, sqrt(n) eps)).
void check_set(const std::string& name, const GyroscopicSystem& set, const Undamped& u, const PervasiveOptions& opt,
               std::vector<DampingLoss>& out) {
    const double eps = std::numeric_limits<double>::epsilon();
    // The residual's rounding floor: its products sum n terms, so it is of the order
    // sqrt(n) eps (probabilistic rounding-error estimate) even for an exact left vector;
    // a backward error below that floor does not make the test stricter than it.
    const double floor = std::sqrt(static_cast<double>(u.sys.size())) * eps;
    const auto limit = [&](const Mode& m) { return std::min(opt.tolerance, 1e3 * std::max(m.backward_error, floor)); };
    for (const Branch* bp : u.branches) {
        const Branch& b = *bp;
        const size_t np = b.points.size();
        std::vector<double> r(np);
        for (size_t k = 0; k < np; ++k) {
            const BranchPoint& q = b.points[k];
            r[k] = plane_at(u, set, q.speed, q.mode, left_plane(q.mode, u.at.at(q.speed)));
            // A residual between the loss limit and the tolerance may be the continued
            // left vector's own error (its components along the other modes, left by a
            // few steps of inverse iteration, not by rounding): polished at the converged
            // eigenvalue, it falls to rounding at a loss and stays where D reaches the mode.
            if (r[k] <= opt.tolerance && r[k] > limit(q.mode)) r[k] = std::min(r[k], polished(u, set, q));
        }
        const auto strict = [&](size_t k) { return k < np && r[k] <= limit(b.points[k].mode); };
        // Inside an interval of losses, a speed whose residual stays at its lost
        // neighbours' level (within 100x, below the tolerance) is lost too: the
        // rounding floor of r follows the left vector's accuracy, which varies
        // from speed to speed more than the backward error shows (sparse LU of a
        // finely meshed rotor), while a mode the damping reaches keeps r orders
        // of magnitude above it.
        const auto lost = [&](size_t k) {
            if (k >= np) return false;
            if (strict(k)) return true;
            if (!(r[k] <= opt.tolerance)) return false;
            const bool before = k > 0 && strict(k - 1) && r[k] <= 100.0 * r[k - 1];
            const bool after = strict(k + 1) && r[k] <= 100.0 * r[k + 1];
            return (before && after) || (before && k + 1 == np) || (after && k == 0);
        };
        const auto emit = [&](double w, Mode m, double res) {
            m.left.resize(0);
            out.push_back({name, w, b.id, std::move(m), res});
        };
        if (np < 2) {   // one point (one speed, or a window's mode seen once): no bracket to refine in
            if (np == 1 && strict(0)) emit(b.points[0].speed, b.points[0].mode, r[0]);
            continue;
        }
        for (size_t k = 0; k < np; ++k) {
            if (lost(k) && ((k > 0 && lost(k - 1)) || lost(k + 1))) {
                // Lost over a whole interval (e.g. a decoupled DOF group): every speed counts.
                emit(b.points[k].speed, b.points[k].mode, r[k]);
                continue;
            }
            const bool left_min = k == 0 || r[k] <= r[k - 1], right_min = k + 1 == np || r[k] < r[k + 1];
            if (!left_min || !right_min || !std::isfinite(r[k])) continue;
            // A zero of |g(w)| with g analytic is a V: sampled at spacing h, the point
            // nearest the kink is at most half its far neighbour, and the samples fit
            // a V. Bowls are no loss and are not refined, which keeps sweeps cheap.
            const double far = std::max(k > 0 ? r[k - 1] : 0.0, k + 1 < np ? r[k + 1] : 0.0);
            if (r[k] > 0.9 * far) continue;
            if (k > 0 && k + 1 < np && !lost(k) &&
                !reaches_zero(b.points[k - 1].speed, r[k - 1], b.points[k].speed, r[k], b.points[k + 1].speed,
                              r[k + 1]))
                continue;
            const double a = b.points[k == 0 ? 0 : k - 1].speed, c = b.points[std::min(k + 1, np - 1)].speed;
            Mode best = b.points[k].mode;
            BranchAt at_best;
            SpectrumSolver solve;   // made where a mode cannot be followed
            const auto f = [&](double w) {
                at_best = branch_at(u, b, (w < b.points[k].speed && k > 0) ? k - 1 : std::min(k, np - 2), w, solve);
                best = at_best.mode();
                // The full SVD (dense): a single left vector is ill-determined near a
                // crossing, where losses of a symmetric rotor lie (the centrifuge's d_R).
                if (u.dense)
                    return pervasion_residual(u.sys.at_speed(w), Eigen::MatrixXd(set.damping_matrix(w)), best.lambda);
                return plane_at(u, set, w, best, left_plane(at_best.mode(), at_best.all()));
            };
            // A V reaching zero keeps its smallest sample within slope x bracket width;
            // a bowl stops shrinking: give up once the smallest value stands a hundred
            // times above the grid slope times the bracket.
            const double slope = std::max(k > 0 ? r[k - 1] : 0.0, k + 1 < np ? r[k + 1] : 0.0) / (c - a);
            const auto bowl = [&](double width, double smallest) { return smallest > 100.0 * slope * width; };
            const double w = a < c ? find_minimum(f, a, c, 1e-14, bowl) : b.points[k].speed;
            const double res = f(w);
            // The full SVD also finds vectors that are no left eigenvector (its P block,
            // scaled by the Frobenius norms, weighs little for high modes): a loss
            // must hold for the left eigenvectors too.
            const double own = plane_at(u, set, w, best, left_plane(at_best.mode(), at_best.all()));
            if (res <= limit(best) && own <= limit(best)) emit(w, best, std::max(res, own));
        }
    }
}

}  // namespace

namespace {

// P(lambda)^T Z for a dense or sparse pencil.
Eigen::MatrixXcd transposed_times(const QuadraticPencil& p, std::complex<double> l, const Eigen::MatrixXcd& Z) {
    return p.evaluate(l).transpose() * Z;
}
Eigen::MatrixXcd transposed_times(const SparsePencil& p, std::complex<double> l, const Eigen::MatrixXcd& Z) {
    using cd = std::complex<double>;
    const Eigen::SparseMatrix<cd> Mt = p.M.transpose().cast<cd>(), Ct = p.C.transpose().cast<cd>(),
                                  Kt = p.K.transpose().cast<cd>();
    return (l * l) * (Mt * Z) + l * (Ct * Z) + Kt * Z;
}

template <class Pencil, class Matrix>
double plane_residual(const Pencil& p, const Matrix& D, std::complex<double> lambda, const Eigen::MatrixXcd& Y) {
    const double nD = D.norm();
    if (nD == 0.0) return 0.0;
    const double np = std::norm(lambda) * p.M.norm() + std::abs(lambda) * p.C.norm() + p.K.norm();
    const Eigen::MatrixXcd Z = Eigen::HouseholderQR<Eigen::MatrixXcd>(Y.conjugate()).householderQ() *
                               Eigen::MatrixXcd::Identity(Y.rows(), Y.cols());
    Eigen::MatrixXcd S(2 * Y.rows(), Y.cols());
    S.topRows(Y.rows()) = transposed_times(p, lambda, Z) / np;
    S.bottomRows(Y.rows()) = D.transpose().template cast<std::complex<double>>() * Z / nD;   // D^T z
    return Eigen::JacobiSVD<Eigen::MatrixXcd>(S).singularValues()(Y.cols() - 1);
}

}  // namespace

double pervasion_residual(const QuadraticPencil& p, const Eigen::MatrixXd& D, std::complex<double> lambda,
                          const Eigen::MatrixXcd& Y) {
    return plane_residual(p, D, lambda, Y);
}

double pervasion_residual(const SparsePencil& p, const SparseMatrix& D, std::complex<double> lambda,
                          const Eigen::MatrixXcd& Y) {
    return plane_residual(p, D, lambda, Y);
}

PervasiveReport pervasive_damping(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  const PervasiveOptions& opt) {
    if (!(opt.tolerance > 0.0 && opt.tolerance < 1.0))
        throw InputError(fmt::format("{} {}: allowed: 0 < tolerance < 1", option_field("tolerance"), opt.tolerance));
    if (speeds.empty()) throw InputError(option_field("speeds") + " (none): allowed: at least one speed in rad/s");
    PervasiveReport rep;
    rep.speeds = static_cast<int>(speeds.size());
    rep.from = speeds.front();
    rep.to = speeds.back();
    std::vector<std::pair<std::string, GyroscopicSystem>> sets;
    const std::vector<std::string> names = sys.damping_names();
    for (const auto& n : names) sets.emplace_back(n, sys.with_damping_only({n}));
    if (!names.empty()) sets.emplace_back("total", sys);
    for (const auto& [name, s] : sets) rep.checked.push_back(name);
    if (sets.empty()) return rep;   // no damping: nothing to check
    // The undamped system's modes, tracked once (the continuation where the solver
    // has one), with their verified left vectors.
    const GyroscopicSystem undamped = sys.with_damping_only({});
    SolverOptions so = opt.solver;
    so.modes = opt.modes;
    so.eig.left_vectors = true;
    const SolverChoice plan = choose_solver(undamped, so);
    const CampbellOptions co = tracking_options(plan, opt.modes, speeds, {1}, opt.threads, opt.f_cut);
    const Tracking t = track(plan.make, co, speeds);
    Undamped u{undamped, t.solver, t.diagram, plan.kind == SolverKind::Dense, {}, {}};
    // The judged modes: those at or below f_cut at some speed (the tracking's band may
    // reach higher, to hold the K lowest a diagram shows); every mode without a band.
    const double f_cut = std::isfinite(t.diagram.band) ? judged_band(opt.f_cut, speeds, {1}) : t.diagram.band;
    const auto judged = [&](const Branch& b) {
        return std::any_of(b.points.begin(), b.points.end(),
                           [&](const BranchPoint& q) { return std::abs(q.mode.lambda.imag()) <= f_cut; });
    };
    for (const auto* list : {&t.diagram.branches, &t.diagram.untracked})
        for (const Branch& b : *list) {
            if (b.points.empty() || b.points.front().mode.left.size() == 0) continue;   // eigenvalues alone
            if (!judged(b)) continue;
            u.branches.push_back(&b);
            for (const BranchPoint& q : b.points) u.at[q.speed].push_back(&q.mode);
        }
    rep.modes = static_cast<int>(u.branches.size());
    rep.band = f_cut;
    rep.partial = t.diagram.partial && !t.diagram.window_holds_band;
    rep.notes = t.diagram.notes;
    for (const auto& [name, s] : sets) check_set(name, s, u, opt, rep.losses);
    // By set (in the order checked), then by speed.
    const auto rank = [&](const DampingLoss& l) {
        return std::find(rep.checked.begin(), rep.checked.end(), l.damping) - rep.checked.begin();
    };
    std::stable_sort(rep.losses.begin(), rep.losses.end(), [&](const DampingLoss& a, const DampingLoss& b) {
        return rank(a) != rank(b) ? rank(a) < rank(b) : a.speed < b.speed;
    });
    return rep;
}

}  // namespace gyrokit
