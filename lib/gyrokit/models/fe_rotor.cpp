#include <gyrokit/models/fe_rotor.hpp>

#include <gyrokit/core/error.hpp>

#include <Eigen/SparseLU>
#include <fmt/format.h>

#include <algorithm>

#include <cmath>
#include <tuple>

namespace gyrokit {

namespace {

// Disks, bearings, pedestals and supports numbered from 1, as the tables number them;
// elements from 0, as nodes and the static tables' element column.
std::string where(const char* kind, std::size_t index) {
    return fmt::format("fe rotor: {} {}", kind, std::string(kind) == "element" ? index : index + 1);
}

void require(bool ok, const std::string& item, const char* key, double value, const std::string& range) {
    if (!ok) throw InputError(fmt::format("{}: {} = {} is out of range; allowed: {}", item, key, value, range));
}

void require_finite(const std::string& item, const char* key, double value) {
    require(std::isfinite(value), item, key, value, "a finite number");
}

}  // namespace

void validate_element(const FeShaftElement& s, const std::string& w) {
    require(std::isfinite(s.length) && s.length > 0, w, "length", s.length, "(0, inf) m");
    if (const auto& c = s.coupling) {
        const std::pair<const char*, double> values[] = {
            {"k_lateral", c->k_lateral}, {"k_bending", c->k_bending}, {"k_axial", c->k_axial},
            {"k_torsion", c->k_torsion}, {"c_lateral", c->c_lateral}, {"c_bending", c->c_bending},
            {"c_axial", c->c_axial},     {"c_torsion", c->c_torsion}, {"mass", c->mass},
            {"Id", c->diametral_inertia}, {"Ip", c->polar_inertia}};
        for (const auto& [key, v] : values) require(std::isfinite(v) && v >= 0, w + " (coupling)", key, v, "[0, inf)");
        return;
    }
    require(std::isfinite(s.outer_diameter) && s.outer_diameter > 0, w, "outer_diameter", s.outer_diameter,
            "(0, inf) m");
    require(std::isfinite(s.inner_diameter) && s.inner_diameter >= 0 && s.inner_diameter < s.outer_diameter, w,
            "inner_diameter", s.inner_diameter, fmt::format("[0, outer_diameter = {}) m", s.outer_diameter));
    if (s.outer_diameter_end || s.inner_diameter_end) {
        const double o1 = s.outer_diameter_end.value_or(s.outer_diameter);
        const double i1 = s.inner_diameter_end.value_or(s.inner_diameter);
        require(std::isfinite(o1) && o1 > 0, w, "outer_diameter_end", o1, "(0, inf) m");
        require(std::isfinite(i1) && i1 >= 0 && i1 < o1, w, "inner_diameter_end", i1,
                fmt::format("[0, outer_diameter_end = {}) m", o1));
    }
    require(std::isfinite(s.youngs_modulus) && s.youngs_modulus > 0, w, "youngs_modulus", s.youngs_modulus,
            "(0, inf) Pa");
    require(std::isfinite(s.shear_modulus) && s.shear_modulus >= 0, w, "shear_modulus", s.shear_modulus,
            "(0, inf) Pa, or 0 to derive it from youngs_modulus and poisson_ratio");
    require(std::isfinite(s.poisson_ratio) && s.poisson_ratio > -1 && s.poisson_ratio <= 0.5, w,
            "poisson_ratio", s.poisson_ratio, "(-1, 0.5]");
    require(std::isfinite(s.density) && s.density > 0, w, "density", s.density, "(0, inf) kg/m^3");
}

void FeRotor::validate() const {
    if (elements.empty())
        throw InputError("fe rotor: elements: the shaft has no elements; allowed: at least one element");
    if (elements.size() > static_cast<std::size_t>(kMaxFeElements))
        throw InputError(fmt::format("fe rotor: elements: {} in all; allowed: at most {} (20,000,000 DOFs)",
                                     elements.size(), kMaxFeElements));
    for (std::size_t e = 0; e < elements.size(); ++e) validate_element(elements[e], where("element", e));
    require(motion == FeMotion::lateral || motion == FeMotion::all || motion == FeMotion::axial ||
                motion == FeMotion::torsional,
            "fe rotor", "motion", static_cast<int>(motion), "lateral, all, axial or torsional");
    const int nodes = node_count();
    const std::string node_range = fmt::format("an integer in [0, {}]", nodes - 1);
    for (std::size_t i = 0; i < disks.size(); ++i) {
        const FeDisk& d = disks[i];
        const std::string w = where("disk", i);
        require(d.node >= 0 && d.node < nodes, w, "node", d.node, node_range);
        require(std::isfinite(d.mass) && d.mass >= 0, w, "mass", d.mass, "[0, inf) kg");
        require(std::isfinite(d.diametral_inertia) && d.diametral_inertia >= 0, w, "diametral_inertia",
                d.diametral_inertia, "[0, inf) kg m^2");
        require(std::isfinite(d.polar_inertia) && d.polar_inertia >= 0, w, "polar_inertia", d.polar_inertia,
                "[0, inf) kg m^2");
        require(std::isfinite(d.unbalance) && d.unbalance >= 0, w, "unbalance", d.unbalance, "[0, inf) kg m");
        require_finite(w, "unbalance_phase", d.unbalance_phase);
    }
    for (std::size_t i = 0; i < bearings.size(); ++i) {
        const FeBearing& b = bearings[i];
        const std::string w = where("bearing", i);
        require(b.node >= 0 && b.node < nodes, w, "node", b.node, node_range);
        const std::pair<const char*, double> coeffs[] = {{"kxx", b.kxx}, {"kxy", b.kxy}, {"kyx", b.kyx},
                                                         {"kyy", b.kyy}, {"cxx", b.cxx}, {"cxy", b.cxy},
                                                         {"cyx", b.cyx}, {"cyy", b.cyy}};
        for (const auto& [key, v] : coeffs) require_finite(w, key, v);
        require_finite(w, "kzz", b.kzz);
        require_finite(w, "czz", b.czz);
    }
    for (std::size_t i = 0; i < pedestals.size(); ++i) {
        const FePedestal& p = pedestals[i];
        const std::string w = where("pedestal", i);
        require(p.node >= 0 && p.node < nodes, w, "node", p.node, node_range);
        require(std::isfinite(p.mass) && p.mass > 0, w, "mass", p.mass, "(0, inf) kg");
        const std::pair<const char*, double> coeffs[] = {{"kxx", p.kxx}, {"kyy", p.kyy}, {"cxx", p.cxx}, {"cyy", p.cyy}};
        for (const auto& [key, v] : coeffs) require(std::isfinite(v) && v >= 0, w, key, v, "[0, inf)");
        for (std::size_t j = 0; j < i; ++j)
            require(pedestals[j].node != p.node, w, "node", p.node,
                    fmt::format("a node without a pedestal (pedestal {} stands there)", j));
    }
    for (std::size_t i = 0; i < supports.size(); ++i) {
        const FeSupport& s = supports[i];
        require(s.node >= 0 && s.node < nodes, where("support", i), "node", s.node, node_range);
    }
}

namespace {

// Local DOF kinds of a node.
enum DofKind { X = 0, Y = 1, TX = 2, TY = 3, Z = 4, TZ = 5 };

// The numbering of the assembled DOFs: which kinds a node carries, which supports hold,
// and where the pedestal DOFs go. Apart from the stamping, so that every element, disk and
// bearing finds its rows through the one map.
struct DofNumbering {
    int slot[6] = {-1, -1, -1, -1, -1, -1};   // slot[kind]: its place within a node, -1 where the motion lacks it
    int per = 0;                              // DOFs per node
    std::vector<int> map;                     // full DOF -> assembled DOF (-1: constrained)
    std::vector<int> pedestal_of;             // assembled index of px at each node, -1: none
    int n = 0;                                // assembled DOFs

