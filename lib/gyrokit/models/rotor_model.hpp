// An FE rotor as an engineer describes it: shaft sections along the axis, and disks,
// bearings of every kind, rigid supports and pedestals at axial positions z. build()
// meshes it into an FeRotor (elements and nodes), assembles it and attaches the
// speed-dependent bearings (tables and fluid films, load = "auto" from the rotor's
// weight). Scene files map their [model] keys to this value (scene/scene.hpp) and
// write_scene writes it back; C++ and Python build it directly.
//
// Every value in SI units (m, kg, N, Pa, rad/s). `length_unit` only says how messages
// print lengths (a scene in mm reports its positions in mm).
#pragma once

#include <gyrokit/core/bearing_table.hpp>
#include <gyrokit/core/gyroscopic_system.hpp>
#include <gyrokit/models/fe_rotor.hpp>
#include <gyrokit/models/journal_bearing.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace gyrokit {

// One shaft section: `elements` equal elements of `shape` (its length is the section's;
// a tapered section's diameters vary linearly from its start to its end), or a
// flexible coupling (shape.coupling set: one element of that length).
struct RotorSection {
    FeShaftElement shape;
    int elements = 1;       // >= 1; a coupling: 1
    std::string origin;     // names the section in messages (a scene: "file: [model.shaft[2]]")
};

// The hollow cylinder a disk is made of: its mass and inertias follow (disk_inertia).
struct DiskGeometry {
    double outer_diameter = 0.0;   // m, > 0
    double inner_diameter = 0.0;   // m, in [0, outer_diameter)
    double width = 0.0;            // m, > 0
    double density = 0.0;          // kg/m^3, > 0
};

struct RotorDisk {
    double z = 0.0;                        // m, at a node
    FeDisk disk;                           // mass, Id, Ip (unless geometry), unbalance; its node is found from z
    std::optional<DiskGeometry> geometry;  // set: mass, Id and Ip from it
    std::string origin;
};

// A bearing at z: constant coefficients, a coefficient table or a fluid-film journal
// bearing from its geometry.
struct RotorBearing {
    enum class Kind { constant, table, fluid_film };
    Kind kind = Kind::constant;
    double z = 0.0;
    FeBearing constant;                    // Kind::constant (its node is found from z)
    BearingTable table;                    // Kind::table: speeds and rows (its DOFs are found when built)
    std::string table_file;                // Kind::table read from this CSV file: the table's name, and
                                           // what a written scene refers to (empty: written inline)
    JournalBearing film;                   // Kind::fluid_film
    bool auto_load = false;                // fluid film: its load from the rotor's weight (film.load unused)
    std::string origin;
};

struct RotorSupport {
    double z = 0.0;
    FeSupport hold;                        // which DOFs are held (its node is found from z)
    std::string origin;
};

struct RotorPedestal {
    double z = 0.0;                        // the position of the bearings it carries
    FePedestal pedestal;
    std::string origin;
};

// Damping of the shaft's beam elements (the damping component "shaft"), in fixed axes: it
// does not turn with the shaft (no circulatory term). Proportional, alpha M_shaft +
// beta K_shaft: a mode of the shaft alone has zeta = alpha / (2 w) + beta w / 2. Modal:
// the shaft's own modes (on its supports, without disks and bearings; K_s phi = w^2 M_s phi,
// Phi^T M_s Phi = I) each with its ratio, M_s Phi diag(2 zeta_i w_i) Phi^T M_s: a mode of
// the shaft alone has exactly zeta_i (the ratios of the lowest modes in order, the last
// one for every mode above; rigid-body modes, w = 0, none). Both may be given: they add.
struct ShaftDamping {
    double alpha = 0.0;          // 1/s, >= 0
    double beta = 0.0;           // s, >= 0
    std::vector<double> modal;   // zeta_1, zeta_2, ..., each in [0, 1); empty: none
};

// Modal damping is formed dense: up to this many DOFs.
constexpr int kModalDampingMaxDofs = 3000;

struct RotorModel {
    std::vector<RotorSection> sections;    // from z = 0 along +z, one chain
    std::vector<RotorDisk> disks;
    std::vector<RotorBearing> bearings;
    std::vector<RotorSupport> supports;
    std::vector<RotorPedestal> pedestals;  // at most one per bearing position
    bool shear_deformation = true;
    bool rotary_inertia = true;
    FeMotion motion = FeMotion::lateral;
    ShaftDamping shaft_damping;
    std::string length_unit = "m";         // "m" or "mm": how messages print lengths
};

// The bearings' numbers, 1 to n in the model's list (what every table names them by,
// "bearing N"), in the order the build keeps them: the constant ones
// (FeRotor::bearings), then the speed-dependent ones (GyroscopicSystem::bearings).
struct BearingNumbers {
    std::vector<int> constant, speed_dependent;
};
BearingNumbers bearing_numbers(const RotorModel& model);
std::string bearing_name(int number);

struct BuiltRotor {
    FeRotor rotor;                 // the mesh: elements, and every item at its node
    std::vector<double> node_z;    // m, z_0 = 0
    GyroscopicSystem system;       // assembled, speed-dependent bearings attached
};

// Meshes, validates and assembles. InputError names the item (its origin, or
// "section 2", "bearing 1", ... when it has none), the value and the allowed range:
// a position that is not a node, a pedestal without a bearing, a journal lifted off
// by the rotor's weight, a bearing on held DOFs, and whatever FeRotor::validate refuses.
BuiltRotor build(const RotorModel& model);

// The bearing span (m): the axial positions of the outermost bearings and rigid
// supports. InputError naming `path` if the rotor has neither.
std::pair<double, double> bearing_span(const RotorModel& model, const std::string& path);

// The rotor with its bearings at one end of their tolerance bands (every fluid film at
// film_extreme), as API 617 screens Level I: "minimum clearance" and "maximum clearance".
struct BearingSet {
    std::string name;
    RotorModel model;
};

// Both ends where a fluid film gives a clearance or viscosity band; empty where none does
// (the bearings as given are the only set). Other bearings keep their coefficients.
std::vector<BearingSet> bearing_extremes(const RotorModel& model);

}  // namespace gyrokit
