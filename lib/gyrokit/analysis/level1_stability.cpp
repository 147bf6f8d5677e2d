#include <gyrokit/analysis/level1_stability.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>
#include <gyrokit/solve/solver_choice.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>

namespace gyrokit {

namespace {

// The (x, y) DOFs of a node's shaft centre; InputError where it has no such pair.
std::pair<int, int> xy_of(const GyroscopicSystem& sys, int node) {
    const int x = sys.dofs.find(node, DofMotion::x), y = sys.dofs.find(node, DofMotion::y);
    if (node < 0 || node >= static_cast<int>(sys.node_z.size()) || x < 0 || y < 0)
        throw InputError(fmt::format("level1: station node {}: no lateral (x, y) pair there; allowed: a node of the "
                                     "rotor (0 to {}) with lateral motion, not held by a rigid support",
                                     node, static_cast<int>(sys.node_z.size()) - 1));
    return {x, y};
}

}  // namespace

GyroscopicSystem with_cross_coupling(const GyroscopicSystem& sys, const std::vector<CrossCouplingStation>& stations,
                                     double q) {
    GyroscopicSystem out = sys;
    std::vector<Eigen::Triplet<double>> t;
    for (const CrossCouplingStation& s : stations) {
        const auto [x, y] = xy_of(sys, s.node);
        t.emplace_back(x, y, s.share * q);
        t.emplace_back(y, x, -s.share * q);
    }
    SparseMatrix add(sys.size(), sys.size());
    add.setFromTriplets(t.begin(), t.end());
    out.K = SparseMatrix(static_cast<const SparseMatrix&>(sys.K) + add);
    return out;
}

namespace {

// Eigenvectors this close (|x^H y| of unit vectors) belong to one mode along a step.
constexpr double kSameMode = 0.9;
// A step between two points of the curve is halved at most this often in all.
constexpr int kMaxHalvings = 10;

class Follower {
public:
    Follower(const GyroscopicSystem& sys, const Level1Options& opt) : sys_(sys), opt_(opt) {
        dense_ = resolve_solver_kind(sys.size(), opt.solver.kind, 0) == SolverKind::Dense;
        if (dense_ && sys.size() > kDenseLimit)
            throw InputError(fmt::format("level1: the dense solver holds up to {} DOFs; this model has {}; allowed: "
                                         "solver auto or sparse",
                                         kDenseLimit, sys.size()));
    }

    // Every mode at Q (dense), or a window of modes near `near` (sparse).
    QuadraticSpectrum solve(double q, double near) {
        throw_if_interrupted();
        ++solves;
        const GyroscopicSystem s = with_cross_coupling(sys_, opt_.stations, q);
        QuadraticSpectrum sp;
        if (dense_) {
            sp = solve_at_speed(s, opt_.speed, opt_.solver.eig);
        } else {
            SolverOptions o = opt_.solver;
            o.kind = SolverKind::Sparse;
            o.modes = std::max(12, o.modes);
            o.target = near;
            o.target_order = 0.0;
            sp = choose_solver(s, o).make()(opt_.speed);
        }
        for (const std::string& n : sp.notes) note(n);
        return sp;
    }

    // The mode at q > q_from that continues `from`: steps from q_from to q, each step
    // accepted where pick() finds it clear; a step where it does not is halved, at most
    // kMaxHalvings times in all, and a step accepted undecided is noted once. `before`,
    // the followed mode at q_before < q_from, gives the first step its linear predictor.
    Mode step(const Mode& from, double q_from, double q, const Mode* before = nullptr, double q_before = 0.0) {
        Mode cur = from;
        double qc = q_from, h = q - q_from;
        std::optional<std::pair<double, std::complex<double>>> prev;
        if (before) prev.emplace(q_before, before->lambda);
        int halvings = 0;
        bool undecided = false;
        while (qc < q) {
            const double qn = qc + h >= q - 1e-12 * std::fabs(q) ? q : qc + h;
            const QuadraticSpectrum sp = solve(qn, std::fabs(cur.lambda.imag()));
            std::optional<std::complex<double>> predicted;
            if (prev && qc > prev->first)
                predicted = cur.lambda + (cur.lambda - prev->second) * ((qn - qc) / (qc - prev->first));
            const Pick p = pick(cur, sp, predicted);
            if (!p.clear && halvings < kMaxHalvings) {
                h *= 0.5;
                ++halvings;
                continue;
            }
            undecided = undecided || !p.clear;
            prev.emplace(qc, cur.lambda);
            cur = sp.modes[static_cast<std::size_t>(p.index)];
            qc = qn;
            h = std::min(2 * h, q - qc);   // back towards the full step after a decided one
        }
        if (undecided)
            note(fmt::format("the mode followed from Q = {:.6g} to {:.6g} N/m could not be told apart from a "
                             "neighbour at every step (eigenvector and nearest eigenvalue disagree)",
                             q_from, q));
        return cur;
    }

