#include <gyrokit/core/dof_layout.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <fmt/format.h>

namespace gyrokit {

int DofLayout::find(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

int DofLayout::find(int node, DofMotion motion, bool on_pedestal_) const {
    // Only where the layout knows motions and places (each list empty or one entry per DOF).
    if (motions.size() != names.size() || (on_pedestal_ ? pedestal_nodes.size() : nodes.size()) != names.size())
        return -1;
    for (int i = 0; i < size(); ++i) {
        const bool here = on_pedestal_ ? pedestal_node(i) == node : nodes[static_cast<std::size_t>(i)] == node;
        if (here && motions[static_cast<std::size_t>(i)] == motion) return i;
    }
    return -1;
}

void DofLayout::add(std::string name, int node, DofMotion motion, int pedestal_node_) {
    const bool rotation = motion == DofMotion::rot_x || motion == DofMotion::rot_y || motion == DofMotion::rot_z;
    names.push_back(std::move(name));
    units.push_back(rotation ? "rad" : "m");
    nodes.push_back(node);
    motions.push_back(motion);
    pedestal_nodes.push_back(pedestal_node_);
}

void DofLayout::check(int n, int node_count, const std::string& origin) const {
    if (size() != n) throw InputError(fmt::format("{}: {} DOF names for {} DOFs", origin, names.size(), n));
    const auto sized = [&](std::size_t count, const char* what) {
        if (count != 0 && static_cast<int>(count) != n)
            throw InputError(fmt::format("{}: {} DOF {} for {} DOFs", origin, count, what, n));
    };
    sized(units.size(), "units");
    sized(nodes.size(), "nodes");
    sized(motions.size(), "motions");
    sized(pedestal_nodes.size(), "pedestal nodes");
    for (const auto* list : {&nodes, &pedestal_nodes})
        for (const int k : *list)
            if (k < -1 || k >= node_count)
                throw InputError(node_count == 0 ? fmt::format("{}: DOF node {} of a model without nodes; allowed: -1 "
                                                               "(none)",
                                                               origin, k)
                                                 : fmt::format("{}: DOF node {} is out of range; allowed: -1 (none) or "
                                                               "a node in [0, {}]",
                                                               origin, k, node_count - 1));
}

}  // namespace gyrokit
