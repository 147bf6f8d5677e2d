#include <gyrokit/models/rotor_model.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/length_unit.hpp>
#include <gyrokit/models/gravity_loads.hpp>
#include <gyrokit/models/materials.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

// An item's name in messages: its origin, or "<kind> <number>" (from 1, as the tables
// number them) for a model built in code.
std::string origin_of(const std::string& origin, const char* kind, std::size_t i) {
    return origin.empty() ? fmt::format("{} {}", kind, i + 1) : origin;
}

}  // namespace

BearingNumbers bearing_numbers(const RotorModel& model) {
    BearingNumbers n;
    for (std::size_t i = 0; i < model.bearings.size(); ++i)
        (model.bearings[i].kind == RotorBearing::Kind::constant ? n.constant : n.speed_dependent)
            .push_back(static_cast<int>(i) + 1);
    return n;
}

std::string bearing_name(int number) { return fmt::format("bearing {}", number); }

namespace {

// How messages print lengths: the model's length_unit.
LengthUnit unit_of(const RotorModel& m) { return LengthUnit::parse(m.length_unit); }

int node_at(const std::vector<double>& nodes, double z, const std::string& where, const LengthUnit& unit) {
    const double L = nodes.back();
    const auto it = std::lower_bound(nodes.begin(), nodes.end(), z - 1e-9 * L);
    if (!std::isfinite(z) || it == nodes.end() || std::abs(*it - z) > 1e-9 * L) {
        double nearest = nodes.front();
        for (double x : nodes)
            if (std::abs(x - z) < std::abs(nearest - z)) nearest = x;
        throw InputError(fmt::format("{} = {} {} is not a node of the mesh; allowed: a section end or "
                                     "subdivision, the nearest is {:.12g} (rotor length {:.12g})",
                                     where, z / unit.metres, unit.name, nearest / unit.metres, L / unit.metres));
    }
    return static_cast<int>(it - nodes.begin());
}

// The sections' elements, end to end; the node positions in `z`.
void mesh_sections(const RotorModel& model, FeRotor& r, std::vector<double>& z) {
    z.assign(1, 0.0);
    std::size_t total = 0;
    for (std::size_t s = 0; s < model.sections.size(); ++s) {
        const RotorSection& sec = model.sections[s];
        validate_element(sec.shape, origin_of(sec.origin, "section", s));
        const int count = sec.shape.coupling ? 1 : sec.elements;
        if (count < 1 || count > kMaxFeElements || total + static_cast<std::size_t>(count) > kMaxFeElements)
            throw InputError(fmt::format("{} elements = {} makes {} elements in all; allowed: 1 to {} in all",
                                         origin_of(sec.origin, "section", s), sec.elements,
                                         total + static_cast<std::size_t>(std::max(count, 0)), kMaxFeElements));
        total += static_cast<std::size_t>(count);
    }
    r.elements.reserve(total);
    for (const RotorSection& sec : model.sections) {
        const int count = sec.shape.coupling ? 1 : sec.elements;
        FeShaftElement el = sec.shape;
        el.length = sec.shape.length / count;
        const bool tapered = sec.shape.outer_diameter_end || sec.shape.inner_diameter_end;
        const double o0 = sec.shape.outer_diameter, i0 = sec.shape.inner_diameter;
        const double o1 = sec.shape.outer_diameter_end.value_or(o0), i1 = sec.shape.inner_diameter_end.value_or(i0);
        for (int i = 0; i < count; ++i) {
            if (tapered) {
                // A conical section: each of its elements is a cone of the section's slope.
                const double a = static_cast<double>(i) / count, b = static_cast<double>(i + 1) / count;
                el.outer_diameter = o0 + a * (o1 - o0);
                el.inner_diameter = i0 + a * (i1 - i0);
                el.outer_diameter_end = o0 + b * (o1 - o0);
                el.inner_diameter_end = i0 + b * (i1 - i0);
            }
            r.elements.push_back(el);
            z.push_back(z.back() + el.length);
        }
    }
}

// Fluid films with load = "auto": the weight's reactions with every speed-dependent
// bearing as a rigid support (constant bearings as their springs); films at one node
// share their node's reaction equally.
void set_auto_loads(const FeRotor& r, const std::vector<const RotorBearing*>& speed_dependent,
                    const std::vector<int>& nodes, std::vector<JournalBearing>& films, const LengthUnit& unit) {
    std::vector<int> auto_nodes;
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (speed_dependent[i]->auto_load) auto_nodes.push_back(nodes[i]);
    if (auto_nodes.empty()) return;
    const std::vector<double> reactions = fe_gravity_reactions(r, nodes);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const RotorBearing& b = *speed_dependent[i];
        if (!b.auto_load) continue;
        const double share =
            reactions[i] / static_cast<double>(std::count(auto_nodes.begin(), auto_nodes.end(), nodes[i]));
        if (!(share > 0.0))
            throw InputError(fmt::format("{} load = \"auto\": the rotor's weight lifts the journal off this "
                                         "bearing (reaction {:.6g} N at node {}); allowed: a bearing that carries "
                                         "weight, or load = a number (N) with load_angle",
                                         b.origin, share, nodes[i]));
        films[i].load = share;
        films[i].validate(b.origin, unit.metres, unit.name.c_str());
    }
}

