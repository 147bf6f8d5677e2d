// The DOF layout: what each DOF of an FE rotor is, read from the layout and checked against
// the spelling of its name (the one place names and layout must agree).
#include <gyrokit/core/dof_layout.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/scene/scene.hpp>

#include <catch2/catch.hpp>
#include <string>

using namespace gyrokit;

namespace {

std::string data(const std::string& name) { return std::string(GYROKIT_DATA_DIR) + "/" + name; }

const char* spelling(DofMotion m) {
    switch (m) {
        case DofMotion::x: return "x";
        case DofMotion::y: return "y";
        case DofMotion::z: return "z";
        case DofMotion::rot_x: return "tx";
        case DofMotion::rot_y: return "ty";
        case DofMotion::rot_z: return "tz";
    }
    return "?";
}

}  // namespace

TEST_CASE("dof layout: every DOF of a 6-DOF rotor with a pedestal is what its name says", "[dof_layout]") {
    const Scene s = load_scene(data("drive_train.toml"));
    const DofLayout& d = s.system.dofs;
    REQUIRE(d.size() == s.system.size());
    REQUIRE(d.motions.size() == d.names.size());
    int pedestal = 0, vertical_plane = 0, lifted = 0;
    for (int i = 0; i < d.size(); ++i) {
        INFO(d.names[static_cast<std::size_t>(i)]);
        const DofMotion m = d.motions[static_cast<std::size_t>(i)];
        const bool rotation = m == DofMotion::rot_x || m == DofMotion::rot_y || m == DofMotion::rot_z;
        CHECK(d.unit(i) == (rotation ? "rad" : "m"));
        if (d.on_pedestal(i)) {
            ++pedestal;
            CHECK(d.nodes[static_cast<std::size_t>(i)] == -1);
            CHECK(d.names[static_cast<std::size_t>(i)] ==
                  std::string("p") + spelling(m) + std::to_string(d.pedestal_node(i)));
            CHECK(d.find(d.pedestal_node(i), m, true) == i);
        } else {
            const int node = d.nodes[static_cast<std::size_t>(i)];
            CHECK(d.names[static_cast<std::size_t>(i)] == spelling(m) + std::to_string(node));
            CHECK(d.find(node, m) == i);
        }
        CHECK(d.find(d.names[static_cast<std::size_t>(i)]) == i);
        vertical_plane += d.in_vertical_plane(i);
        lifted += d.vertical_translation(i);
    }
    CHECK(pedestal == 2);   // px0, py0
    // y and tx of every free node, and py0.
    int y = 0, tx = 0;
    for (const std::string& n : d.names) {
        y += n[0] == 'y' || n.rfind("py", 0) == 0;
        tx += n.rfind("tx", 0) == 0;
    }
    CHECK(lifted == y);
    CHECK(vertical_plane == y + tx);
    CHECK(d.find(0, DofMotion::x, true) >= 0);
    CHECK(d.find(static_cast<int>(s.system.node_z.size()), DofMotion::x) == -1);   // past the last node
    CHECK(d.find("nope") == -1);
}

TEST_CASE("dof layout: lists of the wrong length or nodes off the rotor are refused", "[dof_layout][errors]") {
    DofLayout d;
    d.add("x0", 0, DofMotion::x);
    d.add("y0", 0, DofMotion::y);
    CHECK_NOTHROW(d.check(2, 1, "model"));
    CHECK_THROWS_WITH(d.check(3, 1, "model"), "model: 2 DOF names for 3 DOFs");
    DofLayout short_units = d;
    short_units.units.pop_back();
    CHECK_THROWS_WITH(short_units.check(2, 1, "model"), "model: 1 DOF units for 2 DOFs");
    CHECK_THROWS_WITH(d.check(2, 0, "model"), "model: DOF node 0 of a model without nodes; allowed: -1 (none)");
    d.nodes[1] = 3;
    CHECK_THROWS_WITH(d.check(2, 2, "model"), "model: DOF node 3 is out of range; allowed: -1 (none) or a node in [0, 1]");
    DofLayout names_only;
    names_only.names = {"a", "b"};
    CHECK_NOTHROW(names_only.check(2, 0, "model"));
    CHECK(names_only.unit(1).empty());
    CHECK_FALSE(names_only.on_pedestal(0));
    CHECK_FALSE(names_only.vertical_translation(0));
    CHECK(names_only.find(0, DofMotion::x) == -1);
}
