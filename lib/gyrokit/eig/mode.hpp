// An eigenpair of the quadratic eigenproblem and the quantities engineers read
// off it: frequency, damping ratio, logarithmic decrement, whirl direction.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <limits>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace gyrokit {

// Forward/Backward: the lateral motion turns with / against the spin. Planar:
// lateral motion on straight lines (no turn). None: no lateral motion at all
// (axial or torsional modes). Real: a non-oscillating mode. Undefined: the
// model names no whirl pairs.
enum class Whirl { Forward, Backward, Real, Undefined, Planar, None };
std::string to_string(Whirl w);

// Whether a mode decays, grows, or cannot be told apart from neutral: its real
// part is compared with the error bound of the eigenvalue (docs/numerics.md).
enum class Stability { Stable, Neutral, Unstable };
std::string to_string(Stability s);

struct Mode {
    std::complex<double> lambda;   // eigenvalue (1/s); Im lambda >= 0 for listed modes
    Eigen::VectorXcd right;        // P(lambda) x = 0, unit 2-norm
    Eigen::VectorXcd left;         // y^H P(lambda) = 0, unit 2-norm (empty unless asked for)
    double backward_error = 0.0;   // relative backward error of (lambda, right)
    // d lambda / d w: how the eigenvalue moves with the spin speed, first-order
    // perturbation theory -y^H (dP/dw) x / y^H P'(lambda) x (set_slopes); NaN where
    // unknown (no left vector, a double eigenvalue, a solver that does not set it).
    std::complex<double> slope{std::numeric_limits<double>::quiet_NaN(), 0.0};
    // Bound on |lambda - exact eigenvalue| (1/s): condition number times backward
    // error, with a safety factor; infinity where the condition is unknown.
    double error_bound = 0.0;
    Whirl whirl = Whirl::Undefined;

    double frequency() const { return lambda.imag(); }   // damped natural frequency, rad/s
    // Re(lambda) as far as it is vouched for: 0 where it lies within its (finite)
    // error bound (a neutral mode), so that rounding never shows as damping of
    // either sign; as computed where the bound is unknown (infinite).
    double real_part() const;
    // -real_part()/|lambda|; 0 for a zero eigenvalue and for a neutral mode.
    double damping_ratio() const;
    // -2 pi real_part()/Im(lambda); +-infinity for a non-oscillating mode, 0 for a neutral one.
    double log_decrement() const;
    // Unstable only if Re lambda > error_bound, stable only if Re lambda < -error_bound.
    Stability stability() const;
};

struct PencilAction;

// The pencil's natural frequency scale (rad/s): the square root of the median of
// |K_ii| / |M_ii| over the DOFs where both are nonzero, or sqrt(|K| / |M|)
// (Frobenius) where there is no such DOF. A median, so that a few very stiff
// supports (1e20 N/m, as other packages model a pinned end) do not inflate it as
// they inflate |K|: the scale decides what counts as zero or real.
double natural_frequency_scale(const Eigen::VectorXd& m_diag, const Eigen::VectorXd& k_diag, double norm_M,
                               double norm_K);

// Rigid-body eigenvalues (free motion of a singular K: free-free rotors, free
// axial or torsional DOFs) are zero eigenvalues whose vector K does not see:
// |lambda| <= kRigidBodyTolerance * scale and |K x| <= kRigidBodyTolerance * | |K| |x| |,
// scale the pencil's natural frequency (natural_frequency_scale). The second test
// measures K x against what K's entries could make of x entry by entry: a stiff
// support that x does not move does not count. A zero eigenvalue of a Jordan
// chain of length two (q = a + b t) is computed as +-sqrt(eps) times the scale.
// The test on K x keeps the slow precession of a fast gyroscope (lambda -> 0 as
// the speed grows, but K x of the order of |K| |x|) a mode.
constexpr double kRigidBodyTolerance = 1e-6;
bool is_rigid_body(std::complex<double> lambda, const Eigen::VectorXcd& x, const PencilAction& pencil, double scale);

// Whirl of the motion Re(x e^{lambda t}) (Im lambda > 0): forward if the
// complex coordinates u + i v of the pairs turn in the positive sense, summed
// over the pairs: sum Im(x_u conj(x_v)) > 0. `real_tol` decides when an
// eigenvalue counts as real (|Im lambda| <= real_tol). None if the pair DOFs
// hold less than kWhirlTolerance of the largest amplitude; Planar if no pair
// turns by more than kWhirlTolerance of the largest pair amplitude.
constexpr double kWhirlTolerance = 1e-6;
Whirl classify_whirl(std::complex<double> lambda, const Eigen::VectorXcd& x,
                     const std::vector<std::pair<int, int>>& pairs, double real_tol);

// Moduli that agree to this relative tolerance are a tie, broken by a rule (the
// first DOF), never by rounding: |x| = |y| on a circular orbit.
constexpr double kTieTolerance = 1e-9;

// Unit 2-norm, largest entry real and positive (of entries tied with it, the
// first): reproducible output.
Eigen::VectorXcd unit_vector(const Eigen::VectorXcd& v);

// The products M x, C x, K x of a pencil P(lambda) = lambda^2 M + lambda C + K
// (dense or sparse) and the Frobenius norms of M, C, K.
struct PencilAction {
    std::function<void(const Eigen::VectorXcd& x, Eigen::VectorXcd& Mx, Eigen::VectorXcd& Cx, Eigen::VectorXcd& Kx)>
        apply;
    // |K| a for a >= 0 (entrywise absolute values): the scale of K x entry by entry.
    std::function<void(const Eigen::VectorXd& a, Eigen::VectorXd& absKa)> apply_abs_K;
    // |M| a, |C| a, |K| a at once (the componentwise bound, set_error_bounds); empty: not available.
    std::function<void(const Eigen::VectorXd& a, Eigen::VectorXd& Ma, Eigen::VectorXd& Ca, Eigen::VectorXd& Ka)>
        apply_abs;
    // The most products a row of P(lambda) x sums (nonzeros of M, C, K in one row, the
    // three together): what rounding in a residual entry is measured by.
    double row_terms = 0.0;
    double norm_M = 0.0, norm_C = 0.0, norm_K = 0.0;
};

