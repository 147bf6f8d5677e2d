// The bounds of stability thresholds and critical speeds against an independent root
// search: the eigenvalue at each speed refined by Newton's method on the bordered
// quadratic in long double (residuals 2^11 times finer than the library's; above 40 DOFs
// the residual in long double, the correction from a double sparse LU), the root
// of Re lambda (a threshold) or Im lambda - k w (a crossing) by the Illinois method on
// it. Each printed speed lies within its bound of that root (the bound covers the
// truth), and the bound is at most 100 times the larger of the distance and the root's
// own uncertainty (how far the data's rounding moves it: the reference's scatter about a
// straight line near the root), or 1e-9 of the speed (the bound is tight).
#include "rotor_family.hpp"

#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/rotor_study.hpp>

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <vector>

using namespace gyrokit;

namespace {

using Real = long double;
using Complex = std::complex<Real>;
using MatrixL = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
using VectorL = Eigen::Matrix<Complex, Eigen::Dynamic, 1>;

// The eigenvalue of the pencil at w nearest the start, by Newton's method on
// [P(l) x; c^H x - 1] = 0 with its residual in long double (the pencil's entries as
// stored). `correction(it, l, x, c, f)` gives the step [dx; dl] for the residual f.
struct Refined {
    Complex lambda;
    VectorL x;
};
template <class Correction>
Refined bordered_newton(Refined start, int iterations, const Correction& correction) {
    const Eigen::Index n = start.x.size();
    const VectorL c = start.x / start.x.squaredNorm();
    Refined r = start;
    r.x /= c.dot(r.x);
    for (int it = 0; it < iterations; ++it) {
        const std::optional<VectorL> d = correction(it, r.lambda, r.x, c);
        if (!d) break;
        r.x += d->head(n);
        r.lambda += (*d)(n);
        if (it >= 1 && std::abs((*d)(n)) <= 1e-17L * std::abs(r.lambda)) break;
    }
    return r;
}

// Small pencils: the Jacobian in long double too, a dense LU.
Refined newton(const QuadraticPencil& p, Refined start) {
    const Eigen::Index n = p.M.rows();
    const MatrixL M = p.M.cast<Real>().cast<Complex>(), C = p.C.cast<Real>().cast<Complex>(),
                  K = p.K.cast<Real>().cast<Complex>();
    return bordered_newton(start, 12, [&](int, Complex l, const VectorL& x, const VectorL& c) {
        MatrixL J(n + 1, n + 1);
        J.topLeftCorner(n, n) = l * l * M + l * C + K;
        J.topRightCorner(n, 1) = (Real(2) * l * M + C) * x;
        J.bottomLeftCorner(1, n) = c.adjoint();
        J(n, n) = 0;
        VectorL f(n + 1);
        f.head(n) = J.topLeftCorner(n, n) * x;
        f(n) = c.dot(x) - Real(1);
        return std::optional<VectorL>(J.partialPivLu().solve(-f));
    });
}

// Large sparse pencils in mixed precision: the residual in long double, the correction
// from a sparse LU of the bordered Jacobian in double (iterative refinement: each step
// gains the Jacobian's condition times 1e-16, so the iteration reaches the long-double
// residual's level).
using SparseL = Eigen::SparseMatrix<Complex>;
using SparseD = Eigen::SparseMatrix<std::complex<double>>;
Refined newton_mixed(const SparsePencil& p, Refined start) {
    const Eigen::Index n = p.M.rows();
    const SparseL M = p.M.cast<Real>().cast<Complex>(), C = p.C.cast<Real>().cast<Complex>(),
                  K = p.K.cast<Real>().cast<Complex>();
    Eigen::SparseLU<SparseD> lu;
    return bordered_newton(start, 40, [&](int it, Complex l, const VectorL& x, const VectorL& c) {
        const SparseL P = (l * l) * M + l * C + K;
        if (it % 4 == 0) {   // the Jacobian in double, refreshed now and then
            const VectorL dP = (Real(2) * l) * (M * x) + C * x;
            std::vector<Eigen::Triplet<std::complex<double>>> t;
            for (Eigen::Index j = 0; j < P.outerSize(); ++j)
                for (SparseL::InnerIterator e(P, j); e; ++e)
                    t.emplace_back(e.row(), e.col(), std::complex<double>(e.value()));
            for (Eigen::Index i = 0; i < n; ++i) {
                t.emplace_back(i, n, std::complex<double>(dP(i)));
                t.emplace_back(n, i, std::complex<double>(std::conj(c(i))));
            }
            SparseD J(n + 1, n + 1);
            J.setFromTriplets(t.begin(), t.end());
            lu.compute(J);
            if (lu.info() != Eigen::Success) return std::optional<VectorL>();
        }
        VectorL f(n + 1);
        f.head(n) = P * x;
        f(n) = c.dot(x) - Real(1);
        const Eigen::VectorXcd fd = f.unaryExpr([](const Complex& z) { return std::complex<double>(z); });
        const Eigen::VectorXcd dd = lu.solve(-fd);
        return std::optional<VectorL>(dd.unaryExpr([](const std::complex<double>& z) { return Complex(z); }));
    });
}

// Above this many DOFs the reference takes the mixed-precision iteration (a dense
// long-double LU of 337 would take seconds per step; on every scene and seeded rotor
// here the two iterations give roots within each other's scatter).
constexpr int kMixedPrecisionDofs = 40;

// A scalar function of the speed on the reference's eigenvalue, warm-started from
// the nearest evaluation.
struct Branch {
    const GyroscopicSystem& sys;
    Refined last;
    Complex at(double w) {
        last = sys.size() > kMixedPrecisionDofs ? newton_mixed(sys.sparse_at_speed(w), last)
                                                : newton(sys.at_speed(w), last);
        return last.lambda;
    }
};

// The root of f in [a, b] (f(a), f(b) of opposite signs) by the Illinois method to a
// relative width of 1e-15.
double illinois(const std::function<Real(double)>& f, double a, double b) {
    Real fa = f(a), fb = f(b);
    int side = 0;
    for (int it = 0; it < 100 && b - a > 1e-15 * std::abs(b); ++it) {
        const double c = static_cast<double>((a * fb - b * fa) / (fb - fa));
        if (!(c > a && c < b)) break;
        const Real fc = f(c);
        if ((fc > 0) == (fb > 0)) {
            b = c, fb = fc;
            if (side == -1) fa /= 2;
            side = -1;
        } else {
            a = c, fa = fc;
            if (side == 1) fb /= 2;
            side = 1;
        }
    }
    return std::abs(fa) < std::abs(fb) ? a : b;
}

struct Reference {
    double root = 0.0;
    double scatter = 0.0;   // rad/s: the root's uncertainty from the data's rounding
    bool found = false;
};

// The root of g near w (bracket grown from `h` until g changes sign), and the scatter of g
// about its chord over 2 h around the root, divided by the slope.
Reference reference_root(const std::function<Real(double)>& g, double w, double h) {
    Reference r;
    for (int grow = 0; grow < 12 && !r.found; ++grow, h *= 4.0) {
        const Real lo = g(w - h), hi = g(w + h);
        if ((lo > 0) == (hi > 0)) continue;
        r.root = illinois(g, w - h, w + h);
        r.found = true;
    }
    if (!r.found) return r;
    const double s = std::max(1e-9 * std::abs(r.root), 1e-12);
    const Real g0 = g(r.root - s), g1 = g(r.root + s);
    const Real slope = (g1 - g0) / Real(2 * s);
    Real worst = 0;
    for (int k = -2; k <= 2; ++k) {
        const double x = r.root + 0.5 * k * s;
        const Real line = g0 + slope * Real(x - (r.root - s));
        worst = std::max(worst, std::abs(g(x) - line));
    }
    r.scatter = slope != 0 ? static_cast<double>(worst / std::abs(slope)) : 0.0;
    return r;
}

Refined start_of(const Mode& m) {
    return {Complex(m.lambda.real(), m.lambda.imag()), m.right.cast<Complex>()};
}

int checked = 0;

void check_bound(double speed, double bound, const Reference& ref) {
    CAPTURE(speed, bound, ref.root, ref.scatter, speed - ref.root);
    REQUIRE(ref.found);
    ++checked;
    const double distance = std::abs(speed - ref.root);
    CHECK(distance <= bound);
    CHECK(bound <= std::max(100.0 * std::max(distance, ref.scatter), 1e-9 * std::abs(speed)));
}

void check_system(const GyroscopicSystem& sys, const StudyOptions& opt) {
    const StabilityStudy st = stability_study(sys, opt);
    for (const StabilityChange& c : st.changes) {
        CAPTURE(c.branch);
        Branch b{sys, start_of(c.mode)};
        const Reference ref = reference_root([&](double w) { return b.at(w).real(); }, c.speed,
                                             std::max(2.0 * c.bound, 1e-9 * c.speed));
        check_bound(c.speed, c.bound, ref);
    }
    const std::vector<CriticalSpeed> cs = critical_speeds_of(sys, st.tracked, opt);
    for (const CriticalSpeed& c : cs) {
        CAPTURE(c.branch, c.harmonic);
        Branch b{sys, start_of(c.mode)};
        const Reference ref = reference_root([&](double w) { return b.at(w).imag() - Real(c.harmonic) * w; },
                                             c.speed, std::max(2.0 * c.bound, 1e-9 * c.speed));
        check_bound(c.speed, c.bound, ref);
    }
}

void check_scene(const std::string& name) {
    INFO(name);
    const Scene sc = load_scene(std::string(GYROKIT_DATA_DIR) + "/" + name);
    StudyOptions opt = study_options(sc);
    opt.amplification_factors = false;   // not what is checked here
    check_system(sc.system, opt);
}

}  // namespace

