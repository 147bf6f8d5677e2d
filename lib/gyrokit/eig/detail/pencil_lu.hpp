// The LU factorization of P(lambda) = lambda^2 M + lambda C + K for inverse
// iteration: a band LU with partial pivoting (LAPACK's zgbtf2 algorithm and band
// storage) where the pencil's band is narrow (an FE rotor in node order: 7 to 11
// off-diagonals), else Eigen's SparseLU. The band LU factors in the pencil's
// band_order where it has one.
#pragma once

#include <gyrokit/core/gyroscopic_system.hpp>

#include <Eigen/SparseLU>
#include <complex>
#include <vector>

namespace gyrokit::detail {

// The widest band the band LU takes (lower + upper + 1): beyond it the band's
// fill costs more than SparseLU's ordering.
constexpr int kMaxBandLU = 64;

class PencilLU {
public:
    PencilLU() = default;
    PencilLU(const PencilLU&) = delete;
    PencilLU& operator=(const PencilLU&) = delete;
    ~PencilLU();
    // Factors P(lambda); false if it is singular (or the factorization fails).
    bool compute(const SparsePencil& p, std::complex<double> lambda);
    Eigen::VectorXcd solve(const Eigen::VectorXcd& b) const;           // P x = b
    Eigen::VectorXcd adjoint_solve(const Eigen::VectorXcd& c) const;   // P^H y = c
    // Both at once (one pass over a band factorization each way); x and y must not
    // be b or c.
    void solve_both(const Eigen::VectorXcd& b, const Eigen::VectorXcd& c, Eigen::VectorXcd& x, Eigen::VectorXcd& y) const;
    bool banded() const { return band_; }

private:
    void reorder(Eigen::VectorXcd& v, bool to) const;
    bool band_ = false;
    std::shared_ptr<const BandOrder> order_;   // the pencil's band order (null: as given)
    int n_ = 0, kl_ = 0, ku_ = 0;
    std::vector<std::complex<double>> ab_;   // LAPACK band storage, 2 kl + ku + 1 rows
    std::vector<int> ipiv_;
    std::vector<std::complex<double>> inverse_pivot_;   // 1 / U's diagonal
    // mutable: SparseLU::adjoint() is not const
    mutable Eigen::SparseLU<Eigen::SparseMatrix<std::complex<double>>, Eigen::COLAMDOrdering<int>> sparse_;
};

}  // namespace gyrokit::detail
