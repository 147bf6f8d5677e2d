#include <gyrokit/study/defaults.hpp>

#include <fmt/format.h>

namespace gyrokit::defaults {

const std::vector<Entry>& table() {
    // Values as a front end writes them ({} gives the shortest text that reads back
    // to the same double).
    static const std::vector<Entry> rows = {
        {"modes", "",
         fmt::format("the modes in range: every mode up to f_cut is tracked and judged; a count K shows the K lowest "
                     "branches (critical speeds and verdicts still cover every mode up to f_cut); 0: every mode "
                     "(sparse: a window of {}); at one speed (eig, modes), where no range defines the modes in "
                     "range, every mode (sparse: {})",
                     sparse_modes, sparse_modes),
         "--modes", "modes", "", ""},
        {"f_cut", "",
         fmt::format("{} times the highest excitation frequency (the highest harmonic times the top speed)",
                     f_cut_margin),
         "--f-cut", "f_cut", "", ""},
        {"harmonics", fmt::format("{}", harmonic),
         "the excitation lines k x speed (the scene's [analysis] harmonics first)", "", "", "", ""},
        {"speeds", "", "the scene's [speeds] (required where a command sweeps speeds)", "--speeds", "speeds", "", ""},
        {"units", "",
         fmt::format("speeds and frequencies given and printed (rad/s, Hz or rpm): the scene's [speeds] units, else {}",
                     unit),
         "--units", "unit", "", ""},
        {"method", method, "the dense eigensolver: qz (scaled QZ), qz-classic or state (M^-1 state matrix)",
         "--method", "method", "", ""},
        {"solver", solver,
         fmt::format("dense up to {} DOFs ({} for the modes in range), sparse above; the scene's [analysis] solver "
                     "first",
                     kAutoSparseDofs, kAutoDenseInRangeDofs),
         "", "", "", ""},
        {"lanczos", fmt::format("{}", lanczos), "Arnoldi vectors of the sparse solver: 0 = automatic", "--lanczos",
         "lanczos", "", ""},
        {"jobs", fmt::format("{}", jobs),
         "workers: the threads of a sweep over speeds, the designs of a screening run in parallel; 0 = every core",
         "--jobs", "jobs", "", ""},
        {"tolerance", fmt::format("{}", pervasive_tolerance), "pervasive: the largest residual of a damping loss",
         "--tolerance", "tolerance", "pervasive", "pervasive"},
        {"map modes", fmt::format("{}", critical_map_modes),
         "critical-map: the lowest critical speeds of each whirl at each stiffness", "--modes", "modes",
         "critical-map", "critical_speed_map"},
        {"stiffness", "",
         fmt::format("critical-map: {} values, log spaced, from {} to {} times the shaft's 48 E I / L^3",
                     critical_map_points, critical_map_stiffness_from, critical_map_stiffness_to),
         "--stiffness", "stiffness", "critical-map", "critical_speed_map"},
        {"intervals", fmt::format("{}", level1_intervals), "level1: equal steps of the log decrement's curve over Q",
         "--intervals", "intervals", "level1", "level1"},
        {"q ratio", "",
         fmt::format("level1: the curve's range in multiples of QA: the scene's [api] q_ratio, else {}",
                     level1_q_ratio),
         "--q-ratio",
         "q_ratio", "level1", "level1"},
        {"gravity", fmt::format("{}", gravity), "static: gravity along -y in m/s^2 (0: no weight)", "--gravity",
         "gravity", "static", "static"},
        {"max steps", fmt::format("{}", max_steps), "transient: the largest number of time steps of a run",
         "--max-steps", "max_steps", "transient", "transient"},
        {"start", transient_start, "transient: the initial state (rest, or steady: the steady response at the first "
         "speed)", "--start", "start", "transient", "transient"},
    };
    return rows;
}

}  // namespace gyrokit::defaults
