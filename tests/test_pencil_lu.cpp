// The LU of P(lambda) behind inverse iteration: the band path (zgbtrf's algorithm
// and storage, gyrokit's own code) and the SparseLU path solve P x = b and
// P^H y = b, alone or both at once, to a backward error of rounding size, and a
// singular P is reported.
#include <gyrokit/eig/detail/pencil_lu.hpp>

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

using namespace gyrokit;
using cd = std::complex<double>;

namespace {

// A non-symmetric pencil with `lower` and `upper` off-diagonals, entries that make
// row interchanges happen (small diagonal of K in places).
SparsePencil banded(int n, int lower, int upper) {
    std::vector<Eigen::Triplet<double>> m, c, k;
    for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - lower); j <= std::min(n - 1, i + upper); ++j) {
            const double s = std::sin(1.0 + 3.0 * i + 7.0 * j), t = std::cos(2.0 + 5.0 * i - 3.0 * j);
            k.emplace_back(i, j, (i == j ? (i % 7 == 3 ? 1e-3 : 4.0) : 0.0) + s);
            c.emplace_back(i, j, 0.1 * t);
            if (std::abs(i - j) <= 1) m.emplace_back(i, j, i == j ? 1.0 + 0.1 * s : 0.05 * t);
        }
    SparsePencil p;
    for (auto [A, list] : {std::pair{&p.M, &m}, std::pair{&p.C, &c}, std::pair{&p.K, &k}}) {
        A->resize(n, n);
        A->setFromTriplets(list->begin(), list->end());
        A->makeCompressed();
    }
    return p;
}

Eigen::MatrixXcd dense_at(const SparsePencil& p, cd l) {
    return (l * l) * Eigen::MatrixXd(p.M).cast<cd>() + l * Eigen::MatrixXd(p.C).cast<cd>() +
           Eigen::MatrixXd(p.K).cast<cd>();
}

// |A x - b| / (|A| |x| + |b|): a backward error, of the order of n eps for a stable solve.
double residual(const Eigen::MatrixXcd& A, const Eigen::VectorXcd& x, const Eigen::VectorXcd& b) {
    return (A * x - b).norm() / (A.norm() * x.norm() + b.norm());
}

}  // namespace

TEST_CASE("PencilLU solves P x = b and P^H y = b on the band path and the sparse path to rounding", "[pencil_lu]") {
    const int n = 300;
    const cd l(-3.0, 2.5);
    Eigen::VectorXcd b(n);
    for (int i = 0; i < n; ++i) b[i] = cd(std::sin(0.3 * i), std::cos(1.7 * i));
    const double eps = std::numeric_limits<double>::epsilon();
    // Narrow (the band path: FE rotors in node order) and wide bands (SparseLU).
    for (auto [lower, upper, band] : {std::tuple{3, 5, true}, std::tuple{7, 7, true}, std::tuple{0, 2, true},
                                      std::tuple{40, 30, false}}) {
        CAPTURE(lower, upper);
        const SparsePencil p = banded(n, lower, upper);
        detail::PencilLU lu;
        REQUIRE(lu.compute(p, l));
        CHECK(lu.banded() == band);
        const Eigen::MatrixXcd A = dense_at(p, l);
        const Eigen::VectorXcd x = lu.solve(b), y = lu.adjoint_solve(b);
        CHECK(residual(A, x, b) <= 100 * n * eps);
        CHECK(residual(A.adjoint(), y, b) <= 100 * n * eps);
        // The same solutions as a dense LU, within the condition number's reach.
        const Eigen::PartialPivLU<Eigen::MatrixXcd> dense(A);
        const double cond = A.norm() * dense.inverse().norm();
        CHECK((x - dense.solve(b)).norm() <= 100 * n * eps * cond * x.norm());
        const Eigen::PartialPivLU<Eigen::MatrixXcd> dense_h(A.adjoint());
        CHECK((y - dense_h.solve(b)).norm() <= 100 * n * eps * cond * y.norm());
        // Both at once (one pass each way over the band), with a second right-hand side.
        const Eigen::VectorXcd c = b.reverse().conjugate();
        Eigen::VectorXcd xb, yb;
        lu.solve_both(b, c, xb, yb);
        CHECK(residual(A, xb, b) <= 100 * n * eps);
        CHECK(residual(A.adjoint(), yb, c) <= 100 * n * eps);
        CHECK((xb - x).norm() <= 100 * n * eps * cond * x.norm());
    }
}

TEST_CASE("PencilLU reports a singular P(lambda)", "[pencil_lu]") {
    // P(0) = K with a zero row and column: no factorization, on either path.
    for (int upper : {2, 70}) {
        SparsePencil p = banded(100, 2, upper);
        p.K = SparseMatrix(p.K.pruned());
        for (int k = 0; k < p.K.outerSize(); ++k)
            for (SparseMatrix::InnerIterator it(p.K, k); it; ++it)
                if (it.row() == 50 || it.col() == 50) it.valueRef() = 0.0;
        detail::PencilLU lu;
        CHECK_FALSE(lu.compute(p, cd(0.0)));
    }
}
