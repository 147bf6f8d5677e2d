// The gyroscopic system  M z'' + (D + w G) z' + K z = w^2 Re(u e^{i w t})  with
// sparse matrices, for models too large to hold densely (finite-element rotors,
// large matrix models): the same quantities as GyroscopicSystem without the
// terms only the small analytical models need (circulatory N, K2, speed-
// dependent damping functions), plus speed-dependent bearing tables.
#pragma once

#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>

#include <Eigen/Sparse>
#include <string>
#include <utility>
#include <vector>

namespace gyrokit {

// The quadratic pencil P(lambda) = lambda^2 M + lambda C + K in sparse form.
struct SparsePencil {
    Eigen::SparseMatrix<double> M, C, K;
};

// A dense pencil in sparse form (exact zeros dropped): lets the sparse solver
// run on every dense model too.
SparsePencil to_sparse(const QuadraticPencil& p);

class SparseGyroscopicSystem {
public:
    std::vector<std::string> dof_names;
    Eigen::SparseMatrix<double> M;   // mass, symmetric
    Eigen::SparseMatrix<double> K;   // stiffness
    Eigen::SparseMatrix<double> G;   // gyroscopic per unit speed, skew (0 x 0: none)
    Eigen::SparseMatrix<double> D;   // constant damping (0 x 0: none); may be unsymmetric (cross-coupled bearings)
    std::string damping_name = "D";  // its name as a damping component
    std::vector<BearingTable> bearings;
    Eigen::VectorXcd unbalance;      // force amplitude per w^2 (empty: none)
    std::vector<std::pair<int, int>> whirl_pairs;

    int size() const { return static_cast<int>(M.rows()); }
    // C = D + w G + bearing damping(w), K(w) = K + bearing stiffness(w).
    SparsePencil at_speed(double w) const;
    Eigen::VectorXcd unbalance_force(double w) const;

    // The same model as a dense GyroscopicSystem; D becomes the damping component
    // `damping_name` (it must then be symmetric, as GyroscopicSystem requires).
    GyroscopicSystem to_dense() const;
    // False when D is unsymmetric (cross-coupled bearing damping cxy != cyx),
    // which only the sparse form holds.
    bool dense_representable() const;

    // Dimensions, finiteness, symmetry of M, skew G, bearing tables. Throws InputError naming `origin`.
    void validate(const std::string& origin) const;
};

}  // namespace gyrokit
