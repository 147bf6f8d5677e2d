// Finite-element rotor model: Timoshenko shaft elements (shear deformation,
// rotary inertia, gyroscopic moments; hollow circular sections), rigid disks,
// linear bearings and rigid supports, assembled into sparse M, K, G, D.
//
// Coordinates: the shaft axis is z, the spin w > 0 turns about +z (right hand).
// Each node has four lateral DOFs [x, y, theta_x, theta_y]:
//   x, y          displacements of the shaft centre line,
//   theta_x       rotation of the cross-section about +x  (= -dy/dz for a slender beam),
//   theta_y       rotation of the cross-section about +y  (= +dx/dz for a slender beam);
// with FeMotion::all also the axial displacement z and the torsion theta_z
// (node DOFs [x, y, theta_x, theta_y, z, theta_z]; axial and torsional bars with
// linear shape functions, uncoupled from the lateral motion at constant speed);
// FeMotion::axial or ::torsional builds that bar alone (one DOF per node), since
// at constant speed it does not couple to the rest.
// With this right-handed choice both (x, y) and (theta_x, theta_y) turn in the
// positive sense for forward whirl, so every node contributes the whirl pairs
// (x, y) and (theta_x, theta_y).
//
// Equations of motion: M q'' + (D + w G) q' + K q = w^2 Re(u e^{i w t}), G per
// unit speed and skew, a rigid disk adds G(theta_x, theta_y) = +Ip,
// G(theta_y, theta_x) = -Ip. Element matrices: Nelson & McVaugh (1976),
// Nelson (1980), Friswell et al., "Dynamics of Rotating Machines", ch. 5;
// see docs/fe_rotor.md for the equations as implemented.
#pragma once

#include <gyrokit/core/dof_layout.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/eig/sparse_eigensolver.hpp>

#include <Eigen/Sparse>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gyrokit {

// Flexible coupling between two shafts: springs on the relative motion of its two
// nodes (no coupling between the directions), its mass and inertias half at each node.
// Its dampers act on the same relative motions (the damping component "couplings");
// the lateral and bending ones turn with the shafts (an elastomer element): in fixed
// axes they add the circulatory term w c [0 1; -1 0] on each relative whirl pair, the
// internal damping that destabilises forward whirl above a threshold speed.
struct FeCoupling {
    double k_lateral = 0.0;          // N/m, >= 0: x, y
    double k_bending = 0.0;          // N m/rad, >= 0: theta_x, theta_y (angular misalignment)
    double k_axial = 0.0;            // N/m, >= 0: z
    double k_torsion = 0.0;          // N m/rad, >= 0: theta_z
    double c_lateral = 0.0;          // N s/m, >= 0
    double c_bending = 0.0;          // N m s/rad, >= 0
    double c_axial = 0.0;            // N s/m, >= 0
    double c_torsion = 0.0;          // N m s/rad, >= 0
    double mass = 0.0;               // kg, >= 0
    double diametral_inertia = 0.0;  // Id, kg m^2, >= 0
    double polar_inertia = 0.0;      // Ip, kg m^2, >= 0 (also gyroscopic)
};

// One shaft element between node e and node e + 1 (elements form one chain).
// With `coupling` set the element is a flexible coupling of that length instead of a
// beam (its diameters and material are then unused).
// Tapered (conical) when the diameters at node e + 1 are given: the section then
// varies linearly from node e to node e + 1 (docs/fe_rotor.md, "Tapered elements").
struct FeShaftElement {
    double length = 0.0;            // m, > 0
    double outer_diameter = 0.0;    // m, > 0 (at node e)
    double inner_diameter = 0.0;    // m, in [0, outer_diameter) (at node e)
    std::optional<double> outer_diameter_end;   // m, > 0, at node e + 1; none: uniform
    std::optional<double> inner_diameter_end;   // m, in [0, outer_diameter_end); none: inner_diameter
    std::optional<FeCoupling> coupling;          // set: a flexible coupling, not a beam
    double youngs_modulus = 0.0;    // E, Pa, > 0
    double shear_modulus = 0.0;     // G, Pa, > 0; 0 = E / (2 (1 + poisson_ratio))
    double poisson_ratio = 0.3;     // in (-1, 0.5]; used for G (if 0) and the shear coefficient
    double density = 0.0;           // kg/m^3, > 0
};

