// Steady unbalance response z(t) = Re(Z e^{i w t}) of
// M z'' + (D + w G) z' + (K + w N) z = Re(w^2 u e^{i w t}).
#pragma once

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>

#include <functional>

#include <string>
#include <vector>

namespace gyrokit {

// Complex amplitudes Z at speed w: [K + w N - w^2 M + i w (D + w G)] Z = w^2 u,
// by a dense LU or (Sparse; Auto above kAutoSparseDofs) a sparse LU of the
// dynamic stiffness. Throws SolverError where it is singular (an undamped resonance).
Eigen::VectorXcd unbalance_response(const GyroscopicSystem& sys, double w, SolverKind kind = SolverKind::Auto);

// The steady response Z e^{i w t} to a force f e^{i w t} with the rotor spinning at
// `spin`: [K(spin) + spin N - w^2 M + i w (D(spin) + spin G)] Z = f, by the dense or
// sparse LU as above (the unbalance response is spin = w, f = w^2 u). SolverError
// where the dynamic stiffness is singular.
Eigen::VectorXcd dynamic_response(const GyroscopicSystem& sys, double spin, double w, const Eigen::VectorXcd& f,
                                  SolverKind kind = SolverKind::Auto);

// Amplitudes of every DOF at a speed (one of the functions above, bound to a model).
using ResponseSolver = std::function<Eigen::VectorXcd(double w)>;

struct ResponseCurve {
    std::vector<double> speeds;
    std::vector<int> dofs;   // the model DOF of each column of Z
    Eigen::MatrixXcd Z;      // speeds x dofs
};
// All DOFs (`dofs` empty) or the listed ones.
ResponseCurve unbalance_response(const ResponseSolver& solve, int size, const std::vector<double>& speeds,
                                 const std::vector<int>& dofs = {});
ResponseCurve unbalance_response(const GyroscopicSystem& sys, const std::vector<double>& speeds);

struct ResponseExtremum {
    int dof = 0;           // model DOF index
    bool peak = true;      // false: antiresonance (local minimum)
    double speed = 0;
    double amplitude = 0;  // +inf for an unbounded peak
    // false: a peak narrower than the search resolves (an undamped or nearly
    // undamped resonance): the amplitude there is unbounded for all the model says.
    bool bounded = true;
};

// The largest amplitude of each DOF of a curve over its range: the largest of its
// refined peaks (`extrema`) and of the grid values at the range ends. A grid maximum
// can be far below the true one (a sharp resonance between grid points), so no
// grid value inside the range counts unrefined.
struct ResponseMaximum {
    int dof = 0;
    double speed = 0;
    double amplitude = 0;
    bool refined = false;   // an interior peak, refined; false: a range end
    bool bounded = true;    // false: an unbounded peak (amplitude +inf)
};
std::vector<ResponseMaximum> response_maxima(const ResponseCurve& curve, const std::vector<ResponseExtremum>& extrema);

// Interior local maxima and minima (only maxima with `peaks_only`) of |Z_k| on the
// grid, refined by Brent (peaks) and golden section (antiresonances). A peak whose
// half-power points lie within 10 search resolutions (damping ratio below about
// 6e-7) cannot be located well enough for its height to mean anything: it is
// reported unbounded (amplitude +inf, bounded = false). The DOFs of one resonance peak at nearly one
// speed and their searches visit the same speeds: each speed is solved once.
std::vector<ResponseExtremum> response_extrema(const ResponseSolver& solve, const ResponseCurve& curve,
                                               bool peaks_only = false);
std::vector<ResponseExtremum> response_extrema(const GyroscopicSystem& sys, const ResponseCurve& curve);

}  // namespace gyrokit
