// The linear gyroscopic system  M z'' + (D + w G) z' + (K + w N + w^2 K2) z = w^2 Re(u e^{i w t})
// with w the spin speed (rad/s); G and N per unit speed, K2 per speed squared.
// One type for every model and size: the matrices are stored sparse (a
// finite-element rotor of 100,000 DOFs fits), and the pencil at a speed comes
// dense (at_speed, for the dense solvers) or sparse (sparse_at_speed).
#pragma once

#include <gyrokit/core/band_order.hpp>
#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/dof_layout.hpp>
#include <gyrokit/core/length_unit.hpp>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace gyrokit {

using SparseMatrix = Eigen::SparseMatrix<double>;

// The sparse form of a dense matrix, exact zeros dropped.
SparseMatrix to_sparse(const Eigen::MatrixXd& A);

// A matrix of the system: stored sparse, assigned from a sparse matrix or from
// any dense Eigen expression (exact zeros dropped), so that a small model is
// written down with dense Eigen code and a large one assembled sparse.
class SystemMatrix : public SparseMatrix {
public:
    SystemMatrix() = default;
    SystemMatrix(const SparseMatrix& A) : SparseMatrix(A) {}
    SystemMatrix(SparseMatrix&& A) : SparseMatrix(std::move(A)) {}
    template <class Derived>
    SystemMatrix(const Eigen::SparseMatrixBase<Derived>& A) : SparseMatrix(A) {}
    template <class Derived>
    SystemMatrix(const Eigen::MatrixBase<Derived>& A) : SparseMatrix(to_sparse(A.eval())) {}
    template <class Derived>
    SystemMatrix& operator=(const Eigen::SparseMatrixBase<Derived>& A) {
        SparseMatrix::operator=(A);
        return *this;
    }
    template <class Derived>
    SystemMatrix& operator=(const Eigen::MatrixBase<Derived>& A) {
        SparseMatrix::operator=(to_sparse(A.eval()));
        return *this;
    }
    template <class Derived>
    SystemMatrix(const Eigen::DiagonalBase<Derived>& A) : SparseMatrix(to_sparse(Eigen::MatrixXd(A))) {}
    template <class Derived>
    SystemMatrix& operator=(const Eigen::DiagonalBase<Derived>& A) {
        SparseMatrix::operator=(to_sparse(Eigen::MatrixXd(A)));
        return *this;
    }
    Eigen::MatrixXd dense() const { return Eigen::MatrixXd(static_cast<const SparseMatrix&>(*this)); }
};

// A += B on the rows and columns (i, j): a 2x2 element acting on one DOF pair.
void add_block(Eigen::MatrixXd& A, int i, int j, const Eigen::Matrix2d& B);

// One named source of damping (e.g. "d_G" cage damping); the total damping
// matrix is the sum of all components. Kept apart so that pervasive damping
// can be checked for each component alone. D may be unsymmetric (cross-coupled
// bearing damping, cxy != cyx).
struct DampingComponent {
    std::string name;
    SystemMatrix D;
    // Optional: the matrix at speed w when it depends on speed (e.g. Stokes-layer
    // damping of a liquid ~ sqrt(w)); empty means the constant D.
    std::function<SparseMatrix(double)> of_speed = {};
    SparseMatrix at(double w) const { return of_speed ? of_speed(w) : SparseMatrix(D); }
};

// The three coefficient matrices of the quadratic pencil at one speed:
// P(lambda) = lambda^2 M + lambda C + K.
struct QuadraticPencil {
    Eigen::MatrixXd M, C, K;
    Eigen::MatrixXcd evaluate(std::complex<double> lambda) const;
};

// The same pencil in sparse form; `band_order` (null: as given) the DOF order in
// which the band LU of inverse iteration factors it (BandOrder).
struct SparsePencil {
    SparseMatrix M, C, K;
    std::shared_ptr<const BandOrder> band_order = nullptr;
};
SparsePencil to_sparse(const QuadraticPencil& p);

