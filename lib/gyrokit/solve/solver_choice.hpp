// Which solver a model gets: the options every front end fills from the
// scene's [analysis], its flags or keyword arguments, and the one rule that
// resolves `auto` and validates them.
#pragma once

#include <gyrokit/solve/spectrum_solver.hpp>
#include <gyrokit/core/solver_kind.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// Auto: the sparse solver above this many DOFs, the dense one up to it.
constexpr int kAutoSparseDofs = 200;
// Auto for the modes in range (kModesInRange): the dense solver up to this many
// DOFs. Its continuation tracks every mode in range, where a sparse window holds
// a fixed number that need not reach the band; measured on data/compressor336.toml
// (stability, 151 speeds, 2 threads: dense 5.7 s, every mode in range; a sparse
// window 1.0 s) and on the same rotor in 168 elements (672 DOFs: 32 s and 2.4 s).
constexpr int kAutoDenseInRangeDofs = 400;
// SolverOptions (core/solver_kind.hpp): what a scene or call asks for.

struct SolverChoice {
    SolverKind kind = SolverKind::Dense;  // Dense or Sparse, never Auto
    int modes = 0;                        // the number of modes (sparse: the window size; dense: as asked)
    SolverFactory make;
    std::vector<std::string> notes;       // e.g. the default number of sparse modes
    bool shifted = false;                 // sparse: the window is centred away from zero (target, target_order)
};
// Auto resolved by size: kAutoSparseDofs, or kAutoDenseInRangeDofs where `modes`
// is kModesInRange.
SolverKind resolve_solver_kind(int dofs, SolverKind requested, int modes = 0);
// Validates the options (InputError naming the field) and the system, and makes the solver.
SolverChoice choose_solver(const GyroscopicSystem& sys, const SolverOptions& opt);

// The meaning of a mode count K at one speed on the dense solver: the K lowest by
// frequency (the modes that vibrate first; real, non-oscillating eigenvalues after
// them, by |lambda|), as the Campbell diagram's K lowest at its first speed. (A sparse
// window holds the K nearest its target instead.) Nothing changes where K <= 0 or the
// spectrum holds at most K modes. Returns how many it held.
std::size_t keep_lowest_modes(QuadraticSpectrum& s, int modes);


}  // namespace gyrokit
