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

// A double eigenvalue (a rotor on isotropic supports at standstill, say) has a
// plane of eigenvectors, and the solver returns an arbitrary basis of it, whose
// whirl rounding decides. Each two modes with eigenvalues equal to 1e-6 relative
// are turned into the most forward and the most backward combination in their
// plane (the extremes of the whirl sum over it: circular orbits for a rotor), and
// their whirl classified again. The turn is kept only if it leaves both backward
// errors at the level of the originals, i.e. if the eigenvalue is double to
// working accuracy; a pair split by a real effect (anisotropy) keeps its vectors.
// Left vectors are not touched (for a double eigenvalue any basis is valid).
using BackwardError = std::function<double(std::complex<double>, const Eigen::VectorXcd&)>;
void separate_double_whirl(std::vector<Mode>& modes, const std::vector<std::pair<int, int>>& pairs,
                           double real_tol, const BackwardError& backward_error);

// Modal assurance criterion |a^H b|^2 / (|a|^2 |b|^2), in [0, 1].
double mac(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b);

}  // namespace gyrokit
