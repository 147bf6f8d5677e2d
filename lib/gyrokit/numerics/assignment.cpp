#include <gyrokit/numerics/assignment.hpp>

#include <gyrokit/core/error.hpp>

#include <limits>

namespace gyrokit {

std::vector<int> solve_assignment(const Eigen::MatrixXd& cost) {
    // A NaN or infinite cost would leave no augmenting path: the loop below would never end.
    if (!cost.allFinite()) throw SolverError("mode matching met a NaN or infinite cost (repeated speeds or a NaN "
                                             "eigenvalue); use distinct, increasing speeds");
    const int rows = static_cast<int>(cost.rows()), cols = static_cast<int>(cost.cols());
    const bool transposed = rows > cols;   // the method below needs n <= m
    const Eigen::MatrixXd a = transposed ? Eigen::MatrixXd(cost.transpose()) : cost;
    const int n = static_cast<int>(a.rows()), m = static_cast<int>(a.cols());
    const double inf = std::numeric_limits<double>::infinity();
    // Potentials u, v and matching p (1-based, column -> row), shortest augmenting paths.
    std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
    std::vector<int> p(m + 1, 0), way(m + 1, 0);
    for (int i = 1; i <= n; ++i) {
        p[0] = i;
        int j0 = 0;
        std::vector<double> minv(m + 1, inf);
        std::vector<char> used(m + 1, 0);
        do {
            used[j0] = 1;
            const int i0 = p[j0];
            double delta = inf;
            int j1 = 0;
            for (int j = 1; j <= m; ++j) {
                if (used[j]) continue;
                const double cur = a(i0 - 1, j - 1) - u[i0] - v[j];
                if (cur < minv[j]) { minv[j] = cur; way[j] = j0; }
                if (minv[j] < delta) { delta = minv[j]; j1 = j; }
            }
            for (int j = 0; j <= m; ++j) {
                if (used[j]) { u[p[j]] += delta; v[j] -= delta; }
                else minv[j] -= delta;
            }
            j0 = j1;
        } while (p[j0] != 0);
        do { const int j1 = way[j0]; p[j0] = p[j1]; j0 = j1; } while (j0);
    }
    std::vector<int> result(rows, -1);
    for (int j = 1; j <= m; ++j) {
        if (p[j] == 0) continue;
        if (transposed) result[j - 1] = p[j] - 1;
        else result[p[j] - 1] = j - 1;
    }
    return result;
}

}  // namespace gyrokit
