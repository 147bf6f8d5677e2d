// Steady unbalance response z(t) = Re(Z e^{i w t}) of
// M z'' + (D + w G) z' + (K + w N) z = Re(w^2 u e^{i w t}).
#pragma once

#include "core/gyroscopic_system.hpp"

#include <string>
#include <vector>

namespace gyrokit {

// Complex amplitudes Z at speed w: [K + w N - w^2 M + i w (D + w G)] Z = w^2 u.
// Throws SolverError where the dynamic stiffness is singular (an undamped resonance).
Eigen::VectorXcd unbalance_response(const GyroscopicSystem& sys, double w);

struct ResponseCurve {
    std::vector<double> speeds;
    Eigen::MatrixXcd Z;   // speeds x DOFs
};
ResponseCurve unbalance_response(const GyroscopicSystem& sys, const std::vector<double>& speeds);

struct ResponseExtremum {
    int dof = 0;
    bool peak = true;      // false: antiresonance (local minimum)
    double speed = 0;
    double amplitude = 0;
};

// Interior local maxima and minima of |Z_k| on the grid, refined by golden section.
std::vector<ResponseExtremum> response_extrema(const GyroscopicSystem& sys, const ResponseCurve& curve);

}  // namespace gyrokit
