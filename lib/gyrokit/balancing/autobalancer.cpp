#include <gyrokit/balancing/autobalancer.hpp>

#include <gyrokit/core/error.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

void require(bool ok, const std::string& what) {
    if (!ok) throw InputError("autobalancer: " + what);
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }
bool finite_nonneg(double v) { return std::isfinite(v) && v >= 0.0; }

// Generalized coordinates: at most x, y, phi0, phi1, phi2.
constexpr int kMaxDofs = 5;
using MassMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxDofs, kMaxDofs>;
using DofVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDofs, 1>;

}  // namespace

double AutobalancerParameters::M() const {
    double s = m + m0;
    for (const auto& r : rollers) s += r.m;
    return s;
}

double AutobalancerParameters::J00() const {
    double s = J + m0 * eps0 * eps0;
    for (const auto& r : rollers) s += r.mu * r.m * r.R * r.R;
    return s;
}

double AutobalancerParameters::omega_x() const { return std::sqrt(k_x / M()); }
double AutobalancerParameters::omega_y() const { return std::sqrt(k_y / M()); }

double AutobalancerParameters::f_unbalance(int i, double Omega) const {
    const double U = i == 0 ? m0 * eps0 : rollers.at(static_cast<std::size_t>(i - 1)).unbalance();
    return U * Omega * Omega;
}

double AutobalancerParameters::reference_speed() const { return drive == Drive::Motor ? L0 / beta0 : speed; }

void AutobalancerParameters::validate() const {
    require(finite_positive(m), fmt::format("m = {}: allowed: > 0 kg", m));
    require(finite_nonneg(J), fmt::format("J = {}: allowed: >= 0 kg m^2", J));
    require(finite_nonneg(m0), fmt::format("m0 = {}: allowed: >= 0 kg", m0));
    require(finite_nonneg(eps0), fmt::format("eps0 = {}: allowed: >= 0 m", eps0));
    require(finite_positive(k_x), fmt::format("k_x = {}: allowed: > 0 N/m", k_x));
    require(finite_positive(k_y), fmt::format("k_y = {}: allowed: > 0 N/m", k_y));
    require(finite_nonneg(c_x), fmt::format("c_x = {}: allowed: >= 0 N s/m", c_x));
    require(finite_nonneg(c_y), fmt::format("c_y = {}: allowed: >= 0 N s/m", c_y));
    require(rollers.size() <= 2, fmt::format("{} rollers: allowed: 0, 1 or 2", rollers.size()));
    double sum_beta = 0.0;
    for (std::size_t i = 0; i < rollers.size(); ++i) {
        const Roller& r = rollers[i];
        const std::size_t n = i + 1;
        require(finite_positive(r.m), fmt::format("m{} = {}: allowed: > 0 kg", n, r.m));
        require(finite_positive(r.eps), fmt::format("eps{} = {}: allowed: > 0 m", n, r.eps));
        require(std::isfinite(r.R) && r.R > r.eps,
                fmt::format("R{} = {}: allowed: > eps{} = {} m (the raceway lies outside the path of the "
                            "roller centre)", n, r.R, n, r.eps));
        require(std::isfinite(r.mu) && r.mu >= 0.0 && r.mu <= 1.0,
                fmt::format("mu{} = {}: allowed: 0 <= mu <= 1", n, r.mu));
        // Without viscous coupling the rollers never settle: the slow phase equations need beta_i > 0.
        require(finite_positive(r.beta), fmt::format("beta{} = {}: allowed: > 0 N m s (the rollers need viscous "
                                                     "damping to settle)", n, r.beta));
        sum_beta += r.beta;
    }
    if (drive == Drive::PrescribedSpeed) {
        require(finite_nonneg(speed), fmt::format("speed = {}: allowed: >= 0 rad/s", speed));
    } else {
        require(finite_positive(J), fmt::format("J = {}: allowed with a motor drive: > 0 kg m^2", J));
        require(finite_nonneg(L0), fmt::format("L0 = {}: allowed: >= 0 N m", L0));
        // beta0 of (17) contains sum beta_i; the motor side (slope + external damping) must be positive,
        // otherwise the rotor speed is not bounded.
        require(std::isfinite(beta0) && beta0 > sum_beta,
                fmt::format("beta0 = {}: allowed: > beta1 + beta2 = {} N m s (beta0 of eq. (17) includes the "
                            "rollers' beta_i)", beta0, sum_beta));
    }
}

AutobalancerModel::AutobalancerModel(AutobalancerParameters p) : p_(std::move(p)) {
    p_.validate();
    first_roller_ = motor() ? 6 : 4;
    omega_ref_ = p_.reference_speed();
}

