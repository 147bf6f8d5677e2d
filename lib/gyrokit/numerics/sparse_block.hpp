#pragma once
// A block of a sparse matrix by row and column index lists (the free and held DOFs of a static solve).

#include <Eigen/Sparse>
#include <vector>

namespace gyrokit {

// A(rows, cols): rows.size() x cols.size(), entry (i, j) = A(rows[i], cols[j]).
Eigen::SparseMatrix<double> submatrix(const Eigen::SparseMatrix<double>& A, const std::vector<int>& rows,
                                      const std::vector<int>& cols);

}  // namespace gyrokit
