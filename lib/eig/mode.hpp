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

enum class Whirl { Forward, Backward, Real, Undefined };
std::string to_string(Whirl w);

struct Mode {
    std::complex<double> lambda;   // eigenvalue (1/s); Im lambda >= 0 for listed modes
    Eigen::VectorXcd right;        // P(lambda) x = 0, unit 2-norm
    Eigen::VectorXcd left;         // y^H P(lambda) = 0, unit 2-norm (empty unless asked for)
    double backward_error = 0.0;   // relative backward error of (lambda, right)
    Whirl whirl = Whirl::Undefined;

    double frequency() const { return lambda.imag(); }   // damped natural frequency, rad/s
    // -Re(lambda)/|lambda|; 0 for a zero eigenvalue.
    double damping_ratio() const;
    // -2 pi Re(lambda)/Im(lambda); +-infinity for a non-oscillating mode.
    double log_decrement() const;
};

// Whirl of the motion Re(x e^{lambda t}) (Im lambda > 0): forward if the
// complex coordinates u + i v of the pairs turn in the positive sense, summed
// over the pairs: sum Im(x_u conj(x_v)) > 0. `real_tol` decides when an
// eigenvalue counts as real (|Im lambda| <= real_tol).
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

// Modal assurance criterion |a^H b|^2 / (|a|^2 |b|^2), in [0, 1].
double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);

}  // namespace gyrokit