// Disks at their nodes, with mass and inertias from the geometry where it is given.
void place_disks(const RotorModel& model, const std::vector<double>& z, const LengthUnit& unit, FeRotor& r) {
    for (std::size_t i = 0; i < model.disks.size(); ++i) {
        const RotorDisk& d = model.disks[i];
        const std::string origin = origin_of(d.origin, "disk", i);
        FeDisk disk = d.disk;
        disk.node = node_at(z, d.z, origin + " z", unit);
        if (d.geometry) {
            const DiskGeometry& g = *d.geometry;
            if (!(g.outer_diameter > 0 && g.inner_diameter >= 0 && g.inner_diameter < g.outer_diameter &&
                  g.width > 0 && g.density > 0 && std::isfinite(g.outer_diameter + g.width + g.density)))
                throw InputError(fmt::format("{}: geometry outer_diameter = {}, inner_diameter = {}, width = {}, "
                                             "density = {}; allowed: 0 <= inner < outer, width > 0, density > 0",
                                             origin, g.outer_diameter, g.inner_diameter, g.width, g.density));
            const DiskInertia di = disk_inertia(g.outer_diameter, g.inner_diameter, g.width, g.density);
            disk.mass = di.mass;
            disk.diametral_inertia = di.diametral_inertia;
            disk.polar_inertia = di.polar_inertia;
        }
        r.disks.push_back(disk);
    }
}

// The speed-dependent bearings (fluid films, tables) with their nodes and films: they are
// attached to the system once the constrained DOFs are known.
struct SpeedDependentBearings {
    std::vector<const RotorBearing*> bearings;
    std::vector<int> nodes;
    std::vector<JournalBearing> films;
};

// Constant bearings go into the FE rotor; the speed-dependent ones are returned.
SpeedDependentBearings place_bearings(const RotorModel& model, const std::vector<double>& z, const LengthUnit& unit,
                                      FeRotor& r) {
    SpeedDependentBearings sd;
    for (std::size_t i = 0; i < model.bearings.size(); ++i) {
        const RotorBearing& b = model.bearings[i];
        const int node = node_at(z, b.z, origin_of(b.origin, "bearing", i) + " z", unit);
        if (b.kind == RotorBearing::Kind::constant) {
            FeBearing c = b.constant;
            for (const double v : {c.kxx, c.kxy, c.kyx, c.kyy, c.cxx, c.cxy, c.cyx, c.cyy, c.kzz, c.czz})
                if (!std::isfinite(v))
                    throw InputError(fmt::format("{}: a coefficient is {}; allowed: finite numbers (N/m, N s/m)",
                                                 origin_of(b.origin, "bearing", i), v));
            c.node = node;
            r.bearings.push_back(c);
            continue;
        }
        if (b.kind == RotorBearing::Kind::fluid_film && !b.auto_load)
            b.film.validate(origin_of(b.origin, "bearing", i), unit.metres, unit.name.c_str());
        sd.bearings.push_back(&b);
        sd.nodes.push_back(node);
        sd.films.push_back(b.film);
    }
    return sd;
}

