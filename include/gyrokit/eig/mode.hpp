// An eigenpair of the quadratic eigenproblem and the quantities engineers read
// off it: frequency, damping ratio, logarithmic decrement, whirl direction.
#pragma once

#include <Eigen/Dense>
#include <complex>
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
    // Bound on |lambda - exact eigenvalue| (1/s): condition number times backward
    // error, with a safety factor; infinity where the condition is unknown.
    double error_bound = 0.0;
    Whirl whirl = Whirl::Undefined;

    double frequency() const { return lambda.imag(); }   // damped natural frequency, rad/s
    // -Re(lambda)/|lambda|; 0 for a zero eigenvalue.
    double damping_ratio() const;
    // -2 pi Re(lambda)/Im(lambda); +-infinity for a non-oscillating mode.
    double log_decrement() const;
    // Unstable only if Re lambda > error_bound, stable only if Re lambda < -error_bound.
    Stability stability() const;
};

struct PencilAction;
// Rigid-body eigenvalues (free motion of a singular K: free-free rotors, free
// axial or torsional DOFs) are zero eigenvalues whose vector K does not see:
// |lambda| <= kRigidBodyTolerance * scale and |K x| <= kRigidBodyTolerance |K| |x|,
// scale = sqrt(|K|/|M|) the pencil's natural frequency (Frobenius norms). A zero
// eigenvalue of a Jordan chain of length two (q = a + b t) is computed as
// +-sqrt(eps) * scale (1.5e-8 scale). The test on K x keeps the slow precession
// of a fast gyroscope (lambda -> 0 as the speed grows, but K x of the order of
// |K| |x|) a mode.
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

// Unit 2-norm, largest entry real and positive: reproducible output.
Eigen::VectorXcd unit_vector(const Eigen::VectorXcd& v);

// The products M x, C x, K x of a pencil P(lambda) = lambda^2 M + lambda C + K
// (dense or sparse) and the Frobenius norms of M, C, K.
struct PencilAction {
    std::function<void(const Eigen::VectorXcd& x, Eigen::VectorXcd& Mx, Eigen::VectorXcd& Cx, Eigen::VectorXcd& Kx)>
        apply;
    double norm_M = 0.0, norm_C = 0.0, norm_K = 0.0;
};

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
// left vector get an infinite bound.
void set_error_bounds(std::vector<Mode>& modes, const PencilAction& pencil);

// Modal assurance criterion |a^H b|^2 / (|a|^2 |b|^2), in [0, 1].
double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);

// The order of modes by frequency: modes that vibrate by frequency, then the
// non-oscillating (real, overdamped) eigenvalues by modulus; an overdamped
// eigenvalue is no vibration mode, so "the K lowest modes" are K that vibrate.
std::pair<int, double> frequency_rank(const Mode& m);

}  // namespace gyrokit
