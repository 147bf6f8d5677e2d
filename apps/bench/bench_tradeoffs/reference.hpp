// gyrokit-bench-tradeoffs: reference eigenvalues in long double (reference.cpp)
// and the window of modes a sparse solve should return.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <complex>

namespace tradeoffs {

struct Reference {
    gyrokit::QuadraticSpectrum spectrum;   // the refined eigenvalues (rounded to double)
    double max_backward_error = 0;         // of the refined pairs, evaluated in long double
    double max_move = 0;                   // largest |l_refined - l_start| / |l_start|
    bool distinct = true;                  // no two pairs converged to the same eigenvalue
};

// Every pair of `start` (a dense solution of the pencil `p`) refined by Newton's method in long double.
Reference refine_long_double(const gyrokit::SparsePencil& p, const gyrokit::QuadraticSpectrum& start);

// The `k` modes of `s` nearest the shift: the window a sparse solve should return.
gyrokit::QuadraticSpectrum window(const gyrokit::QuadraticSpectrum& s, int k, std::complex<double> shift);

}  // namespace tradeoffs
