// Element matrices of the finite-element rotor: the Timoshenko beam (uniform and tapered),
// the axial and torsion bars, couplings, and the section properties they integrate.
#include <gyrokit/core/constants.hpp>
#include <gyrokit/models/fe_rotor.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <tuple>

namespace gyrokit {

namespace {

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
    s.area = kPi * (o * o - i * i) / 4;
    s.second_moment = kPi * (o * o * o * o - i * i * i * i) / 64;
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

}  // namespace gyrokit
