#include <gyrokit/numerics/sparse_block.hpp>

namespace gyrokit {

using SpMat = Eigen::SparseMatrix<double>;

SpMat submatrix(const SpMat& A, const std::vector<int>& rows, const std::vector<int>& cols) {
    std::vector<int> row_of(static_cast<std::size_t>(A.rows()), -1), col_of(static_cast<std::size_t>(A.cols()), -1);
    for (std::size_t k = 0; k < rows.size(); ++k) row_of[rows[k]] = static_cast<int>(k);
    for (std::size_t k = 0; k < cols.size(); ++k) col_of[cols[k]] = static_cast<int>(k);
    std::vector<Eigen::Triplet<double>> t;
    for (int c = 0; c < A.outerSize(); ++c)
        for (SpMat::InnerIterator it(A, c); it; ++it)
            if (row_of[it.row()] >= 0 && col_of[it.col()] >= 0)
                t.emplace_back(row_of[it.row()], col_of[it.col()], it.value());
    SpMat B(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
    B.setFromTriplets(t.begin(), t.end());
    return B;
}

}  // namespace gyrokit
