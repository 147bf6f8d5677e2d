#include <gyrokit/models/gravity_loads.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/numerics/sparse_block.hpp>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

using SpMat = Eigen::SparseMatrix<double>;

std::vector<double> fe_gravity_reactions(const FeRotor& r, const std::vector<int>& nodes, double g) {
    FeRotor lateral = r;
    lateral.motion = FeMotion::lateral;   // the weight moves no axial or torsional DOF
    const FeRotorMatrices m = lateral.assemble();
    // The vertical plane's DOFs; the held ones (y at `nodes`) and the free ones.
    std::vector<int> held, free, plane_of(m.size(), -1);
    for (const int node : nodes) {
        const int i = m.dofs.find(node, DofMotion::y);
        if (i < 0)
            throw InputError(fmt::format("fe rotor: gravity reaction at node {}: its y is held by a support; allowed: "
                                         "a node whose y is free",
                                         node));
        if (std::find(held.begin(), held.end(), i) == held.end()) held.push_back(i);
    }
    for (int i = 0; i < m.size(); ++i) {
        if (m.dofs.in_vertical_plane(i) && std::find(held.begin(), held.end(), i) == held.end()) free.push_back(i);
    }
    // Consistent weight: f = -g M r, r = 1 on every vertical translation (a rigid lift).
    Eigen::VectorXd lift = Eigen::VectorXd::Zero(m.size());
    for (int i = 0; i < m.size(); ++i)
        if (m.dofs.vertical_translation(i)) lift(i) = 1.0;
    const Eigen::VectorXd weight = -g * (m.M * lift);
    const auto sub = [&](const std::vector<int>& rows, const std::vector<int>& cols) { return submatrix(m.K, rows, cols); };
    Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(free.size()));
    if (!free.empty()) {
        Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
        const Eigen::SparseMatrix<double> Kff = sub(free, free);
        lu.compute(Kff);
        const Eigen::VectorXd f = weight(free);
        if (lu.info() == Eigen::Success) u = lu.solve(f);
        // A rotor free to fall or tip in the vertical plane has no static solution.
        const double residual = lu.info() == Eigen::Success ? (Kff * u - f).norm() : INFINITY;
        if (!(residual <= 1e-8 * std::max(f.norm(), 1e-300)) || !u.allFinite())
            throw InputError("fe rotor: the static bearing loads need the rotor held in the vertical plane by its "
                             "bearings and supports; it is free to fall or tip there; allowed: load = a number (N) "
                             "for each fluid-film bearing, or more bearings or supports");
    }
    const Eigen::VectorXd R = sub(held, free) * u - weight(held);
    std::vector<double> out;
    for (const int node : nodes) {
        const auto at = std::find(held.begin(), held.end(), m.dofs.find(node, DofMotion::y));
        out.push_back(R(at - held.begin()));
    }
    return out;
}

}  // namespace gyrokit