    // Assembled index of a node's DOF of a kind: -1 if held or not in the model.
    int dof(int node, int kind) const { return slot[kind] < 0 ? -1 : map[per * node + slot[kind]]; }
};

// Numbers the free DOFs node by node, then the pedestal DOFs, and names them in r.
DofNumbering number_dofs(const FeRotor& rotor, FeRotorMatrices& r) {
    const int nodes = rotor.node_count();
    DofNumbering d;
    for (int kind = 0; kind < 6; ++kind)
        if (kind < Z ? rotor.has_lateral() : kind == Z ? rotor.has_axial() : rotor.has_torsion()) d.slot[kind] = d.per++;
    const int per = d.per, full = per * nodes;

    std::vector<char> fixed(full, 0);
    for (const FeSupport& s : rotor.supports) {
        const bool held[6] = {s.x, s.y, s.theta_x, s.theta_y, s.z, s.theta_z};
        for (int kind = 0; kind < 6; ++kind)
            if (held[kind] && d.slot[kind] >= 0) fixed[per * s.node + d.slot[kind]] = 1;
    }
    d.map.assign(full, -1);
    static const char* prefix[6] = {"x", "y", "tx", "ty", "z", "tz"};
    static const DofMotion motion[6] = {DofMotion::x,     DofMotion::y, DofMotion::rot_x,
                                        DofMotion::rot_y, DofMotion::z, DofMotion::rot_z};
    int kind_of_slot[6] = {};
    for (int kind = 0; kind < 6; ++kind)
        if (d.slot[kind] >= 0) kind_of_slot[d.slot[kind]] = kind;
    int n = 0;
    for (int j = 0; j < full; ++j)
        if (!fixed[j]) {
            d.map[j] = n++;
            const int kind = kind_of_slot[j % per];
            r.dofs.add(prefix[kind] + std::to_string(j / per), j / per, motion[kind]);
        }
    // Pedestal DOFs after the node DOFs (not on the shaft's axis: node -1); lateral only.
    d.pedestal_of.assign(nodes, -1);
    if (rotor.has_lateral())
        for (const FePedestal& p : rotor.pedestals) {
            d.pedestal_of[p.node] = n;
            r.dofs.add("px" + std::to_string(p.node), -1, DofMotion::x, p.node);
            r.dofs.add("py" + std::to_string(p.node), -1, DofMotion::y, p.node);
            n += 2;
        }
    if (n == 0)
        throw InputError(fmt::format("fe rotor: supports: every DOF of the {} model is constrained; allowed: at least "
                                     "one free DOF",
                                     to_string(rotor.motion)));
    d.n = n;
    return d;
}

using Triplet = Eigen::Triplet<double>;

// The triplets of the six assembled matrices, filled by the stamp_* steps below.
struct Triplets {
    std::vector<Triplet> m, k, g, d, c, n;   // M, K, G, D (bearings), D (couplings), N
};

// Adds v at the assembled DOFs a, b (skipped where either is held or not modelled).
void add(std::vector<Triplet>& t, int a, int b, double v) {
    if (a >= 0 && b >= 0 && v != 0.0) t.emplace_back(a, b, v);
}

// The shaft elements: lateral 8x8 blocks and the axial and torsion bars.
void stamp_elements(const FeRotor& rotor, const DofNumbering& d, Triplets& t) {
    for (std::size_t e = 0; e < rotor.elements.size(); ++e) {
        const FeElementMatrices em =
            fe_shaft_element_matrices(rotor.elements[e], rotor.shear_deformation, rotor.rotary_inertia);
        const int node = static_cast<int>(e);
        // Element DOF a (0..7) is local DOF a % 4 of node e + a / 4.
        if (rotor.has_lateral())
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    const int i = d.dof(node + a / 4, a % 4), j = d.dof(node + b / 4, b % 4);
                    add(t.m, i, j, em.M(a, b));
                    add(t.k, i, j, em.K(a, b));
                    add(t.g, i, j, em.G(a, b));
                    add(t.c, i, j, em.D(a, b));
                    add(t.n, i, j, em.N(a, b));
                }
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                const int za = d.dof(node + a, Z), zb = d.dof(node + b, Z);
                const int ta = d.dof(node + a, TZ), tb = d.dof(node + b, TZ);
                add(t.m, za, zb, em.M_axial(a, b));
                add(t.k, za, zb, em.K_axial(a, b));
                add(t.c, za, zb, em.D_axial(a, b));
                add(t.m, ta, tb, em.M_torsion(a, b));
                add(t.k, ta, tb, em.K_torsion(a, b));
                add(t.c, ta, tb, em.D_torsion(a, b));
            }
    }
}

