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
        {"method", method,
         fmt::format("the dense eigensolver: auto (the state matrix from {} DOFs, kept where every pair is verified "
                     "and bounded to 1e-6 of its modulus, else scaled QZ, as on uncoupled DOF groups), qz (scaled QZ), qz-classic or state (M^-1 "
                     "state matrix)",
                     kAutoStateDofs),
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
        {"api speeds", fmt::format("{}", api_speeds),
         fmt::format("api-unbalance: grid speeds from 0 to the higher of {} x the trip speed and {} x the mcs "
                     "(peaks are refined between them)",
                     kApiTripReach, kApiMarginReach),
         "--speeds", "speeds", "api-unbalance", "api_unbalance"},
        {"trip speed", "",
         fmt::format("api-unbalance: the scene's [api] trip_speed, else {} x the mcs", api_trip_ratio),
         "--trip-speed", "trip_speed", "api-unbalance", "api_unbalance"},
        {"min speed", "", "api-unbalance: the scene's [api] min_speed, else the mcs (the operating range is one speed)",
         "--min-speed", "min_speed", "api-unbalance", "api_unbalance"},
        {"mesh tolerance", fmt::format("{}", mesh_tolerance),
         "mesh: the largest relative change on doubling of each critical speed and frequency in range (0.001: 0.1 %)",
         "--tolerance", "tolerance", "mesh", "mesh_convergence"},
        {"mesh levels", fmt::format("{}", mesh_levels), "mesh: the meshes at most, x1 to x2^(levels - 1)", "--levels",
         "levels", "mesh", "mesh_convergence"},
        {"mode shapes", fmt::format("{}", report_mode_shapes),
         "report: the critical speeds (lowest first) whose mode shapes are drawn", "--mode-shapes", "mode_shapes",
         "report", "report"},
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