void place_supports(const RotorModel& model, const std::vector<double>& z, const LengthUnit& unit, FeRotor& r) {
    for (std::size_t i = 0; i < model.supports.size(); ++i) {
        FeSupport s = model.supports[i].hold;
        s.node = node_at(z, model.supports[i].z, origin_of(model.supports[i].origin, "support", i) + " z", unit);
        r.supports.push_back(s);
    }
}

// Pedestals: a mass on springs to the ground under the bearings of its node (constant
// ones in r, speed-dependent ones at sd_nodes), one per node.
void place_pedestals(const RotorModel& model, const std::vector<double>& z, const LengthUnit& unit,
                     const std::vector<int>& sd_nodes, FeRotor& r) {
    for (std::size_t i = 0; i < model.pedestals.size(); ++i) {
        const std::string where = origin_of(model.pedestals[i].origin, "pedestal", i) + " z";
        FePedestal p = model.pedestals[i].pedestal;
        p.node = node_at(z, model.pedestals[i].z, where, unit);
        const bool carries = std::any_of(r.bearings.begin(), r.bearings.end(),
                                         [&](const FeBearing& b) { return b.node == p.node; }) ||
                             std::count(sd_nodes.begin(), sd_nodes.end(), p.node) > 0;
        if (!carries)
            throw InputError(fmt::format("{} is at node {}, where no bearing stands; allowed: the z of a bearing "
                                         "(a pedestal carries the bearings at its node)",
                                         where, p.node));
        for (const FePedestal& q : r.pedestals)
            if (q.node == p.node)
                throw InputError(fmt::format("{}: a second pedestal at node {}; allowed: one pedestal per bearing "
                                             "position",
                                             where, p.node));
        r.pedestals.push_back(p);
    }
}

// The speed-dependent bearings as the system's bearing tables, on the DOFs the assembly
// numbered (m.dofs.names), between shaft and pedestal where one stands.
void attach_speed_dependent(const FeRotor& r, const FeRotorMatrices& m, const SpeedDependentBearings& sd,
                            GyroscopicSystem& sys) {
    for (std::size_t i = 0; i < sd.bearings.size(); ++i) {
        const RotorBearing& t = *sd.bearings[i];
        const int node = sd.nodes[i];
        const std::string origin = t.origin.empty() ? fmt::format("bearing at node {}", node) : t.origin;
        const bool on_pedestal =
            std::any_of(r.pedestals.begin(), r.pedestals.end(), [&](const FePedestal& p) { return p.node == node; });
        // A shaft held at a pedestal: the bearing acts between the pedestal and the held
        // shaft, i.e. from the pedestal to the ground (as a constant bearing does there).
        const bool pedestal_only =
            on_pedestal && m.dofs.find(node, DofMotion::x) < 0 && m.dofs.find(node, DofMotion::y) < 0;
        const auto dof = [&](DofMotion motion, bool pedestal) {
            const int i = m.dofs.find(node, motion, pedestal || pedestal_only);
            if (i < 0)
                throw InputError(fmt::format("{}: the bearing at node {} acts on DOF {}{}{}, which a support holds; "
                                             "allowed: a bearing at a node whose x and y are free",
                                             origin, node, pedestal || pedestal_only ? "p" : "",
                                             motion == DofMotion::x ? "x" : "y", node));
            return i;
        };
        // Named by kind and node; a second one at the same node gets a suffix (damping
        // components need unique names).
        const auto unique_name = [&](const std::string& kind) {
            std::string name = kind + "_" + std::to_string(node);
            for (int k = 2; std::any_of(sys.bearings.begin(), sys.bearings.end(),
                                        [&](const BearingTable& b) { return b.name == name; });
                 ++k)
                name = kind + "_" + std::to_string(node) + "_" + std::to_string(k);
            return name;
        };
        if (t.kind == RotorBearing::Kind::fluid_film) {
            const std::string name = unique_name("fluid_film");
            const int dx = dof(DofMotion::x, false), dy = dof(DofMotion::y, false);
            sys.bearings.push_back(journal_bearing_table(sd.films[i], name, dx, dy));
        } else {
            BearingTable b = t.table;
            b.dof_x = dof(DofMotion::x, false);
            b.dof_y = dof(DofMotion::y, false);
            b.pedestal_x = b.pedestal_y = -1;
            b.name = t.table_file.empty() ? origin : t.table_file;   // errors name the table
            b.validate(sys.size());
            if (t.table_file.empty()) b.name = unique_name("table");
            sys.bearings.push_back(b);
        }
        // On a pedestal: the bearing acts between the shaft and the pedestal.
        if (on_pedestal && !pedestal_only) {
            sys.bearings.back().pedestal_x = dof(DofMotion::x, true);
            sys.bearings.back().pedestal_y = dof(DofMotion::y, true);
        }
    }
}

