#include <gyrokit/io/export.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>
#include <gyrokit/io/matrix_market.hpp>

#include <filesystem>
#include <fmt/format.h>

namespace gyrokit {

namespace {

// [A B; C D] of four n x n sparse blocks.
SparseMatrix blocks(const SparseMatrix& A, const SparseMatrix& B, const SparseMatrix& C, const SparseMatrix& D) {
    const Eigen::Index n = A.rows();
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<size_t>(A.nonZeros() + B.nonZeros() + C.nonZeros() + D.nonZeros()));
    const auto add = [&](const SparseMatrix& X, Eigen::Index r0, Eigen::Index c0) {
        for (Eigen::Index j = 0; j < X.outerSize(); ++j)
            for (SparseMatrix::InnerIterator it(X, j); it; ++it) t.emplace_back(it.row() + r0, it.col() + c0, it.value());
    };
    add(A, 0, 0);
    add(B, 0, n);
    add(C, n, 0);
    add(D, n, n);
    SparseMatrix S(2 * n, 2 * n);
    S.setFromTriplets(t.begin(), t.end());
    return S;
}

}  // namespace

ExportReport export_matrices(const GyroscopicSystem& sys, double w, const std::string& dir) {
    namespace fs = std::filesystem;
    sys.validate("export");
    const int n = sys.size();
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(fmt::format("{} {}: cannot create it: {}", option_field("directory"), dir, ec.message()));
    // Every file claimed before the first is written: a folder holding the scene's own
    // matrices is refused whole, not after half of them were replaced.
    const std::string option = option_field("directory");
    std::vector<std::string> names = {"M", "K", "G", "D", "C", "Kw", "pencil_A", "pencil_B", "state"};
    if (sys.has_circulatory()) names.push_back("N");
    if (sys.has_speed_squared_stiffness()) names.push_back("K2");
    for (const auto& c : sys.damping) names.push_back("D_" + c.name);
    for (size_t i = 0; i < sys.bearings.size(); ++i) {
        names.push_back(fmt::format("K_bearing{}", i + 1));
        names.push_back(fmt::format("D_bearing{}", i + 1));
    }
    RunScope run;
    for (const auto& name : names) run.files().claim_output((fs::path(dir) / (name + ".mtx")).string(), option);
    ExportReport report;
    const auto put = [&](const std::string& name, const auto& A, const std::string& what) {
        write_matrix_market((fs::path(dir) / (name + ".mtx")).string(), A, what, option);
        report.files.push_back(name + ".mtx");
    };
    const SparsePencil p = sys.sparse_at_speed(w);
    put("M", sys.M, "mass matrix");
    put("K", sys.K, "stiffness matrix");
    put("G", sys.G.size() ? SparseMatrix(sys.G) : SparseMatrix(n, n), "gyroscopic matrix per unit speed (rad/s)");
    if (sys.has_circulatory()) put("N", sys.N, "circulatory matrix per unit speed (rad/s)");
    if (sys.has_speed_squared_stiffness()) put("K2", sys.K2, "stiffness per speed squared");
    const std::string at = fmt::format(" at speed {:.17g} rad/s", w);
    put("D", sys.damping_matrix(w), "total damping matrix" + at);
    for (const auto& c : sys.damping) put("D_" + c.name, c.at(w), "damping component " + c.name + at);
    for (size_t i = 0; i < sys.bearings.size(); ++i) {
        const auto& b = sys.bearings[i];
        GyroscopicSystem one;   // the table alone: its blocks as n x n matrices
        one.M = SparseMatrix(n, n);
        one.K = SparseMatrix(n, n);
        one.bearings = {b};
        put(fmt::format("K_bearing{}", i + 1), one.sparse_at_speed(w).K, "stiffness of bearing table " + b.name + at);
        put(fmt::format("D_bearing{}", i + 1), one.damping_matrix(w), "damping of bearing table " + b.name + at);
    }
    put("C", p.C, "C = D + w G" + at);
    put("Kw", p.K, "K + w N + w^2 K2 + bearing stiffness" + at);
    SparseMatrix I(n, n);
    I.setIdentity();
    const SparseMatrix Z(n, n);
    put("pencil_A", blocks(-p.C, -p.K, I, Z), "first companion pencil A - lambda B, state [lambda x; x]" + at);
    put("pencil_B", blocks(p.M, Z, Z, I), "first companion pencil A - lambda B" + at);
    // The state matrix is dense (M^-1 fills in): written up to kExportStateLimit DOFs.
    if (n > kExportStateLimit) {
        report.notes.push_back(fmt::format("state.mtx not written: the state matrix is dense (2n x 2n = {} x {}) "
                                           "above {} DOFs; the companion pencil pencil_A, pencil_B holds the same "
                                           "eigenvalues",
                                           2 * n, 2 * n, kExportStateLimit));
        return report;
    }
    const Eigen::MatrixXd M(p.M);
    Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
    if (lu.isInvertible()) {
        Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * n, 2 * n);
        S.topRightCorner(n, n).setIdentity();
        S.bottomLeftCorner(n, n) = -lu.solve(Eigen::MatrixXd(p.K));
        S.bottomRightCorner(n, n) = -lu.solve(Eigen::MatrixXd(p.C));
        put("state", S, "state matrix, state [x; x']" + at);
    } else {
        report.notes.push_back("state.mtx not written: M is singular, so there is no state matrix M^-1 [K C]");
    }
    return report;
}

}  // namespace gyrokit
