#include <gyrokit/io/export.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/matrix_market.hpp>

#include <filesystem>
#include <fmt/format.h>

namespace gyrokit {

void export_matrices(const GyroscopicSystem& sys, double w, const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(fmt::format("--dir {}: cannot create the directory: {}", dir, ec.message()));
    const auto put = [&](const std::string& name, const Eigen::MatrixXd& A, const std::string& what) {
        write_matrix_market((fs::path(dir) / (name + ".mtx")).string(), A, what);
    };
    const int n = sys.size();
    const QuadraticPencil p = sys.at_speed(w);
    put("M", sys.M, "mass matrix");
    put("K", sys.K, "stiffness matrix");
    put("G", sys.G.size() ? sys.G : Eigen::MatrixXd::Zero(n, n), "gyroscopic matrix per unit speed (rad/s)");
    if (sys.N.size()) put("N", sys.N, "circulatory matrix per unit speed (rad/s)");
    if (sys.K2.size()) put("K2", sys.K2, "stiffness per speed squared");
    const std::string at = fmt::format(" at speed {:.17g} rad/s", w);
    put("D", sys.damping_matrix(w), "total damping matrix" + at);
    for (const auto& c : sys.damping) put("D_" + c.name, c.at(w), "damping component " + c.name + at);
    for (size_t i = 0; i < sys.bearings.size(); ++i) {
        const auto& b = sys.bearings[i];
        Eigen::MatrixXd Kb = Eigen::MatrixXd::Zero(n, n), Cb = Kb;
        add_block(Kb, b.dof_x, b.dof_y, b.at(w).K);
        add_block(Cb, b.dof_x, b.dof_y, b.at(w).C);
        put(fmt::format("K_bearing{}", i + 1), Kb, "stiffness of bearing table " + b.name + at);
        put(fmt::format("D_bearing{}", i + 1), Cb, "damping of bearing table " + b.name + at);
    }
    put("C", p.C, "C = D + w G" + at);
    put("Kw", p.K, "K + w N + w^2 K2 + bearing stiffness" + at);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n), B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topLeftCorner(n, n) = -p.C;
    A.topRightCorner(n, n) = -p.K;
    A.bottomLeftCorner(n, n).setIdentity();
    B.topLeftCorner(n, n) = p.M;
    B.bottomRightCorner(n, n).setIdentity();
    put("pencil_A", A, "first companion pencil A - lambda B, state [lambda x; x]" + at);
    put("pencil_B", B, "first companion pencil A - lambda B" + at);
    Eigen::FullPivLU<Eigen::MatrixXd> lu(p.M);
    if (lu.isInvertible()) {
        Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * n, 2 * n);
        S.topRightCorner(n, n).setIdentity();
        S.bottomLeftCorner(n, n) = -lu.solve(p.K);
        S.bottomRightCorner(n, n) = -lu.solve(p.C);
        put("state", S, "state matrix, state [x; x']" + at);
    }
}

}  // namespace gyrokit
