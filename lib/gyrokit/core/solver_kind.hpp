// The solver a scene or a call asks for (SolverOptions: plain data, held by a Scene and
// filled by every front end), its words (the names a scene file, the CLI and Python
// share) and what a mode count means when none is given. Which solver a model then
// gets is decided by solve/solver_choice.hpp.
#pragma once

#include <optional>
#include <string>

namespace gyrokit {

enum class SolverKind { Auto, Dense, Sparse };
SolverKind parse_solver_kind(const std::string& name);   // "auto" | "dense" | "sparse"
std::string to_string(SolverKind k);

// Modes the sparse solver computes when none are asked for.
constexpr int kDefaultSparseModes = 6;

// `modes` not given: the modes in the range the speeds excite (tracking_options);
// to a solver it means every mode (dense) or kDefaultSparseModes (sparse).
constexpr int kModesInRange = -1;

// The dense method: Auto (default: the state matrix where it is faster and every pair
// is verified, else ScaledQZ), ScaledQZ, ClassicQZ, or the state matrix
// (eig/quadratic_eigensolver.hpp).
enum class EigenMethod { Auto, ScaledQZ, StateMatrix, ClassicQZ };
EigenMethod parse_eigen_method(const std::string& name);   // "auto" | "qz" | "qz-classic" | "state"
std::string to_string(EigenMethod m);
// Auto takes the state matrix from this many DOFs on (below it QZ is as fast and
// needs no refinement; docs/benchmarks.md, "Dense eigensolvers").
constexpr int kAutoStateDofs = 64;

struct EigenOptions {
    EigenMethod method = EigenMethod::Auto;
    bool left_vectors = false;   // keep the left vectors in the modes (always computed, for the error bounds)
};

// The fields carry the names of the scene's [analysis] keys (and the CLI's options).
struct SolverOptions {
    SolverKind kind = SolverKind::Auto;   // solver
    EigenOptions eig;                     // dense: auto, scaled QZ or state matrix
    int modes = 0;                        // modes wanted; 0: all (dense) or kDefaultSparseModes (sparse);
                                          // kModesInRange: as 0, the tracking keeps those in range
    std::optional<double> target;         // rad/s: the sparse search centre (default 0: the lowest modes)
    double target_order = 0.0;            // the centre moves as target + target_order * speed
    int lanczos_vectors = 0;              // sparse: Arnoldi vectors, 0 = automatic
    bool reuse = true;                    // sparse: continue each speed from the last one (continue_window)
};

}  // namespace gyrokit
