#include <gyrokit/analysis/critical_speeds.hpp>

#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/error.hpp>
#include "gyrokit/eig/lapack.hpp"
#include <gyrokit/eig/sharp_bound.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>

namespace gyrokit {

namespace {

// An interval [i, i + 1] of a branch holding a change, and how to refine it:
// a root of g (sign change) or the edge of a predicate (bisection).
struct Interval {
    const Branch* branch;
    size_t i;
    double g0, g1;
};

// A refined root and its bound (rad/s; 0 where none is computed).
struct Root {
    double speed = 0.0, bound = 0.0;
};


// Every interval of every oscillating branch that `holds` accepts, refined on
// `workers` (each search is independent) by `refine(mode_at, interval)`, then
// emitted in branch order. A solver of a window of modes refines each interval
// on a window centred on the branch's own frequency (SolverFactory::centred), so
// that the sweep's window cannot move the root.
template <class Holds, class Refine, class Emit>
void scan_branches(const SolverFactory& make, const CampbellDiagram& cd, const Holds& holds, const Refine& refine,
                   Workers workers, const Emit& emit, bool real_ends = false) {
    std::vector<Interval> found;
    // The shown branches and the other modes up to the band (judged, with their vectors).
    std::vector<const Branch*> judged;
    for (const Branch& b : cd.branches) judged.push_back(&b);
    for (const Branch& b : cd.untracked)
        if (!b.points.empty() && b.points.front().mode.right.size() > 0) judged.push_back(&b);
    for (const Branch* bp : judged) {
        const Branch& b = *bp;
        for (size_t i = 0; i + 1 < b.points.size(); ++i) {
            const Mode& m0 = b.points[i].mode;
            const Mode& m1 = b.points[i + 1].mode;
            // A pair that turns overdamped (or back) between two points still crosses a line
            // it was above: Im lambda falls continuously to 0 at the exceptional point
            // (real_ends: the crossings; a stability change keeps to oscillating ends).
            if (real_ends ? m0.whirl == Whirl::Real && m1.whirl == Whirl::Real
                          : m0.whirl == Whirl::Real || m1.whirl == Whirl::Real)
                continue;
            Interval iv{&b, i, 0.0, 0.0};
            if (holds(m0, b.points[i].speed, m1, b.points[i + 1].speed, iv)) found.push_back(iv);
        }
    }
    const std::vector<QuadraticSpectrum> roots =
        run_on_workers(make, found.size(), workers, [&](SpectrumSolver& solve, size_t k) {
            const Branch& b = *found[k].branch;
            const size_t i = found[k].i;
            SpectrumSolver own = make.has_centred() ? make.centred(b.points[i].mode.lambda.imag()) : SpectrumSolver{};
            SpectrumSolver& use = make.has_centred() ? own : solve;
            const auto mode_at = [&](double w) -> Mode {
                if (make.can_follow()) {   // the branch's mode followed from the nearer end
                    const BranchPoint& p0 = b.points[i];
                    const BranchPoint& p1 = b.points[i + 1];
                    const double t = p1.speed > p0.speed ? (w - p0.speed) / (p1.speed - p0.speed) : 0.0;
                    const BranchPoint& near = t < 0.5 ? p0 : p1;
                    const std::complex<double> predicted = (1.0 - t) * p0.mode.lambda + t * p1.mode.lambda;
                    if (auto m = make.follow(near.mode, w, predicted, 0.3 * eigenvalue_gap(cd, b, near))) return *m;
                }
                return continue_branch(b, i, w, use(w));
            };
            const Root r = refine(mode_at, found[k]);
            QuadraticSpectrum s;
            s.speed = r.speed;
            s.speed_bound = r.bound;
            s.modes.push_back(mode_at(s.speed));
            return s;
        });
    for (size_t k = 0; k < found.size(); ++k)
        emit(*found[k].branch, roots[k].speed, roots[k].speed_bound, roots[k].modes.at(0));
}

// Last speed in [a, b] on the side of a where `unstable(w)` equals its value at
// a, by bisection to a relative width of 1e-12: the edge of the unstable range
// where one side is neutral and the real part is rounding there (no root of
// Re lambda to converge to).
template <class Pred>
double bisect_edge(const Pred& unstable, double a, double b) {
    const bool at_a = unstable(a);
    for (int it = 0; it < 200 && b - a > 1e-12 * std::max(std::abs(a), std::abs(b)); ++it) {
        const double m = 0.5 * (a + b);
        (unstable(m) == at_a ? a : b) = m;
    }
    return 0.5 * (a + b);
}

// A part of the eigenvalue at w minus its line (Re lambda: a stability threshold;
// Im lambda - k w: a crossing), and that part's error bound.
struct Measured {
    double g = 0.0, error = 0.0;
};
using Part = std::function<double(const Mode&, double)>;
double real_part(const Mode& m, double) { return m.lambda.real(); }

// The part at w, measured as sharply as the solver allows: where it gives the model's
// pencil, on the mode polished there (refine_eigenpair: right and left vectors and the
// eigenvalue to rounding) and corrected by Newton's step in extended precision
// (sharp_eigenvalue), with what is left of its error; else, or where the polish left
// the mode (another eigenvalue, another shape) or the first order does not hold (an
// exceptional point), on the mode as it is, with its own bound.
std::function<Measured(const Mode&, double)> measured_part(const SolverFactory& solver, Part g, bool real) {
    if (!solver.has_pencil()) return [g](const Mode& m, double w) { return Measured{g(m, w), m.error_bound}; };
    return [&solver, g, real](const Mode& m, double w) {
        const Measured plain{g(m, w), m.error_bound};
        if (!std::isfinite(m.error_bound)) return plain;   // (the polish finds a missing left vector)
        const SparsePencil p = solver.pencil(w);
        Mode polished = m;
        (void)refine_eigenpair(p, sparse_pencil_action(p), polished, 0.0, std::max(std::abs(m.lambda), 1.0));
        if (!(std::abs(polished.lambda - m.lambda) <= std::max(m.error_bound, 1e-10 * std::abs(m.lambda))) ||
            !(mac(polished.right, m.right) >= 0.99))
            return plain;
        const SharpEigenvalue sharp = sharp_eigenvalue(polished, p);
        const double e = real ? sharp.real : sharp.imag;
        if (!(e < m.error_bound)) return plain;
        polished.lambda = sharp.lambda;
        return Measured{g(polished, w), e};
    };
}

// Bound on a root w in [a, b] (rad/s) of g: the part g measured at w is within e of the
// exact one (measure), so the exact root lies where |g| <= e: to first order within
// (|g(w)| + e) / |dg/dw| of w. The slope is a difference over a step that resolves it
// above the noise of the followed modes (up to the interval), and the bound is never
// below the search's own resolution `resolution`.
template <class ModeAt, class Measure>
double root_bound(const ModeAt& mode_at, const Part& g, const Measure& measure, double w, double a, double b,
                  double resolution) {
    const Mode m = mode_at(w);
    const Measured at = measure(m, w);
    const double e = at.error;
    if (!std::isfinite(e) || !(b > a)) return std::numeric_limits<double>::infinity();
    // The slope's differences are of the modes as followed, whose noise is their own bound.
    const double noise = std::max(e, m.error_bound);
    double slope = 0.0;
    for (double h = 1e-6 * (b - a); h <= b - a; h *= 10.0) {
        const double lo = std::max(a, w - h), hi = std::min(b, w + h);
        const double dg = g(mode_at(hi), hi) - g(mode_at(lo), lo);
        slope = dg / (hi - lo);
        if (std::abs(dg) >= 100.0 * noise || hi - lo >= b - a) break;
    }
    if (!(std::abs(slope) > 0.0)) return std::numeric_limits<double>::infinity();
    return std::max((std::abs(at.g) + e) / std::abs(slope), resolution);
}

}  // namespace

std::vector<CriticalSpeed> critical_speeds(const GyroscopicSystem& sys, const CampbellDiagram& cd,
                                           const std::vector<int>& harmonics, const EigenOptions& eig) {
    return critical_speeds(dense_solver(sys, eig), cd, harmonics);
}

std::vector<CriticalSpeed> critical_speeds(const SolverFactory& solver, const CampbellDiagram& cd,
                                           const std::vector<int>& harmonics, Workers workers) {
    std::vector<CriticalSpeed> out;
    for (int k : harmonics) {
        if (k < 1) throw InputError("harmonic " + std::to_string(k) + " is not allowed; allowed: k >= 1");
        const auto g = [k](const Mode& m, double w) { return m.lambda.imag() - k * w; };
        const auto holds = [&](const Mode& m0, double w0, const Mode& m1, double w1, Interval& iv) {
            // A mode that moves no whirl pair (axial, torsional) is not excited by the
            // rotor's unbalance or the spin harmonics: no critical speed.
            if (m0.whirl == Whirl::None && m1.whirl == Whirl::None) return false;
            if ((m0.whirl == Whirl::None && m1.whirl == Whirl::Real) || (m0.whirl == Whirl::Real && m1.whirl == Whirl::None))
                return false;
            iv.g0 = g(m0, w0);
            iv.g1 = g(m1, w1);
            if (iv.g0 == 0.0 && iv.i > 0) return false;   // counted as the end of the previous interval
            return !((iv.g0 > 0) == (iv.g1 > 0) && iv.g0 != 0.0 && iv.g1 != 0.0);
        };
        const auto refine = [&](const auto& mode_at, const Interval& iv) {
            const auto& p = iv.branch->points;
            const double a = p[iv.i].speed, b = p[iv.i + 1].speed;
            const double w = find_root([&](double x) { return g(mode_at(x), x); }, a, b);
            return Root{w, root_bound(mode_at, g, measured_part(solver, g, false), w, a, b, 4e-13 * std::abs(w))};
        };
        scan_branches(solver, cd, holds, refine, workers, [&](const Branch& b, double w, double bound, Mode m) {
            // A root is a crossing only where the mode lies on the line: a branch that jumps
            // between two points (a real eigenvalue matched to a pair far above it) changes
            // the sign of Im lambda - k w without crossing, and the search ends at the jump.
            // A real eigenvalue lies "on" every line at standstill and crosses none: the
            // mode at a crossing vibrates.
            if (std::abs(g(m, w)) <= 1e-6 * k * std::max(w, 1.0) && m.whirl != Whirl::Real && m.lambda.imag() > 0.0)
                out.push_back({w, bound, k, b.id, std::move(m)});
        }, true);
    }
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
    return out;
}

std::vector<StabilityChange> stability_changes(const GyroscopicSystem& sys, const CampbellDiagram& cd,
                                               const EigenOptions& eig) {
    return stability_changes(dense_solver(sys, eig), cd);
}

std::vector<StabilityChange> stability_changes(const SolverFactory& solver, const CampbellDiagram& cd, Workers workers) {
    std::vector<StabilityChange> out;
    const auto unstable = [](const Mode& m) { return m.stability() == Stability::Unstable; };
    // A change: one end unstable, the other not (stable or neutral); g holds Re lambda.
    const auto holds = [&](const Mode& m0, double, const Mode& m1, double, Interval& iv) {
        iv.g0 = m0.lambda.real();
        iv.g1 = m1.lambda.real();
        return unstable(m0) != unstable(m1);
    };
    const auto refine = [&](const auto& mode_at, const Interval& iv) {
        const auto& p = iv.branch->points;
        const Mode& m0 = p[iv.i].mode;
        const Mode& m1 = p[iv.i + 1].mode;
        const double a = p[iv.i].speed, b = p[iv.i + 1].speed;
        // Both ends decided (stable and unstable): the real part crosses zero, Brent
        // finds it (relative tolerance 1e-13). Next to a neutral end, where Re lambda is
        // rounding and may change sign anywhere, the edge of the unstable range is bisected.
        if (m0.stability() != Stability::Neutral && m1.stability() != Stability::Neutral) {
            const double w = find_root([&](double x) { return mode_at(x).lambda.real(); }, a, b);
            return Root{w, root_bound(mode_at, real_part, measured_part(solver, real_part, true), w, a, b, 4e-13 * std::abs(w))};
        }
        const double w = bisect_edge([&](double x) { return unstable(mode_at(x)); }, a, b);
        return Root{w, root_bound(mode_at, real_part, measured_part(solver, real_part, true), w, a, b, 2e-12 * std::abs(w))};
    };
    scan_branches(solver, cd, holds, refine, workers, [&](const Branch& b, double w, double bound, Mode m) {
        const auto& p = b.points;
        const auto it = std::find_if(p.begin(), p.end(), [&](const BranchPoint& q) { return q.speed >= w; });
        const bool after = it != p.end() ? unstable(it->mode) : unstable(p.back().mode);
        out.push_back({w, bound, b.id, after, std::move(m)});
    });
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
    return out;
}

std::vector<UnstableRange> unstable_ranges(const CampbellDiagram& cd, bool every_mode) {
    std::vector<UnstableRange> out;
    std::vector<const Branch*> branches;
    for (const Branch& b : cd.branches) branches.push_back(&b);
    if (every_mode)
        for (const Branch& b : cd.untracked) branches.push_back(&b);
    for (const Branch* bp : branches) {
        const Branch& b = *bp;
        for (size_t i = 0; i < b.points.size(); ++i) {
            const Mode& m = b.points[i].mode;
            if (m.stability() != Stability::Unstable) continue;
            if (!out.empty() && out.back().branch == b.id && out.back().last_index + 1 == i) {
                out.back().to = b.points[i].speed;
                out.back().last_index = i;
                out.back().max_real = std::max(out.back().max_real, m.lambda.real());
                continue;
            }
            UnstableRange r;
            r.branch = b.id;
            r.from = r.to = b.points[i].speed;
            r.max_real = m.lambda.real();
            r.first_index = r.last_index = i;
            out.push_back(r);
        }
        for (UnstableRange& r : out)
            if (r.branch == b.id) r.to_last = r.last_index + 1 == b.points.size();
    }
    return out;
}

std::vector<UnstableRange> refine_edges(std::vector<UnstableRange> ranges, const CampbellDiagram& cd,
                                        const std::vector<StabilityChange>& changes) {
    const auto points_of = [&](int id) -> const std::vector<BranchPoint>* {
        for (const auto* list : {&cd.branches, &cd.untracked})
            for (const Branch& b : *list)
                if (b.id == id) return &b.points;
        return nullptr;
    };
    for (UnstableRange& r : ranges) {
        const std::vector<BranchPoint>* p = points_of(r.branch);
        if (!p || r.last_index >= p->size()) continue;
        for (const StabilityChange& c : changes) {
            if (c.branch != r.branch) continue;
            // The onset lies in the step before the first unstable point, the end in the
            // step after the last one.
            if (c.becomes_unstable && r.first_index > 0 && c.speed >= (*p)[r.first_index - 1].speed &&
                c.speed <= (*p)[r.first_index].speed) {
                r.from = c.speed;
                r.from_bound = c.bound;
                r.from_refined = true;
            }
            if (!c.becomes_unstable && r.last_index + 1 < p->size() && c.speed >= (*p)[r.last_index].speed &&
                c.speed <= (*p)[r.last_index + 1].speed) {
                r.to = c.speed;
                r.to_bound = c.bound;
                r.to_refined = true;
            }
        }
    }
    return ranges;
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
        // The bound: the pencil is Hermitian, so its left vector is x and to first order the exact
        // w^2 is mu + x^H r / x^H B x (r = A x - mu B x); twice that, plus the rounding of r
        // (n + 3 products a row, each within eps of |A| |x| + mu |B| |x|), over d(w^2)/dw = 2 w.
        {
            const Eigen::VectorXcd& x = c.mode.right;
            const Eigen::VectorXcd Bx = B * x;
            const Eigen::VectorXcd r = A * x - mu.real() * Bx;
            const Eigen::VectorXd ax = x.cwiseAbs();
            const double scale = ax.dot(A.cwiseAbs() * ax + mu.real() * (B.cwiseAbs() * ax));
            const double terms = static_cast<double>(A.rows()) + 3.0;
            const double dmu = 2.0 * (std::abs(x.dot(r)) + terms * eps * scale) / std::abs(x.dot(Bx));
            c.bound = std::isfinite(dmu) ? dmu / (2.0 * w) + eps * w : std::numeric_limits<double>::infinity();
        }
        c.mode.whirl = classify_whirl(c.mode.lambda, c.mode.right, sys.whirl_pairs, 0.0);
        if (c.mode.whirl == Whirl::None) continue;   // axial or torsional: not a critical speed
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
