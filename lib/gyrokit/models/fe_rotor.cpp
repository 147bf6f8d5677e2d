#include <gyrokit/models/fe_rotor.hpp>

#include <gyrokit/core/error.hpp>

#include <Eigen/SparseLU>
#include <fmt/format.h>

#include <algorithm>

#include <cmath>
#include <tuple>

namespace gyrokit {

namespace {

constexpr double pi = 3.14159265358979323846;

std::string where(const char* kind, std::size_t index) { return fmt::format("fe rotor: {} {}", kind, index); }

void require(bool ok, const std::string& item, const char* key, double value, const std::string& range) {
    if (!ok) throw InputError(fmt::format("{}: {} = {} is out of range; allowed: {}", item, key, value, range));
}

void require_finite(const std::string& item, const char* key, double value) {
    require(std::isfinite(value), item, key, value, "a finite number");
}

using Mat4 = Eigen::Matrix4d;

// Plane matrices of a Timoshenko beam in the standard DOFs (w1, psi1, w2, psi2),
// psi the cross-section rotation with psi = dw/dz in the slender limit
// (Przemieniecki; Friswell et al. eq. 5.x). Phi = 12 E I / (kappa G A L^2).
struct PlaneMatrices {
    Mat4 K, Mt, Mr;   // stiffness, translational mass, rotary inertia (per rho I)
};

PlaneMatrices plane_matrices(double L, double EI, double rhoA, double rhoI, double Phi) {
    PlaneMatrices p;
    const double L2 = L * L;
    const double k = EI / ((1.0 + Phi) * L2 * L);
    p.K << 12, 6 * L, -12, 6 * L,
           6 * L, (4 + Phi) * L2, -6 * L, (2 - Phi) * L2,
           -12, -6 * L, 12, -6 * L,
           6 * L, (2 - Phi) * L2, -6 * L, (4 + Phi) * L2;
    p.K *= k;

    const double P2 = Phi * Phi;
    const double m1 = 13.0 / 35 + 7.0 * Phi / 10 + P2 / 3;
    const double m2 = 11.0 / 210 + 11.0 * Phi / 120 + P2 / 24;
    const double m3 = 9.0 / 70 + 3.0 * Phi / 10 + P2 / 6;
    const double m4 = 13.0 / 420 + 3.0 * Phi / 40 + P2 / 24;
    const double m5 = 1.0 / 105 + Phi / 60 + P2 / 120;
    const double m6 = 1.0 / 140 + Phi / 60 + P2 / 120;
    p.Mt << m1, m2 * L, m3, -m4 * L,
            m2 * L, m5 * L2, m4 * L, -m6 * L2,
            m3, m4 * L, m1, -m2 * L,
            -m4 * L, -m6 * L2, -m2 * L, m5 * L2;
    p.Mt *= rhoA * L / ((1 + Phi) * (1 + Phi));

    const double r1 = 6.0 / 5;
    const double r2 = 1.0 / 10 - Phi / 2;
    const double r3 = 2.0 / 15 + Phi / 6 + P2 / 3;
    const double r4 = -1.0 / 30 - Phi / 6 + P2 / 6;
    p.Mr << r1, r2 * L, -r1, r2 * L,
            r2 * L, r3 * L2, -r2 * L, r4 * L2,
            -r1, -r2 * L, r1, -r2 * L,
            r2 * L, r4 * L2, -r2 * L, r3 * L2;
    p.Mr *= rhoI / (L * (1 + Phi) * (1 + Phi));
    return p;
}

// 6-point Gauss-Legendre rule on [0, 1]: exact for polynomials of degree 11, so for
// every integrand of a conical element with linear diameters (A(z) of degree 2, I(z) of
// degree 4, shape-function products of degree up to 6) except the shear coefficient's
// rational dependence on di/do, which varies little along an element.
constexpr double gauss_xi[6] = {0.5 - 0.4662347571015760, 0.5 - 0.3306046932331323, 0.5 - 0.1193095930415985,
                                0.5 + 0.1193095930415985, 0.5 + 0.3306046932331323, 0.5 + 0.4662347571015760};
constexpr double gauss_w[6] = {0.0856622461895852, 0.1803807865240693, 0.2339569672863455,
                               0.2339569672863455, 0.1803807865240693, 0.0856622461895852};

// Plane matrices of a tapered element by integrating the interdependent interpolation
// (the shape functions whose exact integrals over a uniform section are the closed forms
// above) over the varying section, xi = z / L:
//   w   = N_w q,   N_w   = [1 - 3xi^2 + 2xi^3 + Phi(1 - xi),  L(xi - 2xi^2 + xi^3 + Phi(xi - xi^2)/2),
//                           3xi^2 - 2xi^3 + Phi xi,           L(-xi^2 + xi^3 - Phi(xi - xi^2)/2)] / (1 + Phi)
//   psi = N_psi q, N_psi = [6(xi^2 - xi)/L,  1 - 4xi + 3xi^2 + Phi(1 - xi),  6(xi - xi^2)/L,
//                           -2xi + 3xi^2 + Phi xi] / (1 + Phi)
//   K  = int EI N_psi'^T N_psi' + kappa G A g^T g dz, shear strain g = N_w' - N_psi (constant),
//   Mt = int rho A N_w^T N_w dz,  Mr = int rho I N_psi^T N_psi dz,
// with Phi from the section at mid-element.
PlaneMatrices integrated_plane_matrices(const FeShaftElement& e, double Phi, bool shear_deformation,
                                        bool rotary_inertia) {
    const double L = e.length, d = 1.0 + Phi;
    PlaneMatrices p;
    p.K.setZero();
    p.Mt.setZero();
    p.Mr.setZero();
    Eigen::RowVector4d g;
    g << -1.0 / L, -0.5, 1.0 / L, -0.5;
    g *= Phi / d;
    for (int q = 0; q < 6; ++q) {
        const double x = gauss_xi[q], wq = gauss_w[q] * L, x2 = x * x, x3 = x2 * x;
        const FeSection s = fe_section(e, x);
        Eigen::RowVector4d Nw, Np, dNp;
        Nw << 1 - 3 * x2 + 2 * x3 + Phi * (1 - x), L * (x - 2 * x2 + x3 + Phi * (x - x2) / 2),
            3 * x2 - 2 * x3 + Phi * x, L * (-x2 + x3 - Phi * (x - x2) / 2);
        Np << 6 * (x2 - x) / L, 1 - 4 * x + 3 * x2 + Phi * (1 - x), 6 * (x - x2) / L, -2 * x + 3 * x2 + Phi * x;
        dNp << 6 * (2 * x - 1) / (L * L), (-4 + 6 * x - Phi) / L, 6 * (1 - 2 * x) / (L * L), (-2 + 6 * x + Phi) / L;
        Nw /= d;
        Np /= d;
        dNp /= d;
        p.K += wq * e.youngs_modulus * s.second_moment * dNp.transpose() * dNp;
        if (shear_deformation) p.K += wq * s.shear_coefficient * s.shear_modulus * s.area * g.transpose() * g;
        p.Mt += wq * e.density * s.area * Nw.transpose() * Nw;
        if (rotary_inertia) p.Mr += wq * e.density * s.second_moment * Np.transpose() * Np;
    }
    return p;
}

// A bar with linear shape functions (axial: EA, rho A; torsion: G J, rho J), integrated
// over the section like the plane matrices: K = int s(z) dz / L^2 [1 -1; -1 1],
// M = int m(z) N^T N dz (uniform: s/L [1 -1; -1 1] and m L/6 [2 1; 1 2]).
template <class Stiffness, class MassPerLength>
void bar_matrices(double L, const Stiffness& stiffness, const MassPerLength& mass, Eigen::Matrix2d& K,
                  Eigen::Matrix2d& M) {
    double s = 0.0;
    M.setZero();
    for (int q = 0; q < 6; ++q) {
        const double x = gauss_xi[q], wq = gauss_w[q] * L;
        const Eigen::Vector2d N(1 - x, x);
        s += wq * stiffness(x);
        M += wq * mass(x) * N * N.transpose();
    }
    K << 1, -1, -1, 1;
    K *= s / (L * L);
}

}  // namespace

double cowper_shear_coefficient(double nu, double m) {
    const double q = (1 + m * m) * (1 + m * m);
    return 6 * (1 + nu) * q / ((7 + 6 * nu) * q + (20 + 12 * nu) * m * m);
}

FeSection fe_section(const FeShaftElement& e, double xi) {
    FeSection s;
    const double o = e.outer_diameter + xi * (e.outer_diameter_end.value_or(e.outer_diameter) - e.outer_diameter);
    const double i0 = e.inner_diameter, i1 = e.inner_diameter_end.value_or(e.inner_diameter);
    const double i = i0 + xi * (i1 - i0);
    s.area = pi * (o * o - i * i) / 4;
    s.second_moment = pi * (o * o * o * o - i * i * i * i) / 64;
    s.shear_coefficient = cowper_shear_coefficient(e.poisson_ratio, i / o);
    s.shear_modulus = e.shear_modulus > 0 ? e.shear_modulus : e.youngs_modulus / (2 * (1 + e.poisson_ratio));
    return s;
}

double fe_element_mass(const FeShaftElement& e) {
    if (e.coupling) return e.coupling->mass;
    const double a = fe_section(e, 0.0).area, m = fe_section(e, 0.5).area, b = fe_section(e, 1.0).area;
    return e.density * e.length * (a + 4 * m + b) / 6;
}

namespace {

// A coupling: diagonal springs and dampers on the relative motion, half its mass and
// inertias lumped at each node (as ROSS's coupling element), Ip / 2 gyroscopic at each node.
FeElementMatrices coupling_matrices(const FeCoupling& c) {
    FeElementMatrices m;
    m.M.setZero();
    m.K.setZero();
    m.G.setZero();
    m.D.setZero();
    m.N.setZero();
    const double k[4] = {c.k_lateral, c.k_lateral, c.k_bending, c.k_bending};
    const double d[4] = {c.c_lateral, c.c_lateral, c.c_bending, c.c_bending};
    const double mass[4] = {c.mass / 2, c.mass / 2, c.diametral_inertia / 2, c.diametral_inertia / 2};
    const auto relative = [](Eigen::Matrix<double, 8, 8>& A, int a, double v) {
        A(a, a) = A(a + 4, a + 4) = v;
        A(a, a + 4) = A(a + 4, a) = -v;
    };
    for (int a = 0; a < 4; ++a) {
        relative(m.K, a, k[a]);
        relative(m.D, a, d[a]);
        m.M(a, a) = m.M(a + 4, a + 4) = mass[a];
    }
    for (const int b : {0, 4}) {
        m.G(b + 2, b + 3) = c.polar_inertia / 2;
        m.G(b + 3, b + 2) = -c.polar_inertia / 2;
    }
    // Rotating dampers in fixed axes (Jeffcott with internal damping c_i: the force
    // -c_i (q' - w J q) with J the quarter turn), on the relative pairs (x, y), (tx, ty):
    // N(u, v) = +c, N(v, u) = -c of each relative pair.
    for (const int p : {0, 2}) {
        const double cp = d[p];
        for (const auto& [a, b, sign] : {std::tuple{0, 0, 1.0}, std::tuple{0, 4, -1.0}, std::tuple{4, 0, -1.0},
                                         std::tuple{4, 4, 1.0}}) {
            m.N(a + p, b + p + 1) = sign * cp;
            m.N(a + p + 1, b + p) = -sign * cp;
        }
    }
    const Eigen::Matrix2d spring = (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
    m.K_axial = c.k_axial * spring;
    m.K_torsion = c.k_torsion * spring;
    m.D_axial = c.c_axial * spring;
    m.D_torsion = c.c_torsion * spring;
    m.M_axial = Eigen::Matrix2d::Identity() * (c.mass / 2);
    m.M_torsion = Eigen::Matrix2d::Identity() * (c.polar_inertia / 2);
    return m;
}

}  // namespace

FeElementMatrices fe_shaft_element_matrices(const FeShaftElement& e, bool shear_deformation, bool rotary_inertia) {
    if (e.coupling) return coupling_matrices(*e.coupling);
    const bool tapered = e.outer_diameter_end.has_value() || e.inner_diameter_end.has_value();
    const FeSection s = fe_section(e, tapered ? 0.5 : 0.0);
    const double L = e.length;
    const double EI = e.youngs_modulus * s.second_moment;
    const double Phi = shear_deformation ? 12 * EI / (s.shear_coefficient * s.shear_modulus * s.area * L * L) : 0.0;
    const double rhoI = rotary_inertia ? e.density * s.second_moment : 0.0;
    const PlaneMatrices p = tapered ? integrated_plane_matrices(e, Phi, shear_deformation, rotary_inertia)
                                    : plane_matrices(L, EI, e.density * s.area, rhoI, Phi);

    // x-z plane: (x, theta_y) with theta_y = +dx/dz: the standard DOFs.
    // y-z plane: (y, theta_x) with theta_x = -dy/dz: standard DOFs (y, -theta_x),
    // i.e. the plane matrix transformed with T = diag(1, -1, 1, -1).
    const int ix[4] = {0, 3, 4, 7};   // x1, ty1, x2, ty2
    const int iy[4] = {1, 2, 5, 6};   // y1, tx1, y2, tx2
    const double t[4] = {1, -1, 1, -1};

    FeElementMatrices m;
    m.M.setZero();
    m.K.setZero();
    m.G.setZero();
    m.D.setZero();   // a beam has no damping of its own
    m.N.setZero();
    m.D_axial.setZero();
    m.D_torsion.setZero();
    const Mat4 Mp = p.Mt + p.Mr;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
            m.K(ix[a], ix[b]) = p.K(a, b);
            m.K(iy[a], iy[b]) = t[a] * t[b] * p.K(a, b);
            m.M(ix[a], ix[b]) = Mp(a, b);
            m.M(iy[a], iy[b]) = t[a] * t[b] * Mp(a, b);
            // Distributed polar inertia 2 rho I: G = int 2 rho I (N_tx^T N_ty - N_ty^T N_tx) dz
            // with N_ty = N_psi S_x, N_tx = -N_psi T S_y:
            // G = 2 (S_y^T T Mr S_x)^T-part: G(x-plane a, y-plane b) = 2 Mr(a,b) t_b, and its negative transpose.
            const double g = 2 * p.Mr(a, b) * t[b];
            m.G(ix[a], iy[b]) = g;
            m.G(iy[b], ix[a]) = -g;
        }
    // Axial bar (E A, rho A) and torsion bar (G J, rho J; J = 2 I, the polar second moment).
    const auto section = [&](double x) { return fe_section(e, tapered ? x : 0.0); };
    bar_matrices(
        L, [&](double x) { return e.youngs_modulus * section(x).area; },
        [&](double x) { return e.density * section(x).area; }, m.K_axial, m.M_axial);
    bar_matrices(
        L, [&](double x) { const FeSection q = section(x); return q.shear_modulus * 2 * q.second_moment; },
        [&](double x) { return e.density * 2 * section(x).second_moment; }, m.K_torsion, m.M_torsion);
    return m;
}

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

FeRotorMatrices FeRotor::assemble() const {
    validate();
    const int nodes = node_count();
    // Local DOF kinds; slot[kind]: its place within a node, -1 where the motion lacks it.
    enum { X = 0, Y = 1, TX = 2, TY = 3, Z = 4, TZ = 5 };
    int slot[6] = {-1, -1, -1, -1, -1, -1};
    int per = 0;
    for (int kind = 0; kind < 6; ++kind)
        if (kind < Z ? has_lateral() : kind == Z ? has_axial() : has_torsion()) slot[kind] = per++;
    const int full = per * nodes;

    // Map full DOF -> assembled DOF (-1: constrained).
    std::vector<char> fixed(full, 0);
    for (const FeSupport& s : supports) {
        const bool held[6] = {s.x, s.y, s.theta_x, s.theta_y, s.z, s.theta_z};
        for (int kind = 0; kind < 6; ++kind)
            if (held[kind] && slot[kind] >= 0) fixed[per * s.node + slot[kind]] = 1;
    }
    std::vector<int> map(full, -1);
    FeRotorMatrices r;
    static const char* prefix[6] = {"x", "y", "tx", "ty", "z", "tz"};
    int kind_of_slot[6] = {};
    for (int kind = 0; kind < 6; ++kind)
        if (slot[kind] >= 0) kind_of_slot[slot[kind]] = kind;
    int n = 0;
    for (int j = 0; j < full; ++j)
        if (!fixed[j]) {
            map[j] = n++;
            r.dof_names.push_back(prefix[kind_of_slot[j % per]] + std::to_string(j / per));
            r.node_of_dof.push_back(j / per);
        }
    // Assembled index of a node's DOF of a kind: -1 if held or not in the model.
    const auto dof = [&](int node, int kind) { return slot[kind] < 0 ? -1 : map[per * node + slot[kind]]; };
    // Pedestal DOFs after the node DOFs (not on the shaft's axis: node -1); lateral only.
    std::vector<int> pedestal_of(nodes, -1);   // assembled index of px at each node
    if (has_lateral())
        for (const FePedestal& p : pedestals) {
            pedestal_of[p.node] = n;
            for (const char* name : {"px", "py"}) {
                r.dof_names.push_back(name + std::to_string(p.node));
                r.node_of_dof.push_back(-1);
                ++n;
            }
        }
    if (n == 0)
        throw InputError(fmt::format("fe rotor: supports: every DOF of the {} model is constrained; allowed: at least "
                                     "one free DOF",
                                     to_string(motion)));
    for (int k = 0; k < nodes; ++k)
        for (int p = 0; p < 2; ++p) {
            const int u = dof(k, 2 * p), v = dof(k, 2 * p + 1);
            if (u >= 0 && v >= 0) r.whirl_pairs.emplace_back(u, v);
        }
    r.node_z.resize(nodes);
    r.node_z[0] = 0.0;
    for (int e = 0; e < nodes - 1; ++e) r.node_z[e + 1] = r.node_z[e] + elements[e].length;

    using T = Eigen::Triplet<double>;
    std::vector<T> tm, tk, tg, td, tc, tn;
    const std::size_t lateral = has_lateral() ? 64 : 0, bars = 4 * (has_axial() + has_torsion());
    tm.reserve((lateral + bars) * elements.size() + per * disks.size());
    tk.reserve((lateral + bars) * elements.size() + 5 * bearings.size());
    tg.reserve(lateral / 2 * elements.size() + 2 * disks.size());
    td.reserve(5 * bearings.size());
    // Adds v at the assembled DOFs a, b (skipped where either is held or not modelled).
    auto add = [&](std::vector<T>& t, int a, int b, double v) {
        if (a >= 0 && b >= 0 && v != 0.0) t.emplace_back(a, b, v);
    };

    for (std::size_t e = 0; e < elements.size(); ++e) {
        const FeElementMatrices em = fe_shaft_element_matrices(elements[e], shear_deformation, rotary_inertia);
        const int node = static_cast<int>(e);
        // Element DOF a (0..7) is local DOF a % 4 of node e + a / 4.
        if (has_lateral())
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    const int i = dof(node + a / 4, a % 4), j = dof(node + b / 4, b % 4);
                    add(tm, i, j, em.M(a, b));
                    add(tk, i, j, em.K(a, b));
                    add(tg, i, j, em.G(a, b));
                    add(tc, i, j, em.D(a, b));
                    add(tn, i, j, em.N(a, b));
                }
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) {
                const int za = dof(node + a, Z), zb = dof(node + b, Z);
                const int ta = dof(node + a, TZ), tb = dof(node + b, TZ);
                add(tm, za, zb, em.M_axial(a, b));
                add(tk, za, zb, em.K_axial(a, b));
                add(tc, za, zb, em.D_axial(a, b));
                add(tm, ta, tb, em.M_torsion(a, b));
                add(tk, ta, tb, em.K_torsion(a, b));
                add(tc, ta, tb, em.D_torsion(a, b));
            }
    }
    r.unbalance = Eigen::VectorXcd::Zero(n);
    for (const FeDisk& d : disks) {
        const int k = d.node;
        add(tm, dof(k, X), dof(k, X), d.mass);
        add(tm, dof(k, Y), dof(k, Y), d.mass);
        add(tm, dof(k, TX), dof(k, TX), d.diametral_inertia);
        add(tm, dof(k, TY), dof(k, TY), d.diametral_inertia);
        add(tg, dof(k, TX), dof(k, TY), d.polar_inertia);
        add(tg, dof(k, TY), dof(k, TX), -d.polar_inertia);
        add(tm, dof(k, Z), dof(k, Z), d.mass);
        add(tm, dof(k, TZ), dof(k, TZ), d.polar_inertia);
        // Force w^2 m_e e (cos(w t + phi), sin(w t + phi)) = Re(w^2 m_e e e^{i phi} (1, -i) e^{i w t}).
        const std::complex<double> f = d.unbalance * std::polar(1.0, d.unbalance_phase);
        if (dof(k, X) >= 0) r.unbalance(dof(k, X)) += f;
        if (dof(k, Y) >= 0) r.unbalance(dof(k, Y)) += std::complex<double>(0, -1) * f;
    }
    for (const FeBearing& br : bearings) {
        const int k = br.node, sx = dof(k, X), sy = dof(k, Y);
        add(tk, sx, sx, br.kxx);
        add(tk, sx, sy, br.kxy);
        add(tk, sy, sx, br.kyx);
        add(tk, sy, sy, br.kyy);
        add(td, sx, sx, br.cxx);
        add(td, sx, sy, br.cxy);
        add(td, sy, sx, br.cyx);
        add(td, sy, sy, br.cyy);
        // On a pedestal the forces act on the relative motion: the pedestal's pair gets
        // +B and the shaft-pedestal blocks -B (a held shaft DOF keeps only the pedestal's).
        if (const int p = pedestal_of[k]; p >= 0) {
            const double kb[2][2] = {{br.kxx, br.kxy}, {br.kyx, br.kyy}}, cb[2][2] = {{br.cxx, br.cxy}, {br.cyx, br.cyy}};
            for (int i = 0; i < 2; ++i)
                for (int j = 0; j < 2; ++j) {
                    const int si = i == 0 ? sx : sy, sj = j == 0 ? sx : sy;
                    for (auto [t, v] : {std::pair{&tk, kb[i][j]}, std::pair{&td, cb[i][j]}}) {
                        add(*t, p + i, p + j, v);
                        add(*t, si, p + j, -v);
                        add(*t, p + i, sj, -v);
                    }
                }
        }
        add(tk, dof(k, Z), dof(k, Z), br.kzz);
        add(td, dof(k, Z), dof(k, Z), br.czz);
    }
    for (const FePedestal& p : pedestals) {
        const int i = pedestal_of[p.node];
        if (i < 0) continue;   // an axial or torsional model: no pedestal DOFs
        tm.emplace_back(i, i, p.mass);
        tm.emplace_back(i + 1, i + 1, p.mass);
        for (auto [t, a, b] : {std::tuple{&tk, p.kxx, p.kyy}, std::tuple{&td, p.cxx, p.cyy}}) {
            if (a != 0.0) t->emplace_back(i, i, a);
            if (b != 0.0) t->emplace_back(i + 1, i + 1, b);
        }
    }
    auto build = [n](Eigen::SparseMatrix<double>& S, const std::vector<T>& t) {
        S.resize(n, n);
        S.setFromTriplets(t.begin(), t.end());
        S.makeCompressed();
    };
    build(r.M, tm);
    build(r.K, tk);
    build(r.G, tg);
    build(r.D, td);
    build(r.D_couplings, tc);
    build(r.N, tn);
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
    s.dof_names = dof_names;
    s.M = M;
    s.K = K;
    s.G = G;
    if (D.nonZeros() > 0) s.damping.push_back({"bearings", D});
    if (D_couplings.nonZeros() > 0) s.damping.push_back({"couplings", D_couplings});
    if (N.nonZeros() > 0) s.N = N;
    if (unbalance.size() > 0 && unbalance.cwiseAbs().maxCoeff() > 0) s.unbalance = unbalance;
    s.whirl_pairs = whirl_pairs;
    s.node_of_dof = node_of_dof;
    s.node_z = node_z;
    for (const auto& name : dof_names) s.dof_units.push_back(name[0] == 't' ? "rad" : "m");   // tx, ty: rotations
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