TEST_CASE("thresholds and critical speeds lie within tight bounds of an independent long-double root",
          "[bounds][scenes]") {
    checked = 0;
    // Every dense data/ scene with a speed range (the fluid-filled rotors have no threshold
    // or crossing in theirs: they are solved, nothing is checked), and the ROSS example
    // (a model no one here wrote); compressor336, on the sparse path, in the case below.
    for (const std::string name :
         {"three_disk_rotor_journal.toml", "fe_rotor.toml", "compressor.toml", "drive_train.toml",
          "three_disk_rotor.toml", "centrifuge.toml", "friswell_5_9_1.toml", "fluid_N1.toml", "fluid_N2.toml",
          "fluid_N3.toml", "fluid_N4.toml", "ross_rotor_example/scene.toml"})
        check_scene(name);
    CHECK(checked >= 50);
    checked = 0;
}

TEST_CASE("the sparse path's thresholds and critical speeds lie within tight bounds of a mixed-precision root",
          "[bounds][scenes]") {
    // data/compressor336.toml (336 DOFs: the sparse window by default); the reference
    // iterates with the residual in long double on a double sparse LU.
    checked = 0;
    check_scene("compressor336.toml");
    CHECK(checked >= 5);
    checked = 0;
}

TEST_CASE("thresholds and critical speeds of seeded random FE rotors lie within tight bounds of a long-double root",
          "[bounds][family]") {
    checked = 0;
    // Light to overdamped bearings, cross-coupling, K unset, 4, 6 or 8 (apps/bench/rotor_family.hpp).
    for (const unsigned seed : {1u, 2u, 3u, 5u, 8u, 67u}) {
        const family::RotorCase c = family::random_rotor(seed, false);
        INFO(c.description);
        StudyOptions opt;
        opt.solver.modes = c.modes;
        opt.speeds = c.speeds;
        opt.harmonics = {1};
        opt.amplification_factors = false;
        check_system(make_system(c.rotor), opt);
    }
    CHECK(checked >= 15);
}
