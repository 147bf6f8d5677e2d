// Matrix Market (.mtx) input and output for dense matrices and vectors.
// The readers are strict: the first problem in a file is reported as a one-line
// gyrokit::InputError "<path>: line <n>: <what is wrong>; <what is allowed>".
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>

namespace gyrokit {

// Reads a real matrix (dense result) from a Matrix Market file: "matrix coordinate|array",
// field "real|integer", symmetry "general|symmetric|skew-symmetric". Throws InputError.
Eigen::MatrixXd read_matrix_market(const std::string& path);

// The same reader with a sparse result: coordinate files of any size (array
// files as for the dense reader); explicit zeros are dropped.
Eigen::SparseMatrix<double> read_matrix_market_sparse(const std::string& path);

// Reads a vector (n x 1 matrix, or 1 x n) that may be real, integer or complex
// (field "complex": two numbers per entry). Throws InputError.
Eigen::VectorXcd read_matrix_market_vector(const std::string& path);

// Writes a dense real matrix in "coordinate real general" form with all nonzeros,
// 17 significant digits, through an OutputFile (`option` names the path in errors).
// Throws gyrokit::Error if the file cannot be written (InputError if the path is an
// input of the run, or A is empty or holds NaN/Inf, which the reader would reject).
void write_matrix_market(const std::string& path, const Eigen::MatrixXd& A, const std::string& comment = "",
                         const std::string& option = "path");
// The same for a sparse matrix: its stored nonzeros, in O(nonzeros).
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A, const std::string& comment = "",
                         const std::string& option = "path");

}  // namespace gyrokit
