// Mesh convergence of an FE rotor scene (gyrokit mesh, gyrokit.mesh_convergence;
// docs/mesh_convergence.md): the scene's rotor meshed with each section's element count
// times 1, 2, 4, ... ; at each mesh the critical speeds (the 1x crossings over the
// scene's speeds) and the damped natural frequencies at the top speed up to f_cut;
// each quantity's change on doubling; and the mesh chosen: the coarsest from which every
// quantity changes by less than the tolerance on each further doubling.
#pragma once

#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/core/speed_range.hpp>
#include <gyrokit/scene/scene.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

// Unless asked otherwise: a change below 0.1 % on doubling; at most 4 meshes (x1 to x8),
// none above 6000 DOFs.
constexpr double kMeshTolerance = 1e-3;
constexpr int kMeshLevels = 4;
constexpr int kMeshMaxDofs = 6000;

struct MeshConvergenceRequest {
    std::optional<std::string> unit;   // rad/s, Hz or rpm: of the speeds in and out
    std::optional<double> tolerance;   // relative change on doubling, in (0, 0.5)
    std::optional<int> levels;         // meshes, x1 to x2^(levels - 1), in [2, 8]
};

struct MeshLevel {
    int factor = 1;                    // each section's elements times this
    int elements = 0;                  // shaft elements in all
    int dofs = 0;
    std::vector<double> critical;      // rad/s: the 1x crossings, ascending
    std::vector<double> frequencies;   // rad/s: at the top speed, up to f_cut, ascending
};

// One quantity across the meshes: critical speed k or frequency k (by order), of those
// every mesh has.
struct MeshQuantity {
    std::string name;                  // "critical speed 1", "frequency 3 at 15000 rpm"
    std::vector<double> values;        // rad/s, one per level
    std::vector<double> change;        // |v(l + 1) - v(l)| / v(l + 1), one per doubling; NaN where unknown
    int converged = -1;                // the coarsest level from which every change is below the tolerance; -1: none
};

struct MeshConvergenceStudy {
    SpeedUnit unit;
    double tolerance = kMeshTolerance;
    double top_speed = 0.0;            // rad/s: where the frequencies are taken
    std::vector<MeshLevel> levels;
    std::vector<MeshQuantity> quantities;
    int chosen = -1;                   // the level chosen (every quantity converged from it); -1: none
    std::vector<int> section_elements; // of the chosen level (or the finest where none)
    Diagnostics diagnostics;
};

// InputError for a scene without an FE rotor or [speeds], and for a value out of range.
MeshConvergenceStudy mesh_convergence_study(const Scene& scene, const MeshConvergenceRequest& request = {});

}  // namespace gyrokit
