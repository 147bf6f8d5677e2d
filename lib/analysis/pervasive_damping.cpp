#include "analysis/pervasive_damping.hpp"

#include "analysis/campbell.hpp"
#include "analysis/scalar_search.hpp"
#include "eig/quadratic_eigensolver.hpp"

#include <Eigen/SVD>
#include <cmath>
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

// Losses of one damping set: per tracked branch, the residual along speed;
// isolated minima are refined by golden section on the continued branch.
void check_set(const std::string& name, const GyroscopicSystem& s, const std::vector<double>& speeds,
               const PervasiveOptions& opt, std::vector<DampingLoss>& out) {
    const double eps = std::numeric_limits<double>::epsilon();
    const CampbellDiagram cd = campbell(s, speeds);
    for (const Branch& b : cd.branches) {
        const size_t np = b.points.size();
        std::vector<double> r(np, std::numeric_limits<double>::infinity());
        double tiny = 0.0;
        for (size_t k = 0; k < np; ++k) {
            const Mode& m = b.points[k].mode;
            const QuadraticPencil p = s.at_speed(b.points[k].speed);
            tiny = 1e-7 * std::sqrt(p.K.norm() / p.M.norm());
            if (std::abs(m.lambda) > tiny)   // rigid-body modes skipped
                r[k] = pervasion_residual(p, s.damping_matrix(b.points[k].speed), m.lambda);
        }
        // A loss leaves a residual at the level of the eigenpair's own accuracy.
        const auto limit = [&](const Mode& m) { return std::min(opt.tolerance, 1e3 * std::max(m.backward_error, eps)); };
        const auto lost = [&](size_t k) { return k < np && r[k] <= limit(b.points[k].mode); };
        const auto emit = [&](double w, const Mode& m, double res) {
            out.push_back({name, w, b.id, m, res});
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
            // nearest the kink is at most half its far neighbour. Shallow bowls (ratio
            // near one) are no loss and are not refined, which keeps sweeps cheap.
            const double far = std::max(k > 0 ? r[k - 1] : 0.0, k + 1 < np ? r[k + 1] : 0.0);
            if (r[k] > 0.9 * far) continue;
            const double a = b.points[k == 0 ? 0 : k - 1].speed, c = b.points[std::min(k + 1, np - 1)].speed;
            Mode best = b.points[k].mode;
            const auto f = [&](double w) {
                const size_t i = (w < b.points[k].speed && k > 0) ? k - 1 : std::min(k, np - 2);
                best = continue_branch(b, i, w, solve_at_speed(s, w));
                return pervasion_residual(s.at_speed(w), s.damping_matrix(w), best.lambda);
            };
            const double w = a < c ? find_minimum(f, a, c) : b.points[k].speed;
            const double res = f(w);
            if (res <= limit(best)) emit(w, best, res);
        }
    }
}

}  // namespace

PervasiveReport pervasive_damping(const GyroscopicSystem& sys, const std::vector<double>& speeds,
                                  const PervasiveOptions& opt) {
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
