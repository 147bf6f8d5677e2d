#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/pervasive_damping.hpp>

#include <gyrokit/analysis/campbell.hpp>
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <map>
#include <limits>

namespace gyrokit {

double pervasion_residual(const QuadraticPencil& p, const Eigen::MatrixXd& D, std::complex<double> lambda) {
    const Eigen::Index n = p.M.rows();
    const double np = std::norm(lambda) * p.M.norm() + std::abs(lambda) * p.C.norm() + p.K.norm();
    Eigen::MatrixXcd S(2 * n, n);
    S.topRows(n) = p.evaluate(lambda).transpose() / np;
    if (D.norm() == 0.0) return 0.0;   // no damping at this speed reaches anything
    S.bottomRows(n) = D.cast<std::complex<double>>() / D.norm();
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

// Losses of one damping set: per tracked branch, the residual along speed, on
// the grid from the left eigenvectors (a 2n x k SVD per mode); minima shaped
// like a V reaching zero are refined by golden section on the continued branch
// with the full SVD. A loss leaves a residual at the level of the eigenpair's
// own accuracy: r <= min(tolerance, 1e3 max(eta, sqrt(n) eps)).
void check_set(const std::string& name, const GyroscopicSystem& s, const std::vector<double>& speeds,
               const PervasiveOptions& opt, std::vector<DampingLoss>& out) {
    const double eps = std::numeric_limits<double>::epsilon();
    SolverOptions so = opt.solver;
    so.modes = opt.modes;
    so.eig.left_vectors = true;
    const SolverChoice solver = choose_solver(s, so);
    const bool dense = solver.kind == SolverKind::Dense;
    SpectrumSolver solve = solver.make();
    CampbellOptions co = tracking_options(solver, opt.modes, speeds, {1}, opt.threads);
    // K asked for: the K lowest are checked, wherever they lie (no cut-off).
    if (opt.modes > 0) co.band = std::numeric_limits<double>::infinity();
    const CampbellDiagram cd = campbell(solver.make, speeds, co);
    // The residual over a mode's left plane, from the dense or the sparse pencil.
    const auto plane = [&](double w, const Mode& m, const Eigen::MatrixXcd& Y) {
        return dense ? pervasion_residual(s.at_speed(w), Eigen::MatrixXd(s.damping_matrix(w)), m.lambda, Y)
                     : pervasion_residual(s.sparse_at_speed(w), s.damping_matrix(w), m.lambda, Y);
    };
    std::map<double, std::vector<const Mode*>> at;   // the modes at each speed, for double eigenvalues
    for (const Branch& b : cd.branches)
        for (const BranchPoint& q : b.points) at[q.speed].push_back(&q.mode);
    // The residual's rounding floor: its products sum n terms, so it is of the order
    // sqrt(n) eps (probabilistic rounding-error estimate) even for an exact left vector;
    // a backward error below that floor does not make the test stricter than it.
    const double floor = std::sqrt(static_cast<double>(s.size())) * eps;
    const auto limit = [&](const Mode& m) { return std::min(opt.tolerance, 1e3 * std::max(m.backward_error, floor)); };
    for (const Branch& b : cd.branches) {
        const size_t np = b.points.size();
        std::vector<double> r(np);
        for (size_t k = 0; k < np; ++k) {
            const BranchPoint& q = b.points[k];
            r[k] = plane(q.speed, q.mode, left_plane(q.mode, at[q.speed]));
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
            QuadraticSpectrum at_best;
            size_t best_index = 0;
            const auto f = [&](double w) {
                const size_t i = (w < b.points[k].speed && k > 0) ? k - 1 : std::min(k, np - 2);
                at_best = solve(w);
                best_index = static_cast<size_t>(&continue_branch(b, i, w, at_best) - at_best.modes.data());
                best = at_best.modes[best_index];
                if (dense) return pervasion_residual(s.at_speed(w), Eigen::MatrixXd(s.damping_matrix(w)), best.lambda);
                std::vector<const Mode*> modes;
                for (const Mode& m : at_best.modes) modes.push_back(&m);
                return plane(w, best, left_plane(best, modes));
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
            std::vector<const Mode*> modes;
            for (const Mode& m : at_best.modes) modes.push_back(&m);
            const double own = plane(w, best, left_plane(at_best.modes[best_index], modes));
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
    S.bottomRows(Y.rows()) = D.template cast<std::complex<double>>() * Z / nD;
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
    PervasiveReport rep;
    std::vector<std::pair<std::string, GyroscopicSystem>> sets;
    const std::vector<std::string> names = sys.damping_names();
    for (const auto& n : names) sets.emplace_back(n, sys.with_damping_only({n}));
    if (!names.empty()) sets.emplace_back("total", sys);
    for (const auto& [name, s] : sets) {
        rep.checked.push_back(name);
        check_set(name, s, speeds, opt, rep.losses);
    }
    std::stable_sort(rep.losses.begin(), rep.losses.end(), [](const DampingLoss& a, const DampingLoss& b) {
        return a.damping == b.damping ? a.speed < b.speed : false;
    });
    return rep;
}

}  // namespace gyrokit
