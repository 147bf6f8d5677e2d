// One computed eigenvalue made sharp, for the results printed with a bound (stability
// thresholds, critical speeds): corrected by Newton's step measured with a residual in
// extended precision, with bounds on the corrected real and imaginary parts.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/mode.hpp>

#include <complex>

namespace gyrokit {

// To first order the exact eigenvalue is lambda - c with c = y^H r / y^H P'(lambda) x,
// r = P(lambda) x (Newton's correction); the residual and both products are summed in
// long double. `lambda` is the corrected eigenvalue. What is left of its error: the
// residual's rounding, at most (terms + 3) eps_ld (E |x|)_i per entry (E = |l|^2 |M| +
// |l| |C| + |K|, terms the row's products), which moves it by eps_ld (terms + 3)
// |y|^T E |x| / |y^H P' x|; the second order (vectors that are not exact), a hundredth of
// |c| for a pair polished to rounding; and eps |lambda|, its rounding to double. `real`
// and `imag` bound the two parts. Infinite (both) without a left vector, or near an
// exceptional point (|y^H P' x| below 1e-6 of |y|^T (2 |l| |M| + |C|) |x|), where the
// first order does not hold.
struct SharpEigenvalue {
    std::complex<double> lambda;
    double real = 0.0, imag = 0.0;
};
SharpEigenvalue sharp_eigenvalue(const Mode& m, const SparsePencil& p);

}  // namespace gyrokit
