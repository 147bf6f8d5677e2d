// The solver a scene or a call asks for, by name, and what a mode count means when
// none is given: the words a scene file, the CLI and Python share. Which solver a
// model then gets is decided by analysis/solver_choice.hpp.
#pragma once

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

}  // namespace gyrokit
