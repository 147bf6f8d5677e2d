// Critical speeds (a tracked branch crosses a harmonic line k w) and stability
// thresholds (a branch becomes unstable: Re lambda beyond its error bound), refined by root finding on
// the branch rather than read off the grid.
#pragma once

#include <gyrokit/analysis/campbell.hpp>

#include <limits>
#include <string>
#include <vector>

namespace gyrokit {

// API 684: amplification factors below this are not critical.
constexpr double kApi684CriticalAmplification = 2.5;
// Half-power amplification factors up to this many DOFs (each costs some hundred
// solves of the dynamic stiffness); beyond, 1/(2 zeta).
constexpr int kHalfPowerDofs = 3000;
enum class AmplificationMethod { HalfPower, DampingRatio };
std::string to_string(AmplificationMethod m);   // "half-power", "1/(2 zeta)"

struct CriticalSpeed {
    double speed = 0;      // rad/s
    // rad/s: |speed - exact crossing| <= bound, to first order: the error bound of
    // Im lambda - k w over its slope (docs/numerics.md); infinite where unknown.
    double bound = std::numeric_limits<double>::infinity();
    int harmonic = 1;      // k of the line Im(lambda) = k w
    int branch = 0;        // Campbell branch id; direct method: rank by frequency at that speed
    Mode mode;             // the mode at the critical speed
    // API 684 amplification factor (set_amplification_factors): NaN until set.
    double amplification = std::numeric_limits<double>::quiet_NaN();
    AmplificationMethod amplification_method = AmplificationMethod::DampingRatio;
    int probe = -1;        // half-power: the DOF whose response peak was measured
    std::string amplification_dof{};    // its name ("" for 1/(2 zeta))
    std::string amplification_note{};   // 1/(2 zeta): why the half-power method did not apply ("" otherwise)
    // API 684: a crossing with an amplification factor below 2.5 is not a critical
    // speed (heavily damped, no separation margin required).
    bool api684_critical() const { return !(amplification < kApi684CriticalAmplification); }
};

// The separation margin (percent) a critical speed with amplification factor `af`
// needs from the operating range (API 617 7th ed. 2.6.2.10, API RP 684 SP6.8.2.10):
// none below AF 2.5 (critically damped); below the range min(17 (1 - 1/(AF - 1.5)), 16),
// above it min(10 + 17 (1 - 1/(AF - 1.5)), 26). The margin is taken from the
// minimum operating speed below and from the maximum continuous speed above.
double api684_required_margin(double af, bool above);

// Amplification factors of critical speeds (API 684, section 2.8): the half-power
// method on the unbalance response, AF = N_peak / (N_2 - N_1) with N_1, N_2 the
// speeds where the amplitude of the probe DOF (the mode's largest translation)
// is 0.707 of its peak; used for 1x crossings of a model with an unbalance whose
// probe shows a peak within 3 damping widths of the crossing and both half-power
// points within the search; where the largest translation shows none, its whirl
// partner at the same node (y for x) is tried. Otherwise (other harmonics, no
// unbalance, no peak, models above kHalfPowerDofs DOFs) AF = 1/(2 zeta) from the
// mode's damping ratio (infinite for an undamped or unstable mode), and
// amplification_note says why.
// `only`: the index of the one crossing to set (the others' speeds still bound its
// half-power search); npos: every crossing.
void set_amplification_factors(std::vector<CriticalSpeed>& cs, const GyroscopicSystem& sys,
                               std::size_t only = static_cast<std::size_t>(-1));

// Crossings of every oscillating branch with the lines k w, k in `harmonics`,
// refined with GSL Brent on f(w) = Im lambda(w) - k w.
std::vector<CriticalSpeed> critical_speeds(const GyroscopicSystem& sys, const CampbellDiagram& cd,
                                           const std::vector<int>& harmonics, const EigenOptions& eig = {});
// The same with any solver (the one the diagram was made with); the root
// searches run on `threads` workers (run_on_workers).
std::vector<CriticalSpeed> critical_speeds(const SolverFactory& solver, const CampbellDiagram& cd,
                                           const std::vector<int>& harmonics, Workers workers = {});

// For undamped systems without circulatory terms, lambda = i k w is an
// eigenvalue exactly at a critical speed, so w^2 solves the linear Hermitian
// pencil K x = w^2 (k^2 M - i k G - K2) x. Throws InputError for damped systems.
std::vector<CriticalSpeed> critical_speeds_direct(const GyroscopicSystem& sys, int harmonic, double from,
                                                  double to);

struct StabilityChange {
    double speed = 0;
    // rad/s: |speed - exact threshold| <= bound, to first order: the real part's
    // error bound over its slope (docs/numerics.md); infinite where unknown.
    double bound = 0;
    int branch = 0;
    bool becomes_unstable = true;   // with increasing speed
    Mode mode;
};

// Speeds where a branch becomes unstable or stable again. A mode is unstable
// only where Re lambda exceeds its error bound (Mode::stability); neutral modes
// (undamped, conservative) never count. Where both ends are decided the root of
// Re lambda is refined by Brent; next to a neutral end, the edge of the unstable
// range by bisection (relative width 1e-12). Each change carries its bound. A
// solver of a window of modes refines on a window centred on the mode.
std::vector<StabilityChange> stability_changes(const GyroscopicSystem& sys, const CampbellDiagram& cd,
                                               const EigenOptions& eig = {});
std::vector<StabilityChange> stability_changes(const SolverFactory& solver, const CampbellDiagram& cd,
                                               Workers workers = {});

// Grid ranges of the diagram where a branch is unstable (oscillating, or a real
// eigenvalue beyond its bound: divergence): what the Campbell diagram and the
// response warn about.
struct UnstableRange {
    int branch = 0;
    double from = 0, to = 0;   // first and last unstable grid speed (refined: the edges)
    double max_real = 0;       // largest Re lambda at the grid speeds
    size_t first_index = 0, last_index = 0;
    bool to_last = false;      // the range runs to the branch's last speed
    // Refined edges (refine_edges): the stability change inside the grid step before
    // (after) the range, with its bound; a range that starts at the first speed or ends
    // at the last has that speed as its edge, and one whose change was not refined (a
    // real eigenvalue's end) keeps its grid speed.
    bool from_refined = false, to_refined = false;
    double from_bound = 0, to_bound = 0;
};
// Of the reported branches, and with `every_mode` of the untracked ones too.
std::vector<UnstableRange> unstable_ranges(const CampbellDiagram& cd, bool every_mode = false);
// The ranges with their edges moved to the refined stability changes of their branch
// (stability_changes of the same diagram): one onset wherever an instability is named.
std::vector<UnstableRange> refine_edges(std::vector<UnstableRange> ranges, const CampbellDiagram& cd,
                                        const std::vector<StabilityChange>& changes);

}  // namespace gyrokit
