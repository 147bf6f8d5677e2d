// Plain cylindrical fluid-film journal bearing of finite length: the Reynolds
// equation solved by finite differences with Gümbel (half-Sommerfeld)
// cavitation, its static equilibrium under a steady load and its 8
// speed-dependent stiffness and damping coefficients (docs/fe_rotor.md,
// "Finite-length solution"). The bearing data, the state and the axes are those
// of the short bearing (journal_bearing.hpp); JournalBearing::solution selects
// this solution in journal_bearing_table.
#pragma once

#include <gyrokit/models/journal_bearing.hpp>

#include <Eigen/Dense>
#include <vector>

namespace gyrokit {

// The film in dimensionless form on one grid. With h = c H, p = eta Omega (R/c)^2 P,
// theta from +x towards +y, zeta = 2 z / L:
//   d/dtheta (H^3 dP/dtheta) + (D/L)^2 d/dzeta (H^3 dP/dzeta) = 12 g,
//   H = 1 - X cos(theta) - Y sin(theta),
//   g = (1/2) dH/dtheta + dH/dtau (tau = Omega t) = (X sin - Y cos)/2 - Xd cos - Yd sin,
// X = x/c, Y = y/c, Xd = x'/(c Omega), Yd = y'/(c Omega); P = 0 at zeta = +-1,
// periodic in theta. The journal is aligned, so P is even in zeta and only
// 0 <= zeta <= 1 is solved (dP/dzeta = 0 at zeta = 0).
//
// Grid: `circumferential` intervals of 2 pi / N (N even: nodes at theta0 and
// theta0 + pi), `axial` intervals over the length (a multiple of 4: M = axial/2
// intervals on the half, an even number for Simpson's rule). Five-point
// conservative differences, H^3 at the half nodes; the operator separates in
// zeta (H does not depend on z), so one solve is M cyclic tridiagonal systems
// in theta (exact for the discrete equations, not an approximation).
class ReynoldsFilm {
public:
    // Throws InputError on a grid outside the ranges of JournalBearing::validate
    // or a length_over_diameter that is not finite and > 0.
    ReynoldsFilm(double length_over_diameter, int circumferential, int axial);

    // The factorised film operator at one journal position (the velocity enters
    // only the right-hand side, so velocity perturbations reuse it).
    class Operator {
    public:
        // P at the nodes (rows theta_i = theta0 + 2 pi i / N, i < N; columns
        // zeta_j = j / M, j < M; P = 0 at zeta = 1) for the velocity (Xd, Yd).
        Eigen::MatrixXd pressure(double Xd, double Yd) const;
        // P for the right-hand side 12 g with g given at the nodes theta_i (length N):
        // the discrete equations are linear in P, one factorisation serves any g.
        Eigen::MatrixXd solve(const Eigen::VectorXd& g) const;

    private:
        friend class ReynoldsFilm;
        const ReynoldsFilm* film_ = nullptr;
        double X_ = 0, Y_ = 0, theta0_ = 0;
        Eigen::VectorXd h3_half_;   // H^3 at theta_{i+1/2}: the off-diagonal of every mode
        // Per axial mode k: the Thomas factors of the cyclic matrix with its corners
        // moved out (Sherman-Morrison), the correction vector z, 1 + v.z, corner/gamma.
        std::vector<Eigen::VectorXd> inv_pivot_, upper_, corr_;
        std::vector<double> corr_den_, corner_over_gamma_;
        Eigen::VectorXd solve_tridiagonal(int k, const Eigen::VectorXd& rhs) const;
    };

    // Factorises the operator for the journal at (X, Y); grid rotated by theta0.
    // Throws SolverError if the film is not positive at a node (|(X, Y)| >= 1).
    // The operator refers to this film: use it while the film exists.
    Operator factor(double X, double Y, double theta0) const;

    // f = int_0^1 int_0^{2pi} max(P, 0) (cos, sin) dtheta dzeta: Gümbel
    // cavitation, the film force F = -eta Omega R L (R/c)^2 f. In theta the
    // trapezoidal rule on the clipped piecewise-linear P (a cell where P changes
    // sign is cut at the linear zero), in zeta Simpson's rule.
    Eigen::Vector2d force(const Eigen::MatrixXd& P, double theta0) const;

    // The node angles theta0 + 2 pi i / N.
    Eigen::VectorXd theta(double theta0) const;
    double length_over_diameter() const { return ld_; }
    int circumferential() const { return n_; }
    int axial() const { return 2 * m_; }

private:
    double ld_;
    int n_, m_;
    Eigen::MatrixXd modes_;      // M x M: modes_(j, k) = cos(beta_k j), beta_k = (2k+1) pi / (2M)
    Eigen::VectorXd eig_;        // (D/L)^2 times the eigenvalues of the zeta second difference
    Eigen::VectorXd unit_;       // the constant 1 in the modes
    Eigen::VectorXd simpson_;    // weights in zeta, j = 0..M-1
};

// The film at eccentricity ratio e, with the line of centres along theta = 0:
// dimensionless, load-free (sommerfeld = (L/D)^2 / |f| is the modified Sommerfeld
// number eta Omega R L^3 / (4 W c^2) of the load this position carries,
// attitude_angle, a, b in the (u, v) axes of JournalBearingState; coefficients
// left zero). Throws SolverError on a non-finite result.
JournalBearingState reynolds_film_state(double length_over_diameter, double eccentricity, int circumferential,
                                        int axial);

// The bearing at spin speed w > 0 (rad/s) by the finite-difference solution
// (b.grid_circumferential, b.grid_axial): eccentricity from the force balance,
// then coefficients, filled like short_bearing's. Throws SolverError (naming the
// speed and what to change) if no equilibrium is found or a result is not finite.
JournalBearingState reynolds_bearing(const JournalBearing& b, double w);

// The speed (rad/s) at which the finite-difference solution has eccentricity e.
double reynolds_bearing_speed_at(const JournalBearing& b, double eccentricity);

}  // namespace gyrokit
