#include <gyrokit/core/gyroscopic_system.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <fmt/format.h>

namespace gyrokit {

void add_block(Eigen::MatrixXd& A, int i, int j, const Eigen::Matrix2d& B) {
    A(i, i) += B(0, 0);
    A(i, j) += B(0, 1);
    A(j, i) += B(1, 0);
    A(j, j) += B(1, 1);
}

Eigen::MatrixXcd QuadraticPencil::evaluate(std::complex<double> lambda) const {
    return (lambda * lambda) * M.cast<std::complex<double>>() + lambda * C.cast<std::complex<double>>() +
           K.cast<std::complex<double>>();
}

Eigen::MatrixXd GyroscopicSystem::damping_matrix(double w) const {
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(size(), size());
    for (const auto& c : damping) D += c.at(w);
    for (const auto& b : bearings)
        if (b.damping_enabled) add_block(D, b.dof_x, b.dof_y, b.at(w).C);
    return D;
}

std::vector<std::string> GyroscopicSystem::damping_names() const {
    std::vector<std::string> names;
    for (const auto& c : damping) names.push_back(c.name);
    for (const auto& b : bearings)
        if (b.has_damping()) names.push_back(b.name);
    return names;
}

bool GyroscopicSystem::has_damping() const {
    for (const auto& c : damping)
        if (c.of_speed || c.D.norm() > 0.0) return true;
    for (const auto& b : bearings)
        if (b.damping_enabled && b.has_damping()) return true;
    return false;
}

QuadraticPencil GyroscopicSystem::at_speed(double w) const {
    QuadraticPencil p{M, damping_matrix(w), K};
    if (G.size() > 0) p.C += w * G;
    if (N.size() > 0) p.K += w * N;
    if (K2.size() > 0) p.K += (w * w) * K2;
    for (const auto& b : bearings) add_block(p.K, b.dof_x, b.dof_y, b.at(w).K);
    return p;
}

Eigen::VectorXcd GyroscopicSystem::unbalance_force(double w) const {
    if (unbalance.size() == 0) return Eigen::VectorXcd::Zero(size());
    return (w * w) * unbalance;
}

GyroscopicSystem GyroscopicSystem::with_damping_only(const std::vector<std::string>& names) const {
    GyroscopicSystem s = *this;
    s.damping.clear();
    const auto named = [&](const std::string& x) { return std::find(names.begin(), names.end(), x) != names.end(); };
    for (const auto& c : damping)
        if (named(c.name)) s.damping.push_back(c);
    for (auto& b : s.bearings) b.damping_enabled = b.damping_enabled && named(b.name);
    return s;
}

namespace {

void check_matrix(const Eigen::MatrixXd& A, int n, const std::string& origin, const char* name,
                  bool optional) {
    if (optional && A.size() == 0) return;
    if (A.rows() != n || A.cols() != n)
        throw InputError(fmt::format("{}: matrix {} is {}x{}, expected {}x{} (the size of M)", origin,
                                     name, A.rows(), A.cols(), n, n));
    if (!A.allFinite())
        throw InputError(fmt::format("{}: matrix {} has a NaN or infinite entry; allowed: finite numbers",
                                     origin, name));
}

// Largest |A - s A^T| relative to |A|, s = +1 for symmetric, -1 for skew.
double asymmetry(const Eigen::MatrixXd& A, double s) {
    const double scale = A.cwiseAbs().maxCoeff();
    if (scale == 0.0) return 0.0;
    return (A - s * A.transpose()).cwiseAbs().maxCoeff() / scale;
}

}  // namespace

void GyroscopicSystem::validate(const std::string& origin) const {
    const int n = size();
    if (n <= 0) throw InputError(fmt::format("{}: the system has no degrees of freedom", origin));
    check_matrix(M, n, origin, "M", false);
    check_matrix(K, n, origin, "K", false);
    check_matrix(G, n, origin, "G", true);
    check_matrix(N, n, origin, "N", true);
    check_matrix(K2, n, origin, "K2", true);
    for (const auto& c : damping) check_matrix(c.D, n, origin, c.name.c_str(), false);
    constexpr double tol = 1e-12;  // structural checks are exact up to rounding of the input
    if (asymmetry(M, 1.0) > tol)
        throw InputError(fmt::format("{}: M is not symmetric (relative asymmetry {:.3g})", origin,
                                     asymmetry(M, 1.0)));
    for (const auto& c : damping)
        if (asymmetry(c.D, 1.0) > tol)
            throw InputError(fmt::format("{}: damping {} is not symmetric (relative asymmetry {:.3g}); "
                                         "put its skew part into G or N",
                                         origin, c.name, asymmetry(c.D, 1.0)));
    if (G.size() > 0 && asymmetry(G, -1.0) > tol)
        throw InputError(fmt::format("{}: G is not skew-symmetric (relative deviation {:.3g})", origin,
                                     asymmetry(G, -1.0)));
    if (M.cwiseAbs().maxCoeff() == 0.0) throw InputError(fmt::format("{}: M is zero", origin));
    validate_attachments(origin, n, unbalance, dof_names, bearings, whirl_pairs);
}

void validate_attachments(const std::string& origin, int n, const Eigen::VectorXcd& unbalance,
                          const std::vector<std::string>& dof_names, const std::vector<BearingTable>& bearings,
                          const std::vector<std::pair<int, int>>& whirl_pairs) {
    if (unbalance.size() != 0 && unbalance.size() != n)
        throw InputError(fmt::format("{}: unbalance has {} entries, expected {}", origin, unbalance.size(), n));
    if (unbalance.size() != 0 && !unbalance.allFinite())
        throw InputError(fmt::format("{}: unbalance has a NaN or infinite entry", origin));
    if (static_cast<int>(dof_names.size()) != n)
        throw InputError(fmt::format("{}: {} DOF names for {} DOFs", origin, dof_names.size(), n));
    for (const auto& b : bearings) b.validate(n);
    for (const auto& [u, v] : whirl_pairs)
        if (u < 0 || v < 0 || u >= n || v >= n || u == v)
            throw InputError(fmt::format("{}: whirl pair ({}, {}) is out of range; allowed: two distinct "
                                         "DOF indices in [0, {}]",
                                         origin, u, v, n - 1));
}

}  // namespace gyrokit