// Rigid disks: mass, inertias, gyroscopic moments, and their unbalance forces.
void stamp_disks(const FeRotor& rotor, const DofNumbering& d, Triplets& t, Eigen::VectorXcd& unbalance) {
    for (const FeDisk& disk : rotor.disks) {
        const int k = disk.node;
        add(t.m, d.dof(k, X), d.dof(k, X), disk.mass);
        add(t.m, d.dof(k, Y), d.dof(k, Y), disk.mass);
        add(t.m, d.dof(k, TX), d.dof(k, TX), disk.diametral_inertia);
        add(t.m, d.dof(k, TY), d.dof(k, TY), disk.diametral_inertia);
        add(t.g, d.dof(k, TX), d.dof(k, TY), disk.polar_inertia);
        add(t.g, d.dof(k, TY), d.dof(k, TX), -disk.polar_inertia);
        add(t.m, d.dof(k, Z), d.dof(k, Z), disk.mass);
        add(t.m, d.dof(k, TZ), d.dof(k, TZ), disk.polar_inertia);
        // Force w^2 m_e e (cos(w t + phi), sin(w t + phi)) = Re(w^2 m_e e e^{i phi} (1, -i) e^{i w t}).
        const std::complex<double> f = disk.unbalance * std::polar(1.0, disk.unbalance_phase);
        if (d.dof(k, X) >= 0) unbalance(d.dof(k, X)) += f;
        if (d.dof(k, Y) >= 0) unbalance(d.dof(k, Y)) += std::complex<double>(0, -1) * f;
    }
}

