#include <gyrokit/models/gyrostat.hpp>

#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

// The rows and columns of `A` belonging to the kept DOFs. A rigid element forces
// its coordinates to zero, so the remaining equations are exactly these.
Eigen::MatrixXd keep(const Eigen::MatrixXd& A, const std::vector<int>& dofs) {
    const int k = static_cast<int>(dofs.size());
    Eigen::MatrixXd B(k, k);
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) B(i, j) = A(dofs[i], dofs[j]);
    return B;
}

}  // namespace

void validate(const GyrostatParameters& p, const std::string& origin) {
    if (p.rigid_shaft && p.rigid_housing)
        throw InputError(origin + ": shaft = 'rigid' with housing = 'rigid' leaves no degree of freedom; "
                                  "allowed: at most one of them rigid");
    const auto pos = [](double v) { return std::isfinite(v) && v > 0; };
    const auto nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
    if (!p.rigid_housing) {
        check_parameter(pos(p.A_G), origin, "A_G", p.A_G, "a finite number > 0 (kg m^2)");
        check_parameter(pos(p.B_G), origin, "B_G", p.B_G, "a finite number > 0 (kg m^2)");
        check_parameter(pos(p.c_G), origin, "c_G", p.c_G, "a finite number > 0 (N m/rad)");
    }
    check_parameter(pos(p.A_R), origin, "A_R", p.A_R, "a finite number > 0 (kg m^2)");
    check_parameter(pos(p.C_R), origin, "C_R", p.C_R, "a finite number > 0 (kg m^2)");
    check_parameter(pos(p.m), origin, "m", p.m, "a finite number > 0 (kg)");
    check_parameter(std::isfinite(p.s), origin, "s", p.s, "a finite number (m)");
    check_parameter(nonneg(p.eps), origin, "eps", p.eps, "a finite number >= 0 (m)");
    if (!p.rigid_shaft) {
        check_parameter(pos(p.c_T), origin, "c_T", p.c_T, "a finite number > 0 (N/m)");
        check_parameter(pos(p.c_R), origin, "c_R", p.c_R, "a finite number > 0 (N m/rad)");
    }
    check_parameter(nonneg(p.d_G), origin, "d_G", p.d_G, "a finite number >= 0 (N m s/rad)");
    check_parameter(nonneg(p.d_T), origin, "d_T", p.d_T, "a finite number >= 0 (N s/m)");
    check_parameter(nonneg(p.d_R), origin, "d_R", p.d_R, "a finite number >= 0 (N m s/rad)");
}

GyroscopicSystem make_system(const GyrostatParameters& p) {
    if (p.rigid_shaft && p.rigid_housing)
        throw InputError("a gyrostat with rigid shaft and rigid housing has no degrees of freedom; "
                         "make at least one of them elastic");
    enum { a = 0, b = 1, x = 2, y = 3, ps = 4, th = 5 };
    const double A = p.A_G + p.A_R + p.m * p.s * p.s;
    const double B = p.B_G + p.A_R + p.m * p.s * p.s;
    const double ms = p.m * p.s;

    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6, 6);
    M(a, a) = A;     M(a, y) = ms;    M(a, ps) = p.A_R;
    M(b, b) = B;     M(b, x) = -ms;   M(b, th) = p.A_R;
    M(x, b) = -ms;   M(x, x) = p.m;
    M(y, a) = ms;    M(y, y) = p.m;
    M(ps, a) = p.A_R; M(ps, ps) = p.A_R;
    M(th, b) = p.A_R; M(th, th) = p.A_R;

    // Gyroscopic coupling L = C_R w of the absolute rotor tilts (alpha+psi, beta+theta).
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(6, 6);
    for (int row : {a, ps}) { G(row, b) = p.C_R;  G(row, th) = p.C_R; }
    for (int row : {b, th}) { G(row, a) = -p.C_R; G(row, ps) = -p.C_R; }

    Eigen::MatrixXd K = Eigen::VectorXd((Eigen::VectorXd(6) << p.c_G, p.c_G, p.c_T, p.c_T, p.c_R, p.c_R)
                                            .finished()).asDiagonal();
    auto diag = [](int i, int j, double d) {
        Eigen::MatrixXd D = Eigen::MatrixXd::Zero(6, 6);
        D(i, i) = D(j, j) = d;
        return D;
    };

    // Unbalance m eps w^2 along (cos wt, sin wt) at the rotor centre, a distance s
    // below the suspension point: f = Re(F e^{i w t}), eq. (12) of the paper with the factor s.
    const std::complex<double> I(0.0, 1.0);
    Eigen::VectorXcd u(6);
    u << -I * p.s, -p.s, 1.0, -I, 0.0, 0.0;
    u *= p.m * p.eps;

    std::vector<int> dofs;
    if (!p.rigid_housing) dofs.insert(dofs.end(), {a, b});
    if (!p.rigid_shaft) dofs.insert(dofs.end(), {x, y, ps, th});
    const char* names[6] = {"alpha", "beta", "x", "y", "psi", "theta"};

    GyroscopicSystem sys;
    sys.M = to_sparse(keep(M, dofs));
    sys.G = to_sparse(keep(G, dofs));
    sys.K = to_sparse(keep(K, dofs));
    const std::vector<std::pair<const char*, Eigen::MatrixXd>> comps = {
        {"d_G", diag(a, b, p.d_G)}, {"d_T", diag(x, y, p.d_T)}, {"d_R", diag(ps, th, p.d_R)}};
    for (const auto& [name, D] : comps) {
        Eigen::MatrixXd Dk = keep(D, dofs);
        if (Dk.norm() > 0.0) sys.damping.push_back({name, to_sparse(Dk)});
    }
    sys.unbalance.resize(static_cast<int>(dofs.size()));
    for (size_t i = 0; i < dofs.size(); ++i) {
        sys.unbalance(static_cast<int>(i)) = u(dofs[i]);
        sys.dofs.names.push_back(names[dofs[i]]);
        sys.dofs.units.push_back(dofs[i] == x || dofs[i] == y ? "m" : "rad");   // cage and rotor tilts: rad
    }
    // Forward whirl: alpha -> beta, x -> y, psi -> theta turn with the spin.
    for (size_t i = 0; i + 1 < dofs.size(); i += 2)
        sys.whirl_pairs.emplace_back(static_cast<int>(i), static_cast<int>(i + 1));
    sys.validate("gyrostat model");
    return sys;
}

}  // namespace gyrokit
