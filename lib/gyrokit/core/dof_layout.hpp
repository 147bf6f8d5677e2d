#pragma once
// What each DOF of a model is: its name, unit, node on the shaft's axis, and the motion it
// measures. Code that asks what a DOF is asks the layout, never the spelling of its name.

#include <string>
#include <vector>

namespace gyrokit {

// The motion a DOF measures: a translation along, or a rotation about, an axis (z: the
// shaft's axis, y: vertical, gravity along -y).
enum class DofMotion { x, y, z, rot_x, rot_y, rot_z };

struct DofLayout {
    std::vector<std::string> names;   // one per DOF: "x3", "ty3", "px2" (FE rotors), or as the model names them
    // Optional (empty: not known), else one entry per DOF:
    std::vector<std::string> units;   // "m", "rad", ...
    std::vector<int> nodes;           // node on the shaft's axis, -1: none (a pedestal's, a fluid's)
    std::vector<DofMotion> motions;   // the motion each DOF measures
    std::vector<int> pedestal_nodes;  // the node whose pedestal mass the DOF moves, -1: the shaft's own DOF

    int size() const { return static_cast<int>(names.size()); }
    // The DOF of that name, -1 if none.
    int find(const std::string& name) const;
    // The shaft's DOF at `node` measuring `motion` (or, with on_pedestal, that of the pedestal
    // under the node); -1 if none (held by a support, or not in the model's motion).
    int find(int node, DofMotion motion, bool on_pedestal = false) const;
    std::string unit(int i) const { return units.empty() ? std::string() : units[static_cast<std::size_t>(i)]; }
    int pedestal_node(int i) const { return pedestal_nodes.empty() ? -1 : pedestal_nodes[static_cast<std::size_t>(i)]; }
    bool on_pedestal(int i) const { return pedestal_node(i) >= 0; }
    // A translation along y (the vertical: gravity lifts it), the shaft's or a pedestal's.
    bool vertical_translation(int i) const { return motion_is(i, DofMotion::y); }
    // Motion in the vertical plane: a y translation or a rotation about x.
    bool in_vertical_plane(int i) const { return motion_is(i, DofMotion::y) || motion_is(i, DofMotion::rot_x); }
    // Appends one DOF of an FE rotor: its unit follows from the motion (m or rad).
    // A pedestal's DOF has node -1 (off the axis) and the node it stands under as pedestal_node.
    void add(std::string name, int node, DofMotion motion, int pedestal_node = -1);
    // InputError (naming `origin`) unless every list is empty or has n entries, and nodes lie in [-1, node_count).
    void check(int n, int node_count, const std::string& origin) const;

private:
    bool motion_is(int i, DofMotion m) const {
        return !motions.empty() && motions[static_cast<std::size_t>(i)] == m;
    }
};

}  // namespace gyrokit