// The largest magnitude of a matrix entry validate() accepts: the solvers form
// products and squares of entries (norms, scaling), which overflow beyond it.
constexpr double kMaxMatrixEntry = 1e150;

class GyroscopicSystem {
public:
    DofLayout dofs;                           // names always; units, nodes, motions where the model knows them
    SystemMatrix M;                           // mass, symmetric
    SystemMatrix K;                           // stiffness (any structure: cross-coupled bearings)
    SystemMatrix G;                           // gyroscopic per unit speed, skew (0 x 0: none)
    SystemMatrix N;                           // circulatory per unit speed (0 x 0: none)
    SystemMatrix K2;                          // stiffness per speed squared (0 x 0: none), e.g. sloshing
    std::vector<DampingComponent> damping;    // D = sum of components
    // Speed-dependent bearings: their stiffness adds to K, their damping to D;
    // each one's damping counts as a damping component named after the table.
    std::vector<BearingTable> bearings;
    Eigen::VectorXcd unbalance;               // force amplitude per w^2 (empty: none)
    // DOF pairs (u, v) whose complex coordinate u + i v turns forward when the
    // motion turns in the sense of the spin; used to classify whirl.
    std::vector<std::pair<int, int>> whirl_pairs;
    std::vector<double> node_z;               // axial position of each node (m)

    int size() const { return static_cast<int>(M.rows()); }
    // The node nearest the axial position z (m); InputError if the model has no
    // nodes or z lies off the shaft (outside its first and last node), naming
    // positions in `unit`.
    int nearest_node(double z, const LengthUnit& unit = {}) const;
    // The DOFs of a node, those in `unit` only if one is given; InputError if the
    // model has no such node.
    std::vector<int> node_dofs(int node, const std::string& unit = "") const;
    // The node's lateral translations: its DOFs in m that are members of a whirl pair
    // (x, y; not an axial z), or all its DOFs in m where the model has no whirl pairs.
    std::vector<int> node_translations(int node) const;
    // Total damping at speed w (speed matters for speed-dependent components and bearing tables).
    SparseMatrix damping_matrix(double w = 0.0) const;
    // Names of the damping components: `damping`, then bearing tables with damping.
    std::vector<std::string> damping_names() const;
    bool has_damping() const;
    bool has_circulatory() const { return N.nonZeros() > 0 && N.norm() > 0.0; }
    bool has_speed_squared_stiffness() const { return K2.nonZeros() > 0 && K2.norm() > 0.0; }

    // Pencil at spin speed w: C = D(w) + w G, K(w) = K + w N + w^2 K2 (+ bearings).
    SparsePencil sparse_at_speed(double w) const;
    // The same pencil dense (for models small enough to hold densely).
    QuadraticPencil at_speed(double w) const;
    // Unbalance force amplitude at speed w (zero vector if there is none).
    Eigen::VectorXcd unbalance_force(double w) const;

    // The same system with only the named damping components (others removed).
    GyroscopicSystem with_damping_only(const std::vector<std::string>& names) const;

    // Checks dimensions, finiteness and the structural properties (M symmetric
    // and not zero, G skew), the unbalance, DOF names, bearing tables, whirl
    // pairs and the optional DOF units and nodes. Throws InputError naming `origin` on violation.
    void validate(const std::string& origin) const;

    // The band order of the pencils sparse_at_speed gives (found at the first).
    mutable BandOrderCache band_order_cache;
};

// DOF indices of a comma-separated list of names ("x12,y12"; empty: none): InputError
// naming `option` for a name that is no DOF of `names` or one listed twice.
std::vector<int> dofs_by_name(const std::string& list, const std::vector<std::string>& names, const std::string& option);
// The same of names given one by one (an empty name, or one with a comma, is no DOF).
std::vector<int> dofs_by_name(const std::vector<std::string>& list, const std::vector<std::string>& names,
                              const std::string& option);
// InputError naming `what` for an index out of range or listed twice (an output would
// be printed twice).
void check_dof_list(const GyroscopicSystem& sys, const std::vector<int>& dofs, const std::string& what);

}  // namespace gyrokit
