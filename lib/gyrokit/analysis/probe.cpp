#include <gyrokit/analysis/probe.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace gyrokit {

namespace {

// cos and sin of an angle in degrees, exact at multiples of 90 degrees (where
// cos(pi/2) would give 6e-17 instead of 0).
std::pair<double, double> cos_sin_degrees(double degrees) {
    double r = std::fmod(degrees, 360.0);
    if (r < 0.0) r += 360.0;
    if (r == 0.0) return {1.0, 0.0};
    if (r == 90.0) return {0.0, 1.0};
    if (r == 180.0) return {-1.0, 0.0};
    if (r == 270.0) return {0.0, -1.0};
    const double a = r * kPi / 180.0;
    return {std::cos(a), std::sin(a)};
}

}  // namespace

std::complex<double> probe_response(const Probe& p, const Eigen::VectorXcd& Z) {
    const auto n = static_cast<int>(Z.size());
    if (p.dof_x < 0 || p.dof_x >= n || p.dof_y < 0 || p.dof_y >= n)
        throw InputError(fmt::format("probe '{}': DOFs {} and {} must lie in 0 to {} (the response's DOFs)", p.name,
                                     p.dof_x, p.dof_y, n - 1));
    if (!std::isfinite(p.angle_degrees))
        throw InputError(fmt::format("probe '{}': angle = {}; allowed: a finite number of degrees", p.name,
                                     p.angle_degrees));
    const auto [c, s] = cos_sin_degrees(p.angle_degrees);
    if (s == 0.0) return c * Z(p.dof_x);
    if (c == 0.0) return s * Z(p.dof_y);
    return c * Z(p.dof_x) + s * Z(p.dof_y);
}

double probe_amplitude(const Probe& p, const Eigen::VectorXcd& Z) { return std::abs(probe_response(p, Z)); }

Probe probe_at_node(const GyroscopicSystem& sys, const std::string& name, int node, double angle_degrees) {
    const std::vector<int> t = sys.node_translations(node);   // InputError for a node that does not exist
    const auto in_node = [&](int i) { return std::find(t.begin(), t.end(), i) != t.end(); };
    for (const auto& [u, v] : sys.whirl_pairs)
        if (in_node(u) && in_node(v)) return Probe{name, u, v, angle_degrees};
    throw InputError(fmt::format("node {} has no free x and y translations (a support holds x or y, or the model "
                                 "has no lateral motion); allowed: a node with free x and y",
                                 node));
}

std::vector<int> probe_dofs(const std::vector<Probe>& probes) {
    std::vector<int> out;
    for (const Probe& p : probes)
        for (int d : {p.dof_x, p.dof_y})
            if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
    return out;
}

Eigen::MatrixXcd probe_readings(const std::vector<Probe>& probes, const std::vector<int>& dofs,
                                const Eigen::MatrixXcd& Z) {
    const auto column = [&](const Probe& p, int dof) {
        const auto it = std::find(dofs.begin(), dofs.end(), dof);
        if (it == dofs.end())
            throw InputError(fmt::format("probe '{}': DOF {} is not among the response's outputs", p.name, dof));
        return static_cast<int>(it - dofs.begin());
    };
    Eigen::MatrixXcd R(Z.rows(), static_cast<Eigen::Index>(probes.size()));
    for (std::size_t k = 0; k < probes.size(); ++k) {
        // The probe on the columns of Z: the same reading, cos and sin exact at multiples of 90 degrees.
        Probe local = probes[k];
        local.dof_x = column(probes[k], probes[k].dof_x);
        local.dof_y = column(probes[k], probes[k].dof_y);
        for (Eigen::Index i = 0; i < Z.rows(); ++i)
            R(i, static_cast<Eigen::Index>(k)) = probe_response(local, Z.row(i).transpose());
    }
    return R;
}

ProbeOutputs probe_outputs(const GyroscopicSystem& sys, const std::vector<Probe>& probes) {
    ProbeOutputs o;
    o.names = sys.dofs.names;
    o.units = sys.dofs.units;
    o.units.resize(o.names.size());
    for (const Probe& p : probes) {
        o.outputs.push_back(static_cast<int>(o.names.size()));
        o.names.push_back(p.name);
        o.units.push_back("m");
    }
    return o;
}

}  // namespace gyrokit