// Bearings: stiffness and damping to ground, or to the pedestal the node stands on.
void stamp_bearings(const FeRotor& rotor, const DofNumbering& d, Triplets& t) {
    for (const FeBearing& br : rotor.bearings) {
        const int k = br.node, sx = d.dof(k, X), sy = d.dof(k, Y);
        add(t.k, sx, sx, br.kxx);
        add(t.k, sx, sy, br.kxy);
        add(t.k, sy, sx, br.kyx);
        add(t.k, sy, sy, br.kyy);
        add(t.d, sx, sx, br.cxx);
        add(t.d, sx, sy, br.cxy);
        add(t.d, sy, sx, br.cyx);
        add(t.d, sy, sy, br.cyy);
        // On a pedestal the forces act on the relative motion: the pedestal's pair gets
        // +B and the shaft-pedestal blocks -B (a held shaft DOF keeps only the pedestal's).
        if (const int p = d.pedestal_of[k]; p >= 0) {
            const double kb[2][2] = {{br.kxx, br.kxy}, {br.kyx, br.kyy}}, cb[2][2] = {{br.cxx, br.cxy}, {br.cyx, br.cyy}};
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                    const int si = i == 0 ? sx : sy, sj = j == 0 ? sx : sy;
                    for (auto [tr, v] : {std::pair{&t.k, kb[i][j]}, std::pair{&t.d, cb[i][j]}}) {
                        add(*tr, p + i, p + j, v);
                        add(*tr, si, p + j, -v);
                        add(*tr, p + i, sj, -v);
                    }
                }
        }
        add(t.k, d.dof(k, Z), d.dof(k, Z), br.kzz);
        add(t.d, d.dof(k, Z), d.dof(k, Z), br.czz);
    }
}

// Pedestals: their mass and their own springs and dampers to ground.
void stamp_pedestals(const FeRotor& rotor, const DofNumbering& d, Triplets& t) {
    for (const FePedestal& p : rotor.pedestals) {
        const int i = d.pedestal_of[p.node];
        if (i < 0) continue;   // an axial or torsional model: no pedestal DOFs
        t.m.emplace_back(i, i, p.mass);
        t.m.emplace_back(i + 1, i + 1, p.mass);
        for (auto [tr, a, b] : {std::tuple{&t.k, p.kxx, p.kyy}, std::tuple{&t.d, p.cxx, p.cyy}}) {
            if (a != 0.0) tr->emplace_back(i, i, a);
            if (b != 0.0) tr->emplace_back(i + 1, i + 1, b);
        }
    }
}

}  // namespace