// The largest number of nonzero entries in a row of M, C and K together.
template <class Matrix>
double pencil_row_terms(const Matrix& M, const Matrix& C, const Matrix& K) {
    Eigen::VectorXd count = Eigen::VectorXd::Zero(M.rows());
    for (const Matrix* A : {&M, &C, &K})
        for (Eigen::Index j = 0; j < A->cols(); ++j)
            for (Eigen::InnerIterator<Matrix> it(*A, j); it; ++it)
                if (it.value() != 0.0) count(it.row()) += 1.0;
    return M.rows() > 0 ? count.maxCoeff() : 0.0;
}

// The action of M, C, K (dense or sparse, referenced: they must outlive it),
// with `times(A, x)` the product A x.
template <class Matrix, class Times>
PencilAction pencil_action(const Matrix& M, const Matrix& C, const Matrix& K, Times times) {
    PencilAction a;
    a.apply = [&M, &C, &K, times](const Eigen::VectorXcd& x, Eigen::VectorXcd& Mx, Eigen::VectorXcd& Cx,
                                  Eigen::VectorXcd& Kx) {
        Mx = times(M, x);
        Cx = times(C, x);
        Kx = times(K, x);
    };
    a.apply_abs_K = [&K](const Eigen::VectorXd& v, Eigen::VectorXd& absKv) { absKv = K.cwiseAbs() * v; };
    a.apply_abs = [&M, &C, &K](const Eigen::VectorXd& v, Eigen::VectorXd& Mv, Eigen::VectorXd& Cv,
                               Eigen::VectorXd& Kv) {
        Mv = M.cwiseAbs() * v;
        Cv = C.cwiseAbs() * v;
        Kv = K.cwiseAbs() * v;
    };
    a.row_terms = pencil_row_terms(M, C, K);
    a.norm_M = M.norm();
    a.norm_C = C.norm();
    a.norm_K = K.norm();
    return a;
}

// Relative backward error |P(lambda) x| / ((|lambda|^2 |M| + |lambda| |C| + |K|) |x|),
// Frobenius norms: the one definition both solvers report.
double backward_error(const PencilAction& p, std::complex<double> lambda, const Eigen::VectorXcd& x);

// A double eigenvalue (a rotor on isotropic supports at standstill, say) has a
// plane of eigenvectors, and the solver returns an arbitrary basis of it, whose
// whirl rounding decides. Two oscillating modes count as a double eigenvalue if
// they are each other's only neighbour within 1e-6 relative and their
// eigenvalues, each refined by one Rayleigh-quotient step
// lambda - x^H P(lambda) x / x^H P'(lambda) x, agree to 1e-10 relative. The pair
// is then turned into the most backward and the most forward combination in its
// plane (the extremes of the whirl sum over it: circular orbits for a rotor);
// the lower eigenvalue gets the backward one. The turn is kept only if the
// residuals |P x| / (|lambda|^2 |M x| + |lambda| |C x| + |K x|) stay within ten
// times the originals' (or 10 eps). A pair split by more (anisotropy) keeps its
// vectors. Left vectors are not touched.
void separate_double_whirl(std::vector<Mode>& modes, const std::vector<std::pair<int, int>>& pairs,
                           double real_tol, const PencilAction& pencil);

// Error bounds of computed eigenvalues from their backward errors and condition
// numbers: for mode i with right vector x and left vector y,
//   bound = 10 max(eta, eps) (|l|^2 |M| + |l| |C| + |K|) |X| |Y| / s_min(Y^H P'(l) X),
// where X, Y hold the vectors of every mode within 1e-6 relative of l (a double
// eigenvalue's plane, whose computed bases need not pair up). Modes without a
// left vector get an infinite bound. The bound is computed twice, on `pencil`
// and on `scaled`, the pencil T P T of a diagonal congruence t > 0 (the solvers'
// DOF scaling: the eigenvalues are the same, the vectors T^-1 x and T^-1 y, eta
// and the condition number those of the scaled pencil, whose Frobenius norms are
// `scaled`), and the smaller is kept: a stiff support inflates |K| and with it the
// normwise measures of the original, not those of the scaled pencil. One product
// per vector serves both (T P T (x / t) = t (P x)). The modes on `threads` threads.
struct PencilNorms {
    double M = 0.0, C = 0.0, K = 0.0;
};
void set_error_bounds(std::vector<Mode>& modes, const PencilAction& pencil, const PencilNorms& scaled,
                      const Eigen::VectorXd& t, int threads = 1);

// Modal assurance criterion |a^H b|^2 / (|a|^2 |b|^2), in [0, 1].
double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);

// The order of modes by frequency: modes that vibrate by frequency, then the
// non-oscillating (real, overdamped) eigenvalues by modulus; an overdamped
// eigenvalue is no vibration mode, so "the K lowest modes" are K that vibrate.
std::pair<int, double> frequency_rank(const Mode& m);
// Modes in that order, equal ranks by real part; real eigenvalues whose moduli
// agree to 1e-9 relative by real part too (a tie is not left to rounding).
void sort_by_frequency(std::vector<Mode>& modes);

}  // namespace gyrokit
