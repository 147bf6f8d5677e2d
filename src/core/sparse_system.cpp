#include <gyrokit/core/sparse_system.hpp>

#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>
#include <tuple>

namespace gyrokit {

using SpMat = Eigen::SparseMatrix<double>;

SparsePencil to_sparse(const QuadraticPencil& p) {
    return {p.M.sparseView(1.0, 0.0), p.C.sparseView(1.0, 0.0), p.K.sparseView(1.0, 0.0)};
}

namespace {

// S + the 2x2 block B on the rows and columns (i, j).
SpMat plus_blocks(const SpMat& S, const std::vector<std::tuple<int, int, Eigen::Matrix2d>>& blocks) {
    if (blocks.empty()) return S;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(4 * blocks.size());
    for (const auto& [i, j, B] : blocks) {
        t.emplace_back(i, i, B(0, 0));
        t.emplace_back(i, j, B(0, 1));
        t.emplace_back(j, i, B(1, 0));
        t.emplace_back(j, j, B(1, 1));
    }
    SpMat A(S.rows(), S.cols());
    A.setFromTriplets(t.begin(), t.end());
    return S + A;
}

double relative_asymmetry(const SpMat& A, double s) {
    const double scale = A.norm();
    if (scale == 0.0) return 0.0;
    const SpMat At = A.transpose();
    return SpMat(A - s * At).norm() / scale;
}

}  // namespace

SparsePencil SparseGyroscopicSystem::at_speed(double w) const {
    const int n = size();
    std::vector<std::tuple<int, int, Eigen::Matrix2d>> kb, cb;
    for (const auto& b : bearings) {
        const BearingCoefficients c = b.at(w);
        kb.emplace_back(b.dof_x, b.dof_y, c.K);
        cb.emplace_back(b.dof_x, b.dof_y, c.C);
    }
    SpMat C(n, n);
    if (D.size() > 0) C = D;
    if (G.size() > 0) C += w * G;
    SparsePencil p{M, plus_blocks(C, cb), plus_blocks(K, kb)};
    p.M.makeCompressed();
    p.C.makeCompressed();
    p.K.makeCompressed();
    return p;
}

Eigen::VectorXcd SparseGyroscopicSystem::unbalance_force(double w) const {
    if (unbalance.size() == 0) return Eigen::VectorXcd::Zero(size());
    return (w * w) * unbalance;
}

GyroscopicSystem SparseGyroscopicSystem::to_dense() const {
    GyroscopicSystem s;
    s.dof_names = dof_names;
    s.M = Eigen::MatrixXd(M);
    s.K = Eigen::MatrixXd(K);
    if (G.size() > 0) s.G = Eigen::MatrixXd(G);
    if (D.size() > 0 && D.nonZeros() > 0) s.damping.push_back({damping_name, Eigen::MatrixXd(D), {}});
    s.bearings = bearings;
    if (unbalance.size() > 0 && unbalance.cwiseAbs().maxCoeff() > 0) s.unbalance = unbalance;
    s.whirl_pairs = whirl_pairs;
    return s;
}

bool SparseGyroscopicSystem::dense_representable() const {
    return D.size() == 0 || relative_asymmetry(D, 1.0) <= 1e-12;
}

void SparseGyroscopicSystem::validate(const std::string& origin) const {
    const int n = size();
    if (n <= 0) throw InputError(fmt::format("{}: the system has no degrees of freedom", origin));
    const auto check = [&](const SpMat& A, const char* name, bool optional) {
        if (optional && A.size() == 0) return;
        if (A.rows() != n || A.cols() != n)
            throw InputError(fmt::format("{}: matrix {} is {}x{}, expected {}x{} (the size of M)", origin, name,
                                         A.rows(), A.cols(), n, n));
        for (int k = 0; k < A.outerSize(); ++k)
            for (SpMat::InnerIterator it(A, k); it; ++it)
                if (!std::isfinite(it.value()))
                    throw InputError(fmt::format("{}: matrix {} has a NaN or infinite entry at ({}, {}); allowed: "
                                                 "finite numbers",
                                                 origin, name, it.row() + 1, it.col() + 1));
    };
    check(M, "M", false);
    check(K, "K", false);
    check(G, "G", true);
    check(D, "D", true);
    constexpr double tol = 1e-12;
    if (M.norm() == 0.0) throw InputError(fmt::format("{}: M is zero", origin));
    if (relative_asymmetry(M, 1.0) > tol)
        throw InputError(fmt::format("{}: M is not symmetric (relative asymmetry {:.3g})", origin,
                                     relative_asymmetry(M, 1.0)));
    if (G.size() > 0 && relative_asymmetry(G, -1.0) > tol)
        throw InputError(fmt::format("{}: G is not skew-symmetric (relative deviation {:.3g})", origin,
                                     relative_asymmetry(G, -1.0)));
    validate_attachments(origin, n, unbalance, dof_names, bearings, whirl_pairs);
}

}  // namespace gyrokit