    int solves = 0;
    std::vector<std::string> notes;

private:
    struct Pick {
        int index = -1;
        bool clear = false;
    };
    // The candidate of the closest eigenvector (|x^H y| of unit vectors at least kSameMode)
    // that is also the nearest eigenvalue (to 1e-6: a double eigenvalue, forward and
    // backward whirl of an isotropic rotor without gyroscopic split, is as near as its
    // partner, and the vector decides). Heavily damped modes can share nearly one shape
    // (a runner-up overlap of kSameMode or more): then the eigenvalue alone decides, and
    // must have moved less than half the way to the next nearest and, where the step has a
    // linear predictor from the last two points, also be the eigenvalue nearest to it.
    static Pick pick(const Mode& from, const QuadraticSpectrum& sp, std::optional<std::complex<double>> predicted) {
        Pick p;
        double best_c = -1.0, second_c = -1.0;
        double near_d = std::numeric_limits<double>::infinity(), next_d = near_d;   // the two nearest eigenvalues
        double pred_d = near_d;                                                     // nearest to the prediction
        int pred_index = -1;
        for (std::size_t i = 0; i < sp.modes.size(); ++i) {
            const double c = std::abs(from.right.dot(sp.modes[i].right));   // dot: conjugates the first
            if (c > best_c) {
                second_c = best_c;
                best_c = c;
                p.index = static_cast<int>(i);
            } else if (c > second_c) {
                second_c = c;
            }
            const double d = std::abs(sp.modes[i].lambda - from.lambda);
            if (d < near_d) {
                next_d = near_d;
                near_d = d;
            } else if (d < next_d) {
                next_d = d;
            }
            if (predicted && std::abs(sp.modes[i].lambda - *predicted) < pred_d) {
                pred_d = std::abs(sp.modes[i].lambda - *predicted);
                pred_index = static_cast<int>(i);
            }
        }
        if (p.index < 0) throw SolverError("level1: no mode to follow (the solver returned none)");
        const double d = std::abs(sp.modes[static_cast<std::size_t>(p.index)].lambda - from.lambda);
        const bool nearest = d <= near_d * (1 + 1e-6) + 1e-300;
        const bool by_value = d < 0.5 * next_d && (!predicted || pred_index == p.index);
        p.clear = best_c >= kSameMode && nearest && (second_c < kSameMode || by_value);
        return p;
    }
    void note(const std::string& n) {
        if (std::find(notes.begin(), notes.end(), n) == notes.end()) notes.push_back(n);
    }

