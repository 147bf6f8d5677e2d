// Design studies: a sweep file names a base scene, the parameters to vary
// (grid or Latin hypercube), the operating speed range and the criteria each
// design must meet. See docs/screening.md for the file format.
#pragma once

#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/scene/scene.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// One varied scene value: a path such as "model.c_G", "model.bearing[0].kxx" or
// "model.shaft[*].outer_diameter" (every entry), or a name with several tied
// `paths` that take the same value.
struct SweepParameter {
    std::string name;
    double from = 0, to = 0;       // range (grid with count, or Latin hypercube)
    int count = 0;                 // grid points (grid with from/to)
    std::vector<double> values;    // explicit grid values (instead of from/to/count)
    bool log_scale = false;        // points equally spaced in log(value)
    std::vector<std::string> paths;   // tied paths, one value; empty: `name` is the path
};

// List: the designs are given one by one (`Sweep::designs`), e.g. from a script.
enum class Sampling { Grid, LatinHypercube, List };

// Critical speeds must keep `margin_percent` (API 684 style) from the operating
// range: below it SM = 100 (from - w_c)/from, above it SM = 100 (w_c - to)/to,
// inside it SM < 0.
struct SeparationCriterion {
    double margin_percent = 15.0;
    bool forward_only = false;       // count forward-whirl crossings only
    std::vector<int> harmonics;      // lines k w (default: the scene's)
    int count = 121;                 // Campbell grid from 0 to to (1 + margin) * 1.05
    // rule "api684": each critical speed's margin from its amplification factor
    // (api684_required_margin; none below AF 2.5) instead of margin_percent.
    bool api684 = false;
    // A limit on the amplification factor of every critical speed of the scan (a run-up
    // passes through those below the range too); none: the factors only rule the margins.
    std::optional<double> max_amplification;
    // Crossings that `critical` calls heavily damped (AF < 2.5, not critical by API 684)
    // need no margin unless the sweep asks for them (heavily_damped = "count").
    bool count_heavily_damped = false;
};

// No mode with Re(lambda) > 0 from speed 0 up to `up_to`; with `min_log_dec`, also
// no oscillating mode whose logarithmic decrement -2 pi Re(lambda)/Im(lambda) lies
// below it (API 684 stability margin) at the speeds scanned.
struct StabilityCriterion {
    double up_to = 0;                // rad/s
    int count = 121;
    std::optional<double> min_log_dec;   // > 0; unset: only instability fails
};

// The named damping sets pervade at every operating speed.
struct PervasiveCriterion {
    std::vector<std::string> damping{"total"};
    double tolerance = 1e-8;
};

// A named probe of the response criterion: the displacement along `angle_degrees`
// (from +x towards +y) of two DOFs named in the scene, or of a node's x and y
// (probe_at_node), found in each design's model.
struct ResponseProbe {
    std::string name;
    std::string dof_x, dof_y;        // DOF names; empty with `node`
    int node = -1;                   // a node of a model with nodes (fe_rotor); -1: by DOF names
    double angle_degrees = 0;
};

// Largest unbalance response amplitude over the operating range: of the DOFs, or
// read by the probes (either, not both).
struct ResponseCriterion {
    double max_amplitude = 0;        // in the units of the DOFs (m or rad)
    std::vector<std::string> dofs;   // empty: all DOFs (without probes)
    std::vector<ResponseProbe> probes;
};

struct Criteria {
    std::optional<SeparationCriterion> separation;
    std::optional<StabilityCriterion> stability;
    std::optional<PervasiveCriterion> pervasive;
    std::optional<ResponseCriterion> response;
    // A balancer limit-speed criterion belongs here once scenes have balancer
    // models; the reader rejects [criteria.balancer] until then.
};

// Builds the scene of one design from the parameter overrides.
using SceneLoader = std::function<Scene(const std::map<std::string, double>&)>;

struct Sweep {
    std::string path;                 // the sweep file
    std::string title;
    std::string scene;                // base scene path (resolved against the sweep's folder), or the name of scene_text
    std::string scene_text;           // the base scene as TOML when given in code (empty: the file `scene`)
    std::vector<SweepParameter> parameters;
    Sampling sampling = Sampling::Grid;
    long long samples = 0;            // Latin hypercube
    std::uint64_t seed = 1;
    SpeedUnit unit;                   // unit of the speeds in the file and in the output
    double op_from = 0, op_to = 0;    // operating range, rad/s
    int op_count = 41;                // operating speeds checked (pervasive, response)
    Criteria criteria;
    std::vector<std::string> plot_axes;   // two parameter names (default: the first two)
    DofLayout dofs;                   // of the base scene
    SceneLoader loader;               // default: load_scene(scene, overrides)
    std::vector<double> lhs;          // Latin hypercube points, samples x parameters
    std::vector<std::vector<double>> designs;   // List: each design's values, in the order of `parameters`

    // Number of designs: product of grid counts, `samples`, or the listed designs.
    std::size_t design_count() const;
    // Parameter values of design i (0-based), in the order of `parameters`.
    std::vector<double> design(std::size_t i) const;
    std::vector<double> operating_speeds() const;
};

// Reads and validates a sweep file. Every error is a one-line InputError naming
// the file and the key: unknown parameters, empty ranges, criteria that the
// scene cannot evaluate (no unbalance, no damping, no balancer model).
// `scene_text` (a scene written by scene_text(), named `scene_name` in messages), if
// given, is the base scene in place of the file's `scene` key (which may then be left out).
Sweep read_sweep(const std::string& path, const std::string& scene_text = "", const std::string& scene_name = "");

// The scene overrides of one design: each parameter's value at each of its paths.
std::map<std::string, double> design_overrides(const Sweep& s, const std::vector<double>& values);

// Checks a sweep assembled in code (parameters, ranges, criteria, loader set)
// and fills `lhs`; read_sweep calls it too.
// `check_parameters` false: the parameters were checked on the whole study
// already (one design of it evaluated apart, e.g. by a Python executor).
void finalize_sweep(Sweep& s, bool check_parameters = true);

// Latin hypercube on [0, 1)^d: n points, each coordinate's n strata hit once.
// Uses std::mt19937_64 with its own mappings to integers and reals, so the
// points are the same on every platform. Row-major, n x d.
std::vector<double> latin_hypercube(std::size_t n, std::size_t d, std::uint64_t seed);

// Shard K of N (0 <= K < N) owns the designs i with i mod N == K.
struct Shard {
    int index = 0, count = 1;
    bool owns(std::size_t i) const { return static_cast<int>(i % static_cast<std::size_t>(count)) == index; }
    static Shard parse(const std::string& text);   // "K/N"; throws InputError
};

}  // namespace gyrokit
