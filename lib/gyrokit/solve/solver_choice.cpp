#include <gyrokit/solve/solver_choice.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

SolverKind resolve_solver_kind(int dofs, SolverKind requested, int modes) {
    if (requested != SolverKind::Auto) return requested;
    return dofs > (modes == kModesInRange ? kAutoDenseInRangeDofs : kAutoSparseDofs) ? SolverKind::Sparse
                                                                                     : SolverKind::Dense;
}

SolverChoice choose_solver(const GyroscopicSystem& sys, const SolverOptions& opt) {
    if (opt.modes < kModesInRange)
        throw InputError(fmt::format("{} {}: allowed: 0 (all modes; the sparse solver: {}) or more",
                                     option_field("modes"), opt.modes, kDefaultSparseModes));
    if (opt.target && !std::isfinite(*opt.target))
        throw InputError(fmt::format("{} {}: allowed: a finite frequency in rad/s", option_field("target"), *opt.target));
    if (!std::isfinite(opt.target_order))
        throw InputError(fmt::format("{} {}: allowed: a finite multiple of the speed", option_field("target_order"),
                                     opt.target_order));
    if (opt.lanczos_vectors < 0)
        throw InputError(fmt::format("{} {}: allowed: 0 (automatic) or more", option_field("lanczos_vectors"),
                                     opt.lanczos_vectors));
    const int n = sys.size();
    SolverChoice c;
    c.kind = resolve_solver_kind(n, opt.kind, opt.modes);
    if (c.kind == SolverKind::Dense) {
        c.modes = std::max(0, opt.modes);   // every mode is computed; a target does not matter
        c.make = dense_solver(sys, opt.eig);
        return c;
    }
    SparseEigenOptions so;
    so.modes = opt.modes > 0 ? opt.modes : kDefaultSparseModes;
    if (opt.modes <= 0)
        c.notes.push_back(fmt::format("the sparse solver computes {} modes near the target; set modes for another "
                                      "number",
                                      so.modes));
    so.shift = {0.0, opt.target.value_or(0.0)};
    c.shifted = opt.target.value_or(0.0) != 0.0 || opt.target_order != 0.0;
    so.shift_order = opt.target_order;
    so.lanczos_vectors = opt.lanczos_vectors;
    so.left_vectors = opt.eig.left_vectors;
    c.modes = so.modes;
    c.make = sparse_solver(sys, so, opt.reuse);
    return c;
}

std::size_t keep_lowest_modes(QuadraticSpectrum& s, int modes) {
    const std::size_t held = s.modes.size();
    if (modes <= 0 || held <= static_cast<std::size_t>(modes)) return held;
    sort_by_frequency(s.modes);
    s.modes.resize(static_cast<std::size_t>(modes));
    s.partial = true;   // not every mode of the pencil
    return held;
}

}  // namespace gyrokit
