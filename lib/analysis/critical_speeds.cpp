#include "analysis/critical_speeds.hpp"

#include "analysis/scalar_search.hpp"
#include "core/error.hpp"
#include "eig/lapack.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyrokit {

namespace {

// Refines a sign change of g(mode, w) between points i and i+1 of a branch.
template <class G>
std::pair<double, Mode> refine_on_branch(SpectrumSolver& solve, const Branch& b, size_t i, const G& g) {
    const auto mode_at = [&](double w) { return continue_branch(b, i, w, solve(w)); };
    const double w = find_root([&](double x) { return g(mode_at(x), x); }, b.points[i].speed,
                               b.points[i + 1].speed);
    return {w, mode_at(w)};
}

// Every sign change of g along every oscillating branch, refined on `threads`
// workers (each root search is independent), then emitted in branch order.
template <class G, class Emit>
void scan_branches(const SolverFactory& make, const CampbellDiagram& cd, const G& g, int threads, const Emit& emit) {
    struct Interval {
        const Branch* branch;
        size_t i;
        double g0, g1;
    };
    std::vector<Interval> found;
    for (const Branch& b : cd.branches) {
        for (size_t i = 0; i + 1 < b.points.size(); ++i) {
            const Mode& m0 = b.points[i].mode;
            const Mode& m1 = b.points[i + 1].mode;
            if (m0.whirl == Whirl::Real || m1.whirl == Whirl::Real) continue;
            const double g0 = g(m0, b.points[i].speed), g1 = g(m1, b.points[i + 1].speed);
            if (g0 == 0.0 && i > 0) continue;   // counted as the end of the previous interval
            if ((g0 > 0) == (g1 > 0) && g0 != 0.0 && g1 != 0.0) continue;
            found.push_back({&b, i, g0, g1});
        }
    }
    const std::vector<QuadraticSpectrum> roots =
        run_on_workers(make, found.size(), threads, [&](SpectrumSolver& solve, size_t k) {
            auto [w, m] = refine_on_branch(solve, *found[k].branch, found[k].i, g);
            QuadraticSpectrum s;
            s.speed = w;
            s.modes.push_back(std::move(m));
            return s;
        });
    for (size_t k = 0; k < found.size(); ++k)
        emit(*found[k].branch, roots[k].speed, roots[k].modes.at(0), found[k].g0, found[k].g1);
}

}  // namespace

std::vector<CriticalSpeed> critical_speeds(const GyroscopicSystem& sys, const CampbellDiagram& cd,
                                           const std::vector<int>& harmonics, const EigenOptions& eig) {
    return critical_speeds(dense_solver(sys, eig), cd, harmonics);
}

std::vector<CriticalSpeed> critical_speeds(const SolverFactory& solver, const CampbellDiagram& cd,
                                           const std::vector<int>& harmonics, int threads) {
    std::vector<CriticalSpeed> out;
    for (int k : harmonics) {
        if (k < 1) throw InputError("harmonic " + std::to_string(k) + " is not allowed; allowed: k >= 1");
        const auto g = [k](const Mode& m, double w) { return m.lambda.imag() - k * w; };
        scan_branches(solver, cd, g, threads, [&](const Branch& b, double w, Mode m, double, double) {
            out.push_back({w, k, b.id, std::move(m)});
        });
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
    return out;
}

std::vector<StabilityChange> stability_changes(const GyroscopicSystem& sys, const CampbellDiagram& cd,
                                               const EigenOptions& eig) {
    return stability_changes(dense_solver(sys, eig), cd);
}

std::vector<StabilityChange> stability_changes(const SolverFactory& solver, const CampbellDiagram& cd, int threads) {
    std::vector<StabilityChange> out;
    const auto g = [](const Mode& m, double) { return m.lambda.real(); };
    scan_branches(solver, cd, g, threads, [&](const Branch& b, double w, Mode m, double g0, double g1) {
        out.push_back({w, b.id, g1 > g0, std::move(m)});
    });
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
    return out;
}

std::vector<CriticalSpeed> critical_speeds_direct(const GyroscopicSystem& sys, int harmonic, double from,
                                                  double to) {
    if (sys.has_damping())
        throw InputError("the direct critical-speed method needs an undamped system; this one has damping "
                         "(use the branch method)");
    if (sys.has_circulatory())
        throw InputError("the direct critical-speed method needs a system without circulatory matrix N");
    if (!sys.bearings.empty())
        throw InputError("the direct critical-speed method needs speed-independent matrices; this model has "
                         "bearing tables (use the branch method)");
    if (harmonic < 1) throw InputError("harmonic must be >= 1");
    const double k = harmonic;
    const std::complex<double> I(0.0, 1.0);
    Eigen::MatrixXcd A = sys.K.cast<std::complex<double>>();
    Eigen::MatrixXcd B = (k * k) * sys.M.cast<std::complex<double>>();
    if (sys.G.size() > 0) B -= (I * k) * sys.G.cast<std::complex<double>>();
    if (sys.K2.size() > 0) B -= sys.K2.cast<std::complex<double>>();   // K + w^2 K2 stays linear in w^2
    const GeneralizedEigen ge = lapack_zggev(A, B);
    std::vector<CriticalSpeed> out;
    const double eps = std::numeric_limits<double>::epsilon();
    for (Eigen::Index j = 0; j < ge.alpha.size(); ++j) {
        if (std::abs(ge.beta_c(j)) <= 100 * eps * std::abs(ge.alpha(j))) continue;   // infinite
        const std::complex<double> mu = ge.alpha(j) / ge.beta_c(j);
        // Hermitian pencil: real mu up to rounding; mu = w^2 > 0.
        if (mu.real() <= 0.0 || std::abs(mu.imag()) > 1e-8 * std::abs(mu)) continue;
        const double w = std::sqrt(mu.real());
        if (w < from || w > to) continue;
        CriticalSpeed c;
        c.speed = w;
        c.harmonic = harmonic;
        c.mode.lambda = I * (k * w);
        c.mode.right = ge.right.col(j).normalized();
        c.mode.backward_error = backward_error(sys.at_speed(w), c.mode.lambda, c.mode.right);
        c.mode.whirl = classify_whirl(c.mode.lambda, c.mode.right, sys.whirl_pairs, 0.0);
        // Mode number: its rank by frequency among the modes at that speed.
        const QuadraticSpectrum sp = solve_at_speed(sys, w);
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < sp.modes.size(); ++i)
            if (std::abs(sp.modes[i].lambda - c.mode.lambda) < nearest) {
                nearest = std::abs(sp.modes[i].lambda - c.mode.lambda);
                c.branch = static_cast<int>(i) + 1;
            }
        out.push_back(std::move(c));
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
    return out;
}

}  // namespace gyrokit