std::vector<double> AutobalancerModel::initial_state(const std::vector<double>& alpha, double x, double y) const {
    if (alpha.size() != p_.rollers.size())
        throw InputError(fmt::format("autobalancer: {} initial phases given for {} rollers", alpha.size(),
                                     p_.rollers.size()));
    std::vector<double> s(state_size(), 0.0);
    s[0] = x;
    s[1] = y;
    if (motor()) s[5] = omega_ref_;
    for (int i = 0; i < rollers(); ++i) s[alpha_index(i)] = alpha[static_cast<std::size_t>(i)];
    return s;
}

void AutobalancerModel::set_nominal_profile(NominalSpeedProfile profile) {
    if (!motor()) throw InputError("autobalancer: a nominal-speed profile needs the motor drive (L0, beta0)");
    if (!profile.speed || !profile.angle)
        throw InputError("autobalancer: a nominal-speed profile needs both its speed and its angle");
    profile_ = std::move(profile);
}

double AutobalancerModel::rotor_angle(double t, const double* s) const {
    if (has_profile()) return profile_.angle(t) + s[4];
    return omega_ref_ * t + (motor() ? s[4] : 0.0);
}

double AutobalancerModel::rotor_speed(const double* s) const { return motor() ? s[5] : omega_ref_; }

bool AutobalancerModel::rhs(double t, const double* s, double* dsdt, const char** why) const {
    const int nr = rollers();
    const bool mot = motor();
    for (std::size_t k = 0; k < state_size(); ++k)
        if (!std::isfinite(s[k])) {
            if (why) *why = "the state is not finite";
            return false;
        }
    const double phi0 = rotor_angle(t, s), w0 = rotor_speed(s);
    // DOF order: x, y, [phi0], phi_1..phi_n
    const int nd = 2 + (mot ? 1 : 0) + nr;
    const int i0 = 2, ir = mot ? 3 : 2;
    MassMatrix Mq = MassMatrix::Zero(nd, nd);
    DofVector Q = DofVector::Zero(nd);
    const double M = p_.M();
    Mq(0, 0) = M;
    Mq(1, 1) = M;
    const double x = s[0], y = s[1], vx = s[2], vy = s[3];
    Q(0) = -p_.c_x * vx - p_.k_x * x;
    Q(1) = -p_.c_y * vy - p_.k_y * y;

    // Unbalance: centrifugal term with phi0'^2; its phi0'' term sits in the mass matrix
    // (motor drive) or vanishes (phi0'' = 0 at prescribed speed).
    const double U0 = p_.m0 * p_.eps0, s0 = std::sin(phi0), c0 = std::cos(phi0);
    Q(0) += U0 * w0 * w0 * c0;
    Q(1) += U0 * w0 * w0 * s0;
    if (mot) {
        Mq(i0, i0) = p_.J00();
        Mq(0, i0) = Mq(i0, 0) = -U0 * s0;
        Mq(1, i0) = Mq(i0, 1) = U0 * c0;
        const double L0 = has_profile() ? p_.beta0 * profile_.speed(t) : p_.L0;
        Q(i0) = L0 - p_.beta0 * w0;
    }
    for (int i = 0; i < nr; ++i) {
        const Roller& r = p_.rollers[static_cast<std::size_t>(i)];
        const double alpha = s[alpha_index(i)], wrel = s[alpha_rate_index(i)];
        const double phi = phi0 + alpha, w = w0 + wrel;
        const double U = r.unbalance(), si = std::sin(phi), ci = std::cos(phi);
        const int k = ir + i;
        Mq(k, k) = r.J_ii();
        Mq(0, k) = Mq(k, 0) = -U * si;
        Mq(1, k) = Mq(k, 1) = U * ci;
        Q(0) += U * w * w * ci;
        Q(1) += U * w * w * si;
        Q(k) = -r.beta * wrel;   // beta_i (phi0' - phi_i')
        if (mot) {
            Mq(i0, k) = Mq(k, i0) = -r.J_0i();
            Q(i0) += r.beta * w;   // the total beta0 * phi0' above already holds -beta_i phi0'
        }
    }
    const Eigen::LLT<MassMatrix> llt(Mq);
    if (llt.info() != Eigen::Success) {
        if (why) *why = "the mass matrix is not positive definite";
        return false;
    }
    const DofVector qdd = llt.solve(Q);
    dsdt[0] = vx;
    dsdt[1] = vy;
    dsdt[2] = qdd(0);
    dsdt[3] = qdd(1);
    double phi0dd = 0.0;
    if (mot) {
        phi0dd = qdd(i0);
        dsdt[4] = w0 - (has_profile() ? profile_.speed(t) : omega_ref_);
        dsdt[5] = phi0dd;
    }
    for (int i = 0; i < nr; ++i) {
        dsdt[alpha_index(i)] = s[alpha_rate_index(i)];
        dsdt[alpha_rate_index(i)] = qdd(ir + i) - phi0dd;
    }
    for (std::size_t k = 0; k < state_size(); ++k)
        if (!std::isfinite(dsdt[k])) {
            if (why) *why = "the right-hand side is not finite";
            return false;
        }
    return true;
}

}  // namespace gyrokit