// Rigid disk attached at a node.
struct FeDisk {
    int node = 0;
    double mass = 0.0;              // kg, >= 0 (lateral and axial)
    double diametral_inertia = 0.0; // Id, kg m^2, >= 0
    double polar_inertia = 0.0;     // Ip, kg m^2, >= 0 (gyroscopic, and torsional)
    double unbalance = 0.0;         // m_e e, kg m, >= 0 (mass times eccentricity)
    double unbalance_phase = 0.0;   // rad, angle of the unbalance at t = 0 from +x
};

// Linear bearing between a node and the ground, acting on (x, y):
// force = -[kxx kxy; kyx kyy] (x, y) - [cxx cxy; cyx cyy] (x', y'); where the model
// has the axial DOF also a thrust stiffness and damping on z (kzz, czz; 0 otherwise).
// Each part acts where the model has its DOFs (a torsional model: none).
struct FeBearing {
    int node = 0;
    double kxx = 0.0, kxy = 0.0, kyx = 0.0, kyy = 0.0;   // N/m
    double cxx = 0.0, cxy = 0.0, cyx = 0.0, cyy = 0.0;   // N s/m
    double kzz = 0.0;                                     // N/m, axial
    double czz = 0.0;                                     // N s/m, axial
};

// Bearing pedestal (support): a mass on springs and dampers to the ground that
// carries every bearing at its node (their forces act on the relative motion of
// shaft and pedestal). Adds the DOFs px<node>, py<node> after the node DOFs
// (in a model with lateral DOFs; an axial or torsional model leaves it out).
struct FePedestal {
    int node = 0;
    double mass = 0.0;               // kg, > 0
    double kxx = 0.0, kyy = 0.0;     // N/m, >= 0, pedestal to ground
    double cxx = 0.0, cyy = 0.0;     // N s/m, >= 0
};

// Rigid support: the chosen DOFs of a node are held at zero and removed from
// the assembled system (pinned: x and y; clamped: all of the node's DOFs).
// Holds on DOFs the model does not build (FeRotor::motion) are no-ops.
struct FeSupport {
    int node = 0;
    bool x = true, y = true, theta_x = false, theta_y = false;
    bool z = false, theta_z = false;
};

// The assembled matrices (constrained DOFs removed). Row/column order: node by
// node, the motion's DOFs in the order [x, y, theta_x, theta_y, z, theta_z] each,
// constrained DOFs skipped, then (px, py) of each pedestal in the order given.
struct FeRotorMatrices {
    Eigen::SparseMatrix<double> M;   // mass (translational + rotary + disks), symmetric positive definite
    Eigen::SparseMatrix<double> K;   // stiffness (shaft + bearings); symmetric when kxy = kyx
    Eigen::SparseMatrix<double> G;   // gyroscopic per unit speed, skew
    Eigen::SparseMatrix<double> D;   // bearing and pedestal damping; symmetric when cxy = cyx
    Eigen::SparseMatrix<double> D_couplings;   // coupling damping, symmetric
    Eigen::SparseMatrix<double> N;   // circulatory per unit speed (rotating coupling dampers), skew
    Eigen::VectorXcd unbalance;      // force amplitude per w^2 (forward-turning disk unbalance)
    DofLayout dofs;                                // "x3", "y3", "tx3", "ty3" (and "z3", "tz3"; pedestals "px3", "py3")
    std::vector<std::pair<int, int>> whirl_pairs;  // (x, y) and (theta_x, theta_y) of each node, when both are free
    std::vector<double> node_z;                    // axial position of each node (m), z_0 = 0

    int size() const { return static_cast<int>(M.rows()); }
    // Sparse pencil at spin speed w: M, C = D + w G, K + w N.
    SparsePencil at_speed(double w) const;
    // The model as a gyroscopic system (damping components "bearings" and "couplings").
    GyroscopicSystem to_system() const;
};