// M Phi diag(2 zeta_i w_i) Phi^T M over the modes of (K, M), Phi^T M Phi = I. Eigenvalues
// w^2 within the rounding of the reduction, tau = n eps (||K|| + w^2 ||M||) / mu_min(M)
// (Golub & Van Loan 8.7), are one mode: the two planes of an axisymmetric shaft take one
// ratio, so D does not depend on the basis LAPACK picks in them. A mode with w^2 within tau
// of 0 is a rigid-body motion of the shaft and gets no damping.
Eigen::MatrixXd modal_damping(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, const std::vector<double>& zeta) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    if (es.info() != Eigen::Success)
        throw InputError("modal shaft damping: the shaft's mass matrix is not positive definite");
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> me(M, Eigen::EigenvaluesOnly);
    const double n = static_cast<double>(M.rows()), mu = me.eigenvalues().minCoeff();
    const auto tau = [&](double w2) {
        return n * std::numeric_limits<double>::epsilon() * (K.norm() + std::abs(w2) * M.norm()) / mu;
    };
    const Eigen::VectorXd& w2 = es.eigenvalues();   // ascending
    Eigen::VectorXd c = Eigen::VectorXd::Zero(w2.size());
    std::size_t mode = 0;   // flexible modes counted once per frequency
    for (Eigen::Index i = 0; i < w2.size(); ++i) {
        if (!(w2(i) > tau(0.0))) continue;
        const bool same = i > 0 && w2(i - 1) > tau(0.0) && w2(i) - w2(i - 1) <= tau(w2(i - 1)) + tau(w2(i));
        if (!same && i > 0 && w2(i - 1) > tau(0.0)) ++mode;
        c(i) = 2.0 * zeta[std::min(mode, zeta.size() - 1)] * std::sqrt(w2(i));
    }
    const Eigen::MatrixXd MPhi = M * es.eigenvectors();
    Eigen::MatrixXd D = MPhi * c.asDiagonal() * MPhi.transpose();
    return 0.5 * (D + D.transpose());   // symmetric to the last bit
}

// alpha M + beta K of the beam elements alone: the rotor without disks, bearings and
// pedestals, couplings without springs or mass, the same supports, so its DOFs are the
// node DOFs of the whole rotor in the same order (the pedestals' come after them).
Eigen::SparseMatrix<double> shaft_damping_matrix(const FeRotor& r, const ShaftDamping& d, int size) {
    using SpMatrix = Eigen::SparseMatrix<double>;
    FeRotor shaft = r;
    shaft.disks.clear();
    shaft.bearings.clear();
    shaft.pedestals.clear();
    for (FeShaftElement& e : shaft.elements)
        if (e.coupling) e.coupling = FeCoupling{};
    const FeRotorMatrices m = shaft.assemble();
    SpMatrix D(size, size);
    std::vector<Eigen::Triplet<double>> t;
    SpMatrix Ds = d.alpha * m.M + d.beta * m.K;
    if (!d.modal.empty()) Ds += to_sparse(modal_damping(Eigen::MatrixXd(m.M), Eigen::MatrixXd(m.K), d.modal));
    for (int c = 0; c < Ds.outerSize(); ++c)
        for (SpMatrix::InnerIterator it(Ds, c); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    D.setFromTriplets(t.begin(), t.end());
    return D;
}

}  // namespace