FeRotorMatrices FeRotor::assemble() const {
    validate();
    const int nodes = node_count();
    FeRotorMatrices r;
    const DofNumbering d = number_dofs(*this, r);
    const int n = d.n;
    for (int k = 0; k < nodes; ++k)
        for (int p = 0; p < 2; ++p) {
            const int u = d.dof(k, 2 * p), v = d.dof(k, 2 * p + 1);
            if (u >= 0 && v >= 0) r.whirl_pairs.emplace_back(u, v);
        }
    r.node_z.resize(nodes);
    r.node_z[0] = 0.0;
    for (int e = 0; e < nodes - 1; ++e) r.node_z[e + 1] = r.node_z[e] + elements[e].length;

    Triplets t;
    const std::size_t lateral = has_lateral() ? 64 : 0, bars = 4 * (has_axial() + has_torsion());
    t.m.reserve((lateral + bars) * elements.size() + d.per * disks.size());
    t.k.reserve((lateral + bars) * elements.size() + 5 * bearings.size());
    t.g.reserve(lateral / 2 * elements.size() + 2 * disks.size());
    t.d.reserve(5 * bearings.size());
    stamp_elements(*this, d, t);
    r.unbalance = Eigen::VectorXcd::Zero(n);
    stamp_disks(*this, d, t, r.unbalance);
    stamp_bearings(*this, d, t);
    stamp_pedestals(*this, d, t);
    auto build = [n](Eigen::SparseMatrix<double>& S, const std::vector<Triplet>& tr) {
        S.resize(n, n);
        S.setFromTriplets(tr.begin(), tr.end());
        S.makeCompressed();
    };
    build(r.M, t.m);
    build(r.K, t.k);
    build(r.G, t.g);
    build(r.D, t.d);
    build(r.D_couplings, t.c);
    build(r.N, t.n);
    return r;
}

SparsePencil FeRotorMatrices::at_speed(double w) const {
    SparsePencil p;
    p.M = M;
    p.C = D + D_couplings + w * G;
    p.K = N.nonZeros() > 0 ? SparseMatrix(K + w * N) : K;
    return p;
}

GyroscopicSystem FeRotorMatrices::to_system() const {
    GyroscopicSystem s;
    s.dofs = dofs;
    s.M = M;
    s.K = K;
    s.G = G;
    if (D.nonZeros() > 0) s.damping.push_back({"bearings", D});
    if (D_couplings.nonZeros() > 0) s.damping.push_back({"couplings", D_couplings});
    if (N.nonZeros() > 0) s.N = N;
    if (unbalance.size() > 0 && unbalance.cwiseAbs().maxCoeff() > 0) s.unbalance = unbalance;
    s.whirl_pairs = whirl_pairs;
    s.node_z = node_z;
    return s;
}


int dofs_per_node(FeMotion m) {
    switch (m) {
        case FeMotion::lateral: return 4;
        case FeMotion::all: return 6;
        case FeMotion::axial:
        case FeMotion::torsional: return 1;
    }
    return 0;
}

const char* to_string(FeMotion m) {
    switch (m) {
        case FeMotion::lateral: return "lateral";
        case FeMotion::all: return "all";
        case FeMotion::axial: return "axial";
        case FeMotion::torsional: return "torsional";
    }
    return "?";
}

GyroscopicSystem make_system(const FeRotor& r) {
    GyroscopicSystem s = r.assemble().to_system();
    s.validate("fe rotor");
    return s;
}

FeRotor fe_uniform_shaft(double length, int count, double outer_diameter, double inner_diameter,
                         double youngs_modulus, double poisson_ratio, double density) {
    if (count < 1)
        throw InputError(fmt::format("fe rotor: element count = {} is out of range; allowed: an integer >= 1", count));
    FeRotor r;
    FeShaftElement e;
    e.length = length / count;
    e.outer_diameter = outer_diameter;
    e.inner_diameter = inner_diameter;
    e.youngs_modulus = youngs_modulus;
    e.poisson_ratio = poisson_ratio;
    e.density = density;
    r.elements.assign(static_cast<std::size_t>(count), e);
    return r;
}

}  // namespace gyrokit