// At most this many elements in all: 20,000,000 DOFs (the largest size a Matrix
// Market file may declare), far beyond the solvers' reach, refused before assembly.
constexpr int kMaxFeElements = 4'999'999;

// Which DOFs each node has. At constant speed the axial and the torsional bars couple
// neither to each other nor to the lateral motion, so an axial or torsional analysis
// needs only its own DOF.
enum class FeMotion {
    lateral,     // x, y, theta_x, theta_y (4 per node)
    all,         // lateral, z and theta_z (6 per node)
    axial,       // z (1 per node)
    torsional,   // theta_z (1 per node)
};
int dofs_per_node(FeMotion m);
const char* to_string(FeMotion m);

class FeRotor {
public:
    std::vector<FeShaftElement> elements;   // element e joins node e and node e + 1
    std::vector<FeDisk> disks;
    std::vector<FeBearing> bearings;
    std::vector<FeSupport> supports;
    std::vector<FePedestal> pedestals;       // at most one per node
    bool shear_deformation = true;   // false: Euler-Bernoulli / Rayleigh beam (Phi = 0)
    bool rotary_inertia = true;      // false: no rotary inertia and no shaft gyroscopic moments
    FeMotion motion = FeMotion::lateral;

    bool has_lateral() const { return motion == FeMotion::lateral || motion == FeMotion::all; }
    bool has_axial() const { return motion == FeMotion::all || motion == FeMotion::axial; }
    bool has_torsion() const { return motion == FeMotion::all || motion == FeMotion::torsional; }

    int node_count() const { return elements.empty() ? 0 : static_cast<int>(elements.size()) + 1; }

    // Throws InputError naming the item (element/disk/bearing/support index), the
    // key, the value and the allowed range.
    void validate() const;
    // Validates, then assembles in O(number of elements + disks + bearings).
    FeRotorMatrices assemble() const;
};


// The checks validate() makes of one shaft element (or a section of equal ones),
// naming it `where` in messages.
void validate_element(const FeShaftElement& e, const std::string& where);

// The rotor's GyroscopicSystem (validated, assembled): the verb every model shares.
GyroscopicSystem make_system(const FeRotor& r);

// Section and element quantities, exposed for tests and documentation.
struct FeSection {
    double area = 0.0;              // A = pi (do^2 - di^2) / 4
    double second_moment = 0.0;     // I = pi (do^4 - di^4) / 64
    double shear_coefficient = 0.0; // kappa, Cowper (1966) for hollow circular sections
    double shear_modulus = 0.0;     // G actually used
};
// The section at node e (xi = 0) or, of a tapered element, at xi = (z - z_e) / length in [0, 1].
FeSection fe_section(const FeShaftElement& e, double xi = 0.0);
// The element's mass rho int A dz (Simpson's rule: exact, A is quadratic along a cone).
double fe_element_mass(const FeShaftElement& e);

// Cowper's shear coefficient of a hollow circular section, m = di / do:
// kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2).
double cowper_shear_coefficient(double poisson_ratio, double diameter_ratio);

// Element matrices: lateral in the element DOF order [x1 y1 tx1 ty1 x2 y2 tx2 ty2];
// the axial (z1, z2) and torsional (tz1, tz2) bars. D: a coupling's dampers, N their
// circulatory part per unit speed (both 0 for a beam).
struct FeElementMatrices {
    Eigen::Matrix<double, 8, 8> M, K, G, D, N;
    Eigen::Matrix2d M_axial, K_axial, D_axial, M_torsion, K_torsion, D_torsion;
};
FeElementMatrices fe_shaft_element_matrices(const FeShaftElement& e, bool shear_deformation = true,
                                            bool rotary_inertia = true);

// A uniform shaft of `count` equal elements (convenience for studies and tests).
FeRotor fe_uniform_shaft(double length, int count, double outer_diameter, double inner_diameter,
                         double youngs_modulus, double poisson_ratio, double density);

}  // namespace gyrokit
