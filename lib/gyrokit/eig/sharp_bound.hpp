// Sharp bounds on the real and imaginary parts of one computed eigenvalue, for the
// results printed with a bound (stability thresholds, critical speeds): the error
// itself to first order, measured with a residual in extended precision.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/mode.hpp>

namespace gyrokit {

// Bounds on |Re lambda - Re exact| and |Im lambda - Im exact| (1/s). To first order the
// exact eigenvalue is lambda - c with c = y^H r / y^H P'(lambda) x, r = P(lambda) x
// (Newton's correction), so each part's error is that part of c. The residual is
// summed in long double: its rounding, at most (terms + 3) eps_ld (E |x|)_i per entry
// (E = |l|^2 |M| + |l| |C| + |K|), adds eps_ld (terms + 3) |y|^T E |x| / |y^H P' x|.
// Twice each part of c, a hundredth of |c| (the second order, vectors that are not
// exact) and eps |lambda| (lambda's own rounding) are added. Structure counts: a real
// pencil's perturbations move a lightly damped mode's frequency, hardly its decay,
// and the real part's bound sees that where a normwise one cannot. Infinite (both)
// without a left vector or where y^H P' x vanishes.
struct PartBounds {
    double real = 0.0, imag = 0.0;
};
PartBounds sharp_part_bounds(const Mode& m, const SparsePencil& p);

}  // namespace gyrokit
