// The linear gyroscopic system  M z'' + (D + w G) z' + (K + w N) z = w^2 Re(u e^{i w t})
// with w the spin speed (rad/s). G and N are given per unit speed.
#pragma once

#include <gyrokit/core/bearing_table.hpp>

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace gyrokit {

// A += B on the rows and columns (i, j): a 2x2 element acting on one DOF pair.
void add_block(Eigen::MatrixXd& A, int i, int j, const Eigen::Matrix2d& B);

// One named source of damping (e.g. "d_G" cage damping); the total damping
// matrix is the sum of all components. Kept apart so that pervasive damping
// can be checked for each component alone.
struct DampingComponent {
    std::string name;
    Eigen::MatrixXd D;
    // Optional: the matrix at speed w when it depends on speed (e.g. Stokes-layer
    // damping of a liquid ~ sqrt(w)); empty means the constant D.
    std::function<Eigen::MatrixXd(double)> of_speed;
    Eigen::MatrixXd at(double w) const { return of_speed ? of_speed(w) : D; }
};

// The three coefficient matrices of the quadratic pencil at one speed:
// P(lambda) = lambda^2 M + lambda C + K.
struct QuadraticPencil {
    Eigen::MatrixXd M, C, K;
    Eigen::MatrixXcd evaluate(std::complex<double> lambda) const;
};

class GyroscopicSystem {
public:
    std::vector<std::string> dof_names;
    Eigen::MatrixXd M;                        // mass, symmetric
    Eigen::MatrixXd K;                        // stiffness
    Eigen::MatrixXd G;                        // gyroscopic per unit speed, skew
    Eigen::MatrixXd N;                        // circulatory per unit speed (empty: none)
    Eigen::MatrixXd K2;                       // stiffness per speed squared (empty: none), e.g. sloshing
    std::vector<DampingComponent> damping;    // D = sum of components
    // Speed-dependent bearings: their stiffness adds to K, their damping to D;
    // each one's damping counts as a damping component named after the table.
    std::vector<BearingTable> bearings;
    Eigen::VectorXcd unbalance;               // force amplitude per w^2 (empty: none)
    // DOF pairs (u, v) whose complex coordinate u + i v turns forward when the
    // motion turns in the sense of the spin; used to classify whirl.
    std::vector<std::pair<int, int>> whirl_pairs;

    int size() const { return static_cast<int>(M.rows()); }
    // Total damping at speed w (speed matters only for speed-dependent components).
    Eigen::MatrixXd damping_matrix(double w = 0.0) const;
    // Names of the damping components: `damping`, then bearing tables with damping.
    std::vector<std::string> damping_names() const;
    bool has_damping() const;
    bool has_circulatory() const { return N.size() > 0 && N.norm() > 0.0; }
    bool has_speed_squared_stiffness() const { return K2.size() > 0 && K2.norm() > 0.0; }

    // Pencil at spin speed w: C = D(w) + w G, K(w) = K + w N + w^2 K2 (+ bearings).
    QuadraticPencil at_speed(double w) const;
    // Unbalance force amplitude at speed w (zero vector if there is none).
    Eigen::VectorXcd unbalance_force(double w) const;

    // The same system with only the named damping components (others removed).
    GyroscopicSystem with_damping_only(const std::vector<std::string>& names) const;

    // Checks dimensions, finiteness and the structural properties (M, D
    // symmetric; G skew). Throws InputError naming `origin` on violation.
    void validate(const std::string& origin) const;
};

// The checks both system forms share: unbalance size and finiteness, one name
// per DOF, bearing tables, whirl pairs in range. Throws InputError naming `origin`.
void validate_attachments(const std::string& origin, int n, const Eigen::VectorXcd& unbalance,
                          const std::vector<std::string>& dof_names, const std::vector<BearingTable>& bearings,
                          const std::vector<std::pair<int, int>>& whirl_pairs);

}  // namespace gyrokit
