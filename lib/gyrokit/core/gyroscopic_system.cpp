#include <gyrokit/core/gyroscopic_system.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tuple>

namespace gyrokit {

SparseMatrix to_sparse(const Eigen::MatrixXd& A) {
    SparseMatrix S = A.sparseView(1.0, 0.0);
    S.makeCompressed();
    return S;
}

SparsePencil to_sparse(const QuadraticPencil& p) { return {to_sparse(p.M), to_sparse(p.C), to_sparse(p.K)}; }

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

namespace {

using Block = std::tuple<int, int, Eigen::Matrix2d>;

// A bearing's 2x2 block: on its own pair, or between the pair and a pedestal's
// (relative motion: +B on both diagonal pairs, -B off them). The off-diagonal blocks
// go in `coupled` as (rows x, y; columns x, y) quadruples.
struct CoupledBlock {
    int ri, rj, ci, cj;
    Eigen::Matrix2d B;
};
void add_bearing(std::vector<Block>& blocks, std::vector<CoupledBlock>& coupled, const BearingTable& b,
                 const Eigen::Matrix2d& B) {
    blocks.emplace_back(b.dof_x, b.dof_y, B);
    if (b.pedestal_x < 0) return;
    blocks.emplace_back(b.pedestal_x, b.pedestal_y, B);
    coupled.push_back({b.dof_x, b.dof_y, b.pedestal_x, b.pedestal_y, -B});
    coupled.push_back({b.pedestal_x, b.pedestal_y, b.dof_x, b.dof_y, -B});
}

// The n x n matrix of 2x2 blocks on the rows and columns (i, j).
SparseMatrix blocks_matrix(int n, const std::vector<Block>& blocks) {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(4 * blocks.size());
    for (const auto& [i, j, B] : blocks) {
        t.emplace_back(i, i, B(0, 0));
        t.emplace_back(i, j, B(0, 1));
        t.emplace_back(j, i, B(1, 0));
        t.emplace_back(j, j, B(1, 1));
    }
    SparseMatrix A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    return A;
}

SparseMatrix blocks_matrix(int n, const std::vector<Block>& blocks, const std::vector<CoupledBlock>& coupled) {
    SparseMatrix A = blocks_matrix(n, blocks);
    if (coupled.empty()) return A;
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(4 * coupled.size());
    for (const CoupledBlock& c : coupled) {
        t.emplace_back(c.ri, c.ci, c.B(0, 0));
        t.emplace_back(c.ri, c.cj, c.B(0, 1));
        t.emplace_back(c.rj, c.ci, c.B(1, 0));
        t.emplace_back(c.rj, c.cj, c.B(1, 1));
    }
    SparseMatrix C(n, n);
    C.setFromTriplets(t.begin(), t.end());
    return A + C;
}

bool present(const SparseMatrix& A) { return A.rows() > 0 && A.nonZeros() > 0; }

}  // namespace

SparseMatrix GyroscopicSystem::damping_matrix(double w) const {
    const int n = size();
    SparseMatrix D(n, n);
    for (const auto& c : damping) D += c.at(w);
    std::vector<Block> cb;
    std::vector<CoupledBlock> cc;
    for (const auto& b : bearings)
        if (b.damping_enabled) add_bearing(cb, cc, b, b.at(w).C);
    if (!cb.empty()) D += blocks_matrix(n, cb, cc);
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

SparsePencil GyroscopicSystem::sparse_at_speed(double w) const {
    SparsePencil p{M, damping_matrix(w), K};
    if (present(G)) p.C += w * G;
    if (present(N)) p.K += w * N;
    if (present(K2)) p.K += (w * w) * K2;
    std::vector<Block> kb;
    std::vector<CoupledBlock> kc;
    for (const auto& b : bearings) add_bearing(kb, kc, b, b.at(w).K);
    if (!kb.empty()) p.K += blocks_matrix(size(), kb, kc);
    p.M.makeCompressed();
    p.C.makeCompressed();
    p.K.makeCompressed();
    p.band_order = band_order_cache.get({&p.M, &p.C, &p.K});
    return p;
}

QuadraticPencil GyroscopicSystem::at_speed(double w) const {
    const SparsePencil p = sparse_at_speed(w);
    return {Eigen::MatrixXd(p.M), Eigen::MatrixXd(p.C), Eigen::MatrixXd(p.K)};
}

Eigen::VectorXcd GyroscopicSystem::unbalance_force(double w) const {
    if (unbalance.size() == 0) return Eigen::VectorXcd::Zero(size());
    return (w * w) * unbalance;
}

int GyroscopicSystem::nearest_node(double z, const LengthUnit& unit) const {
    if (node_z.empty()) throw InputError("this model has no nodes on an axis; allowed: DOFs by name");
    const auto [lo, hi] = std::minmax_element(node_z.begin(), node_z.end());
    const double slack = 1e-9 * std::max(1.0, *hi - *lo);
    if (!std::isfinite(z) || z < *lo - slack || z > *hi + slack)
        throw InputError(fmt::format("axial position {:.6g} {} is off the shaft; allowed: [{:.6g}, {:.6g}] {}", unit.in_unit(z),
                                     unit.name, unit.in_unit(*lo), unit.in_unit(*hi), unit.name));
    int best = 0;
    for (int k = 1; k < static_cast<int>(node_z.size()); ++k)
        if (std::abs(node_z[static_cast<size_t>(k)] - z) < std::abs(node_z[static_cast<size_t>(best)] - z)) best = k;
    return best;
}

std::vector<int> GyroscopicSystem::node_dofs(int node, const std::string& unit) const {
    if (node < 0 || node >= static_cast<int>(node_z.size()))
        throw InputError(node_z.empty() ? std::string("this model has no nodes on an axis; allowed: DOFs by name")
                                        : fmt::format("node {} does not exist; allowed: 0 to {}", node,
                                                      static_cast<int>(node_z.size()) - 1));
    std::vector<int> out;
    for (int i = 0; i < static_cast<int>(dofs.nodes.size()); ++i)
        if (dofs.nodes[static_cast<size_t>(i)] == node && (unit.empty() || dofs.unit(i) == unit)) out.push_back(i);
    return out;
}

std::vector<int> GyroscopicSystem::node_translations(int node) const {
    std::vector<int> out = node_dofs(node, dofs.units.empty() ? "" : "m");
    if (whirl_pairs.empty()) return out;
    const auto paired = [&](int i) {
        return std::any_of(whirl_pairs.begin(), whirl_pairs.end(),
                           [&](const std::pair<int, int>& p) { return p.first == i || p.second == i; });
    };
    out.erase(std::remove_if(out.begin(), out.end(), [&](int i) { return !paired(i); }), out.end());
    return out;
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

void check_matrix(const SparseMatrix& A, int n, const std::string& origin, const std::string& name, bool optional) {
    if (optional && A.size() == 0) return;
    if (A.rows() != n || A.cols() != n)
        throw InputError(fmt::format("{}: matrix {} is {}x{}, expected {}x{} (the size of M)", origin, name, A.rows(),
                                     A.cols(), n, n));
    for (int k = 0; k < A.outerSize(); ++k)
        for (SparseMatrix::InnerIterator it(A, k); it; ++it)
            if (!std::isfinite(it.value()))
                throw InputError(fmt::format("{}: matrix {} has a NaN or infinite entry at ({}, {}); allowed: "
                                             "finite numbers",
                                             origin, name, it.row() + 1, it.col() + 1));
            else if (std::abs(it.value()) > kMaxMatrixEntry)
                // The solvers square and scale the entries: beyond this they overflow (LAPACK's info = -5).
                throw InputError(fmt::format("{}: matrix {} has the entry {:.3g} at ({}, {}); allowed: magnitudes up "
                                             "to {:.0e} (a parameter of the model far outside physical ranges?)",
                                             origin, name, it.value(), it.row() + 1, it.col() + 1, kMaxMatrixEntry));
}

// Largest |A - s A^T| relative to the largest |A|, s = +1 for symmetric, -1 for skew.
double asymmetry(const SparseMatrix& A, double s) {
    double scale = 0.0;
    for (int k = 0; k < A.outerSize(); ++k)
        for (SparseMatrix::InnerIterator it(A, k); it; ++it) scale = std::max(scale, std::abs(it.value()));
    if (scale == 0.0) return 0.0;
    const SparseMatrix At = A.transpose();
    const SparseMatrix R = A - s * At;
    double worst = 0.0;
    for (int k = 0; k < R.outerSize(); ++k)
        for (SparseMatrix::InnerIterator it(R, k); it; ++it) worst = std::max(worst, std::abs(it.value()));
    return worst / scale;
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
    for (const auto& c : damping) check_matrix(c.D, n, origin, "damping " + c.name, c.of_speed != nullptr);
    constexpr double tol = 1e-12;  // structural checks are exact up to rounding of the input
    if (M.norm() == 0.0) throw InputError(fmt::format("{}: M is zero", origin));
    // A mass matrix is positive semidefinite: a negative diagonal entry says it is not (a sign slip).
    for (int i = 0; i < M.outerSize(); ++i)
        for (SparseMatrix::InnerIterator it(M, i); it; ++it)
            if (it.row() == it.col() && it.value() < 0.0)
                throw InputError(fmt::format("{}: M has the diagonal entry {} at DOF {}{}; a mass matrix is positive "
                                             "semidefinite; allowed: diagonal entries >= 0",
                                             origin, it.value(), it.row(),
                                             static_cast<std::size_t>(it.row()) < dofs.names.size()
                                                 ? " (" + dofs.names[static_cast<std::size_t>(it.row())] + ")"
                                                 : std::string()));
    if (asymmetry(M, 1.0) > tol)
        throw InputError(fmt::format("{}: M is not symmetric (relative asymmetry {:.3g})", origin, asymmetry(M, 1.0)));
    if (G.size() > 0 && asymmetry(G, -1.0) > tol)
        throw InputError(fmt::format("{}: G is not skew-symmetric (relative deviation {:.3g})", origin,
                                     asymmetry(G, -1.0)));
    if (unbalance.size() != 0 && unbalance.size() != n)
        throw InputError(fmt::format("{}: unbalance has {} entries, expected {}", origin, unbalance.size(), n));
    if (unbalance.size() != 0 && !unbalance.allFinite())
        throw InputError(fmt::format("{}: unbalance has a NaN or infinite entry", origin));
    dofs.check(n, static_cast<int>(node_z.size()), origin);
    for (const auto& b : bearings) b.validate(n);
    // A DOF that no matrix touches (no mass, stiffness, damping or coupling) makes
    // P(lambda) singular for every lambda: every number is an "eigenvalue", and the
    // solvers have nothing to find (the sparse LU spun forever on one).
    {
        std::vector<char> touched(static_cast<size_t>(n), 0);
        const auto mark = [&](const SparseMatrix& A) {
            for (int k = 0; k < A.outerSize(); ++k)
                for (SparseMatrix::InnerIterator it(A, k); it; ++it)
                    if (it.value() != 0.0) touched[static_cast<size_t>(it.row())] = touched[static_cast<size_t>(it.col())] = 1;
        };
        for (const SparseMatrix* A : {&static_cast<const SparseMatrix&>(M), &static_cast<const SparseMatrix&>(K),
                                      &static_cast<const SparseMatrix&>(G), &static_cast<const SparseMatrix&>(N),
                                      &static_cast<const SparseMatrix&>(K2)})
            if (A->size() > 0) mark(*A);
        for (const auto& c : damping) mark(c.of_speed ? c.of_speed(0.0) : SparseMatrix(c.D));
        for (const auto& b : bearings)
            for (const int d : {b.dof_x, b.dof_y, b.pedestal_x, b.pedestal_y})
                if (d >= 0 && d < n) touched[static_cast<size_t>(d)] = 1;
        for (int i = 0; i < n; ++i)
            if (!touched[static_cast<size_t>(i)])
                throw InputError(fmt::format("{}: DOF {} ({}) has no mass, stiffness, damping or coupling: the pencil "
                                             "is singular at every eigenvalue; allowed: every DOF in some matrix",
                                             origin, i, static_cast<int>(dofs.names.size()) == n ? dofs.names[static_cast<size_t>(i)]
                                                                                             : std::to_string(i)));
    }
    std::vector<int> pair_of(static_cast<size_t>(std::max(n, 0)), -1);
    for (size_t k = 0; k < whirl_pairs.size(); ++k) {
        const auto [u, v] = whirl_pairs[k];
        if (u < 0 || v < 0 || u >= n || v >= n || u == v)
            throw InputError(fmt::format("{}: whirl pair ({}, {}) is out of range; allowed: two distinct "
                                         "DOF indices in [0, {}]",
                                         origin, u, v, n - 1));
        // (0, 1) and (1, 0) would call every orbit both forward and backward.
        for (const int d : {u, v}) {
            if (pair_of[static_cast<size_t>(d)] >= 0) {
                const auto [a, b] = whirl_pairs[static_cast<size_t>(pair_of[static_cast<size_t>(d)])];
                throw InputError(fmt::format("{}: DOF {} is in whirl pairs ({}, {}) and ({}, {}); allowed: each DOF "
                                             "in at most one pair",
                                             origin, d, a, b, u, v));
            }
            pair_of[static_cast<size_t>(d)] = static_cast<int>(k);
        }
    }
    for (const double z : node_z)
        if (!std::isfinite(z)) throw InputError(fmt::format("{}: a node position is NaN or infinite", origin));
}

std::vector<int> dofs_by_name(const std::string& list, const std::vector<std::string>& names, const std::string& option) {
    std::vector<int> out;
    std::size_t start = 0;
    while (!list.empty() && start <= list.size()) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        const std::string name = list.substr(start, end - start);
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end())
            throw InputError(fmt::format("{} '{}': '{}' is not a DOF of the model; allowed: names such as {}", option,
                                         list, name, names.empty() ? std::string("-") : names.front()));
        const int k = static_cast<int>(it - names.begin());
        if (std::find(out.begin(), out.end(), k) != out.end())
            throw InputError(fmt::format("{} '{}': '{}' is listed twice; allowed: each DOF once", option, list, name));
        out.push_back(k);
        start = end + 1;
    }
    return out;
}

std::vector<int> dofs_by_name(const std::vector<std::string>& list, const std::vector<std::string>& names,
                              const std::string& option) {
    std::string joined;
    for (std::size_t i = 0; i < list.size(); ++i) joined += (i ? "," : "") + list[i];
    for (const std::string& name : list)   // a name that the joined text would read as none, or as two
        if (name.empty() || name.find(',') != std::string::npos)
            throw InputError(fmt::format("{} '{}': '{}' is not a DOF of the model; allowed: names such as {}", option,
                                         joined, name, names.empty() ? std::string("-") : names.front()));
    return dofs_by_name(joined, names, option);
}

void check_dof_list(const GyroscopicSystem& sys, const std::vector<int>& dofs, const std::string& what) {
    for (std::size_t i = 0; i < dofs.size(); ++i) {
        if (dofs[i] < 0 || dofs[i] >= sys.size())
            throw InputError(fmt::format("{}: output DOF {}; allowed: 0 to {}", what, dofs[i], sys.size() - 1));
        for (std::size_t j = 0; j < i; ++j)
            if (dofs[j] == dofs[i])
                throw InputError(fmt::format("{}: output DOF {} ({}) is listed twice; allowed: each DOF once", what,
                                             dofs[i], static_cast<std::size_t>(dofs[i]) < sys.dofs.names.size()
                                                          ? sys.dofs.names[static_cast<std::size_t>(dofs[i])]
                                                          : std::string("?")));
    }
}

}  // namespace gyrokit