BuiltRotor build(const RotorModel& model) {
    const LengthUnit unit = unit_of(model);
    BuiltRotor out;
    FeRotor& r = out.rotor;
    r.shear_deformation = model.shear_deformation;
    r.rotary_inertia = model.rotary_inertia;
    r.motion = model.motion;
    if (model.sections.empty()) throw InputError("sections: none; required: one or more shaft sections");
    mesh_sections(model, r, out.node_z);
    const std::vector<double>& z = out.node_z;

    place_disks(model, z, unit, r);
    // Speed-dependent bearings, attached once the constrained DOFs are known.
    SpeedDependentBearings sd = place_bearings(model, z, unit, r);
    place_supports(model, z, unit, r);
    place_pedestals(model, z, unit, sd.nodes, r);

    const FeRotorMatrices m = r.assemble();
    out.system = m.to_system();
    const ShaftDamping& damping = model.shaft_damping;
    if (!(std::isfinite(damping.alpha) && damping.alpha >= 0 && std::isfinite(damping.beta) && damping.beta >= 0))
        throw InputError(fmt::format("shaft damping alpha = {}, beta = {}; allowed: finite numbers >= 0 (1/s, s)",
                                     damping.alpha, damping.beta));
    for (std::size_t i = 0; i < damping.modal.size(); ++i)
        if (!(damping.modal[i] >= 0.0 && damping.modal[i] < 1.0))
            throw InputError(fmt::format("shaft damping zeta[{}] = {}: out of range; allowed: 0 <= zeta < 1 (a "
                                         "damping ratio; steel shafts: 0.001 to 0.01)",
                                         i, damping.modal[i]));
    if (!damping.modal.empty() && m.size() > kModalDampingMaxDofs)
        throw InputError(fmt::format("shaft damping zeta: modal damping is formed dense, up to {} DOFs; this rotor has "
                                     "{} (allowed here: damping_alpha and damping_beta)",
                                     kModalDampingMaxDofs, m.size()));
    const bool modal = std::any_of(damping.modal.begin(), damping.modal.end(), [](double z) { return z > 0; });
    if (damping.alpha > 0 || damping.beta > 0 || modal)
        out.system.damping.push_back({"shaft", shaft_damping_matrix(r, damping, m.size())});
    // Speed-dependent bearings act on x and y alone: an axial or torsional model has no use for them.
    if (!r.has_lateral()) return out;
    set_auto_loads(r, sd.bearings, sd.nodes, sd.films, unit);
    attach_speed_dependent(r, m, sd, out.system);
    return out;
}

std::pair<double, double> bearing_span(const RotorModel& model, const std::string& path) {
    std::vector<double> z;
    for (const RotorBearing& b : model.bearings) z.push_back(b.z);
    for (const RotorSupport& s : model.supports) z.push_back(s.z);
    if (z.empty())
        throw InputError(path + ": the rotor has no bearing or support; the API analyses load a rotor on its "
                                "bearings");
    return {*std::min_element(z.begin(), z.end()), *std::max_element(z.begin(), z.end())};
}

std::vector<BearingSet> bearing_extremes(const RotorModel& model) {
    const bool any = std::any_of(model.bearings.begin(), model.bearings.end(), [](const RotorBearing& b) {
        return b.kind == RotorBearing::Kind::fluid_film && has_extremes(b.film);
    });
    if (!any) return {};
    std::vector<BearingSet> sets;
    for (const FilmExtreme e : {FilmExtreme::minimum_clearance, FilmExtreme::maximum_clearance}) {
        BearingSet s{to_string(e), model};
        for (RotorBearing& b : s.model.bearings)
            if (b.kind == RotorBearing::Kind::fluid_film) b.film = film_extreme(b.film, e);
        sets.push_back(std::move(s));
    }
    return sets;
}

}  // namespace gyrokit