    const GyroscopicSystem& sys_;
    const Level1Options& opt_;
    bool dense_ = true;
};

Level1Point point_of(double q, const Mode& m) {
    Level1Point p;
    p.q = q;
    p.lambda = m.lambda;
    p.error_bound = m.error_bound;
    p.log_decrement = m.log_decrement();
    p.whirl = m.whirl;
    return p;
}

void check(const GyroscopicSystem& sys, const Level1Options& o) {
    if (!(std::isfinite(o.speed) && o.speed > 0))
        throw InputError(fmt::format("level1: speed = {}; allowed: a finite speed > 0 (rad/s)", o.speed));
    if (!(std::isfinite(o.q_max) && o.q_max > 0))
        throw InputError(fmt::format("level1: q_max = {}; allowed: a finite stiffness > 0 (N/m)", o.q_max));
    if (o.intervals < 2 || o.intervals > 10000)
        throw InputError(fmt::format("level1: intervals = {}; allowed: [2, 10000]", o.intervals));
    for (const double m : o.marks)
        if (!(m > 0 && m <= o.q_max))
            throw InputError(fmt::format("level1: Q = {} N/m to mark; allowed: (0, q_max = {}]", m, o.q_max));
    if (o.stations.empty()) throw InputError("level1: no station for the cross-coupling; required: at least one node");
    double shares = 0.0;
    for (const CrossCouplingStation& s : o.stations) {
        xy_of(sys, s.node);
        if (!(std::isfinite(s.share) && s.share > 0))
            throw InputError(fmt::format("level1: station share {}; allowed: > 0", s.share));
        shares += s.share;
    }
    if (std::fabs(shares - 1.0) > 1e-12)
        throw InputError(fmt::format("level1: the stations' shares sum to {}; allowed: 1", shares));
}

// A mode's orbit where Q acts (the largest over the stations) against its largest orbit
// over the rotor's nodes, each orbit sqrt(|x|^2 + |y|^2).
double station_orbit_ratio(const GyroscopicSystem& sys, const std::vector<CrossCouplingStation>& stations,
                           const Mode& m) {
    const auto orbit = [&](int node) {
        const int x = sys.dofs.find(node, DofMotion::x), y = sys.dofs.find(node, DofMotion::y);
        if (x < 0 || y < 0) return 0.0;
        return std::sqrt(std::norm(m.right[x]) + std::norm(m.right[y]));
    };
    double largest = 0.0, at = 0.0;
    for (int node = 0; node < static_cast<int>(sys.node_z.size()); ++node) largest = std::max(largest, orbit(node));
    for (const CrossCouplingStation& s : stations) at = std::max(at, orbit(s.node));
    return largest > 0 ? at / largest : 1.0;   // no node orbits to compare (a bare matrix model): Q loads it
}

// The first forward mode Q loads: the lowest oscillating mode that whirls forward and
// moves where Q acts (kLevel1MinStationOrbit of its largest orbit); the lower forward
// modes passed over go to `passed`.
Mode first_forward(const GyroscopicSystem& sys, const Level1Options& o, const QuadraticSpectrum& sp,
                   std::vector<PassedMode>& passed) {
    for (const Mode& m : sp.modes) {
        if (m.whirl != Whirl::Forward || !(m.lambda.imag() > sp.real_tol)) continue;
        const double r = station_orbit_ratio(sys, o.stations, m);
        if (r >= kLevel1MinStationOrbit) return m;
        passed.push_back({m.lambda, m.error_bound, m.log_decrement(), r});
    }
    throw InputError(fmt::format("level1: the rotor has no forward-whirling mode at {} rad/s with Q = 0 that moves "
                                 "where Q acts (its modes: {}); Level I follows the first forward mode",
                                 o.speed, sp.modes.size()));
}

// Q0 between a (stable) and b (unstable) on the followed mode: regula falsi with the
// Illinois rule (a bracket that shrinks from both ends, superlinearly), until the bracket
// is below 1e-10 b or Re(lambda) lies within its error bound.
void bracket_q0(Follower& f, Level1Curve& c, Mode ma, double a, Mode mb, double b) {
    double fa = ma.lambda.real(), fb = mb.lambda.real();
    const double slope0 = (fb - fa) / (b - a);   // Re(lambda) rises across the bracket
    int side = 0;
    for (int it = 0; it < 100 && b - a > 1e-10 * b; ++it) {
        double m = (a * fb - b * fa) / (fb - fa);
        m = std::min(std::max(m, a + 1e-3 * (b - a)), b - 1e-3 * (b - a));
        const Mode mm = f.step(ma, a, m);
        const double re = mm.lambda.real();
        if (std::fabs(re) <= mm.error_bound) {   // neutral within its bound: as tight as the eigenvalue allows
            a = b = m;
            ma = mb = mm;
            break;
        }
        if (re < 0) {
            a = m, ma = mm, fa = re;
            if (side == -1) fb *= 0.5;   // Illinois: the end kept twice gives way
            side = -1;
        } else {
            b = m, mb = mm, fb = re;
            if (side == 1) fa *= 0.5;
            side = 1;
        }
    }
    const double slope = b > a ? (mb.lambda.real() - ma.lambda.real()) / (b - a) : slope0;
    const double eb = std::max(ma.error_bound, mb.error_bound);
    c.q0 = 0.5 * (a + b);
    c.q0_bound = 0.5 * (b - a) + (slope > 0 ? eb / slope : std::numeric_limits<double>::infinity());
}

}  // namespace

Level1Curve level1_curve(const GyroscopicSystem& sys, const Level1Options& opt) {
    check(sys, opt);
    // The grid, a grid value within rounding of a mark giving way to the mark.
    std::vector<double> qs(opt.marks);
    for (int i = 0; i <= opt.intervals; ++i) {
        const double q = i == opt.intervals ? opt.q_max : opt.q_max * i / opt.intervals;
        if (std::none_of(opt.marks.begin(), opt.marks.end(),
                         [&](double m) { return std::fabs(m - q) <= 1e-9 * opt.q_max; }))
            qs.push_back(q);
    }
    std::sort(qs.begin(), qs.end());
    qs.erase(std::unique(qs.begin(), qs.end()), qs.end());

    Follower f(sys, opt);
    Level1Curve c;
    std::vector<Mode> modes{first_forward(sys, opt, f.solve(0.0, 0.0), c.passed)};
    c.points.push_back(point_of(0.0, modes[0]));
    const auto unstable = [](const Mode& m) { return m.lambda.real() > m.error_bound; };
    // Unstable, or neutral within its bound (no damping): any Q > 0 destabilises it.
    if (modes[0].lambda.real() >= -modes[0].error_bound) {
        c.q0 = 0.0;
        c.q0_bound = 0.0;
    }
    for (std::size_t i = 1; i < qs.size(); ++i) {
        const Mode* before = i >= 2 ? &modes[i - 2] : nullptr;
        modes.push_back(f.step(modes.back(), qs[i - 1], qs[i], before, i >= 2 ? qs[i - 2] : 0.0));
        c.points.push_back(point_of(qs[i], modes.back()));
        if (!c.q0 && unstable(modes.back())) {
            // The bracket's stable end: the last point whose eigenvalue lies left of zero.
            std::size_t a = i - 1;
            while (a > 0 && modes[a].lambda.real() >= 0) --a;
            bracket_q0(f, c, modes[a], qs[a], modes[i], qs[i]);
        }
    }
    c.solves = f.solves;
    c.notes = f.notes;
    return c;
}

double region_b_boundary(double rho) {
    if (rho <= 16.53) return 2.5;
    if (rho <= 60.0) return 2.69 - 0.0115 * rho;
    return 0.0;
}

std::size_t governing_screen(const std::vector<Level1Screen>& screens) {
    if (screens.empty()) throw Error("governing_screen: no screen");
    // Q0/QA, with no Q0 in the range as infinitely large (it lies beyond the curve).
    const auto ratio = [](const Level1Screen& s) {
        return s.curve.q0 ? *s.curve.q0 / s.qa : std::numeric_limits<double>::infinity();
    };
    std::size_t worst = 0;
    for (std::size_t i = 1; i < screens.size(); ++i) {
        const Level1Screen &a = screens[i], &b = screens[worst];
        if (a.level2_required != b.level2_required) {
            if (a.level2_required) worst = i;
            continue;
        }
        if (ratio(a) != ratio(b)) {
            if (ratio(a) < ratio(b)) worst = i;
            continue;
        }
        if (a.at_qa.log_decrement < b.at_qa.log_decrement) worst = i;
    }
    return worst;
}

std::string passed_text(const PassedMode& m, const SpeedUnit& unit) {
    return fmt::format("the forward mode at {:.6g} {} (log decrement {:.3g}) barely moves where Q acts (its orbit "
                       "there is {:.2g} of its largest, below {}): Q does not load it, and the next forward mode is "
                       "followed",
                       unit.factor * m.lambda.imag(), unit.name, m.log_decrement, m.orbit_ratio,
                       kLevel1MinStationOrbit);
}

}  // namespace gyrokit
