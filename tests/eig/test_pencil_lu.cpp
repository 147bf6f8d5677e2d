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

namespace {

// p with its DOFs renumbered: DOF i of p becomes new_of[i].
SparsePencil renumbered(const SparsePencil& p, const std::vector<int>& new_of) {
    SparsePencil q;
    for (auto [A, B] : {std::pair{&q.M, &p.M}, std::pair{&q.C, &p.C}, std::pair{&q.K, &p.K}}) {
        std::vector<Eigen::Triplet<double>> t;
        for (int k = 0; k < B->outerSize(); ++k)
            for (SparseMatrix::InnerIterator it(*B, k); it; ++it)
                t.emplace_back(new_of[static_cast<size_t>(it.row())], new_of[static_cast<size_t>(k)], it.value());
        A->resize(B->rows(), B->cols());
        A->setFromTriplets(t.begin(), t.end());
        A->makeCompressed();
    }
    return q;
}

}  // namespace

TEST_CASE("A pencil numbered by kind is factored in its band order, with the same solutions", "[pencil_lu]") {
    // A band pencil (3 and 5 off-diagonals) renumbered as a model exported by kind
    // numbers its DOFs (the even ones first, then the odd ones): its band is then
    // half the model, beyond the band LU; reverse Cuthill-McKee brings it back.
    const int n = 300;
    const SparsePencil p = banded(n, 3, 5);
    std::vector<int> by_kind(n);
    for (int i = 0; i < n; ++i) by_kind[static_cast<size_t>(i)] = (i % 2) * (n / 2) + i / 2;
    SparsePencil q = renumbered(p, by_kind);
    int kl = 0, ku = 0;
    pattern_bandwidths({&q.M, &q.C, &q.K}, nullptr, kl, ku);
    REQUIRE(kl + ku + 1 > detail::kMaxBandLU);
    q.band_order = narrower_band_order({&q.M, &q.C, &q.K});
    REQUIRE(q.band_order);
    pattern_bandwidths({&q.M, &q.C, &q.K}, q.band_order.get(), kl, ku);
    CAPTURE(kl, ku);
    // The pattern's graph has bandwidth 5 in p's numbering; Cuthill-McKee's levels
    // are at most two of those apart.
    CHECK(kl <= 10);
    CHECK(ku <= 10);

    const cd l(-3.0, 2.5);
    Eigen::VectorXcd b(n), c(n);
    for (int i = 0; i < n; ++i) b[i] = cd(std::sin(0.3 * i), std::cos(1.7 * i)), c[i] = cd(std::cos(0.2 * i), 0.5);
    const double eps = std::numeric_limits<double>::epsilon();
    const Eigen::MatrixXcd A = dense_at(q, l);
    detail::PencilLU lu;
    REQUIRE(lu.compute(q, l));
    CHECK(lu.banded());
    Eigen::VectorXcd x, y;
    lu.solve_both(b, c, x, y);
    CHECK(residual(A, x, b) <= 100 * n * eps);
    CHECK(residual(A.adjoint(), y, c) <= 100 * n * eps);
    CHECK(residual(A, lu.solve(b), b) <= 100 * n * eps);
    CHECK(residual(A.adjoint(), lu.adjoint_solve(c), c) <= 100 * n * eps);
    // The same solution as the pencil in its band numbering (the LU there: row
    // interchanges may differ, within the condition number's reach).
    detail::PencilLU lu_p;
    REQUIRE(lu_p.compute(p, l));
    Eigen::VectorXcd bp(n);
    for (int i = 0; i < n; ++i) bp[i] = b[by_kind[static_cast<size_t>(i)]];
    const Eigen::VectorXcd xp = lu_p.solve(bp);
    const Eigen::PartialPivLU<Eigen::MatrixXcd> dense(A);
    const double cond = A.norm() * dense.inverse().norm();
    double diff = 0.0;
    for (int i = 0; i < n; ++i) diff = std::max(diff, std::abs(xp[i] - x[by_kind[static_cast<size_t>(i)]]));
    CHECK(diff <= 100 * n * eps * cond * x.norm());

    // Any order gives the same solutions: one that widens the band (a shuffle) is
    // measured as it is and factored on the path its band allows.
    auto shuffle = std::make_shared<BandOrder>();
    shuffle->old_of.resize(n);
    for (int i = 0; i < n; ++i) shuffle->old_of[static_cast<size_t>(i)] = (i * 7) % n;   // 7 and 300 coprime
    shuffle->new_of.resize(n);
    for (int i = 0; i < n; ++i) shuffle->new_of[static_cast<size_t>(shuffle->old_of[static_cast<size_t>(i)])] = i;
    q.band_order = shuffle;
    detail::PencilLU lu_s;
    REQUIRE(lu_s.compute(q, l));
    CHECK_FALSE(lu_s.banded());
    CHECK(residual(A, lu_s.solve(b), b) <= 100 * n * eps);
    // An order for another size is not used (the pencil as numbered: SparseLU).
    auto half = std::make_shared<BandOrder>();
    for (int i = 0; i < n / 2; ++i) half->old_of.push_back(i), half->new_of.push_back(i);
    q.band_order = half;
    detail::PencilLU lu_h;
    REQUIRE(lu_h.compute(q, l));
    CHECK_FALSE(lu_h.banded());
    CHECK(residual(A, lu_h.solve(b), b) <= 100 * n * eps);
    // A pencil already in band order keeps it.
    CHECK_FALSE(narrower_band_order({&p.M, &p.C, &p.K}));
}
