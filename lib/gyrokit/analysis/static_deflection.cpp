#include <gyrokit/analysis/static_deflection.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/numerics/sparse_block.hpp>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

namespace gyrokit {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// The lateral DOFs of the rotor without its supports: every node's x, y, tx, ty, then the pedestals'.
struct FreeBody {
    FeRotorMatrices m;
    std::map<std::string, int> index;
    int at(const std::string& prefix, int node) const {
        const auto it = index.find(prefix + std::to_string(node));
        return it == index.end() ? -1 : it->second;
    }
};

// Which DOFs are held, and by which support or rigid node (its reaction's owner).
struct Holds {
    std::vector<int> dofs;
    std::map<int, std::size_t> owner;       // held DOF -> reaction index
    std::vector<StaticReaction> reactions;  // one per support and rigid node
};

Holds holds_of(const FeRotor& r, const StaticOptions& o, const FreeBody& b) {
    Holds h;
    const auto hold = [&](std::size_t owner, const char* prefix, int node) {
        const int i = b.at(prefix, node);
        if (i >= 0 && h.owner.emplace(i, owner).second) h.dofs.push_back(i);
    };
    for (std::size_t s = 0; s < r.supports.size(); ++s) {
        const FeSupport& sp = r.supports[s];
        h.reactions.push_back({fmt::format("support {}", s + 1), sp.node, 0, 0, 0, 0, 0});
        if (sp.x) hold(s, "x", sp.node);
        if (sp.y) hold(s, "y", sp.node);
        if (sp.theta_x) hold(s, "tx", sp.node);
        if (sp.theta_y) hold(s, "ty", sp.node);
    }
    for (std::size_t k = 0; k < o.rigid.size(); ++k) {
        const int node = o.rigid[k].node;
        if (node < 0 || node >= r.node_count())
            throw InputError(fmt::format("static analysis: rigid hold {} at node {}; allowed: 0 to {}", k + 1, node,
                                         r.node_count() - 1));
        h.reactions.push_back({o.rigid[k].name.empty() ? fmt::format("rigid {}", k + 1) : o.rigid[k].name, node, 0, 0, 0,
                               0, 0});
        hold(h.reactions.size() - 1, "x", node);
        hold(h.reactions.size() - 1, "y", node);
    }
    std::sort(h.dofs.begin(), h.dofs.end());
    return h;
}

// The consistent weight and the point loads.
Eigen::VectorXd loads_of(const FeRotor& r, const StaticOptions& o, const FreeBody& b, double& weight) {
    const int n = b.m.size();
    Eigen::VectorXd lift = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i)
        if (b.m.dofs.vertical_translation(i)) lift(i) = 1.0;
    const Eigen::VectorXd Mr = b.m.M * lift;
    weight = o.gravity * lift.dot(Mr);
    Eigen::VectorXd f = -o.gravity * Mr;
    for (std::size_t k = 0; k < o.loads.size(); ++k) {
        const StaticLoad& l = o.loads[k];
        if (l.node < 0 || l.node >= r.node_count())
            throw InputError(fmt::format("static analysis: load {} at node {}; allowed: 0 to {}", k, l.node,
                                         r.node_count() - 1));
        // Beyond 1e15 N the deflections' squares leave double precision's range (and no machine bears it).
        for (const double v : {l.fx, l.fy, l.mx, l.my})
            if (!(std::abs(v) <= kMaxStaticLoad) || (v != 0.0 && std::abs(v) < std::numeric_limits<double>::min()))
                throw InputError(fmt::format("static analysis: load {} at node {} has the component {}; allowed: "
                                             "finite magnitudes up to {:g} (N, N m), 0 or at least 2.2e-308",
                                             k, l.node, v, kMaxStaticLoad));
        f(b.at("x", l.node)) += l.fx;
        f(b.at("y", l.node)) += l.fy;
        f(b.at("tx", l.node)) += l.mx;
        f(b.at("ty", l.node)) += l.my;
    }
    return f;
}

// End forces of each element in the plane conventions of StaticSection.
void add_sections(const FeRotor& r, const FreeBody& b, const Eigen::VectorXd& u, double g, StaticResult& out) {
    double z = 0.0;
    for (std::size_t e = 0; e < r.elements.size(); ++e) {
        const FeShaftElement& el = r.elements[e];
        const FeElementMatrices em = fe_shaft_element_matrices(el, r.shear_deformation, r.rotary_inertia);
        Eigen::Matrix<double, 8, 1> ue, lift;
        const char* prefix[4] = {"x", "y", "tx", "ty"};
        for (int k = 0; k < 8; ++k) ue(k) = u(b.at(prefix[k % 4], static_cast<int>(e) + k / 4));
        lift << 0, 1, 0, 0, 0, 1, 0, 0;
        // Forces and moments the nodes exert on the element, its own weight taken off.
        const Eigen::Matrix<double, 8, 1> F = em.K * ue + g * (em.M * lift);
        const double z1 = z + el.length;
        out.sections.push_back({static_cast<int>(e), z, F(0), -F(3), F(1), F(2)});
        out.sections.push_back({static_cast<int>(e), z1, -F(4), F(7), -F(5), -F(6)});
        z = z1;
    }
}

// The displacements: K u = f on the DOFs the holds leave free (held ones stay 0), with
// the solve's backward error, condition estimate and error bound in out; InputError for
// a rotor free to move.
Eigen::VectorXd solve_displacements(const FreeBody& b, const Holds& h, const Eigen::VectorXd& f, StaticResult& out) {
    std::vector<int> free;
    for (int i = 0, k = 0; i < b.m.size(); ++i) {
        if (k < static_cast<int>(h.dofs.size()) && h.dofs[k] == i)
            ++k;
        else
            free.push_back(i);
    }
    Eigen::VectorXd u = Eigen::VectorXd::Zero(b.m.size());
    if (!free.empty()) {
        const SpMat Kff = submatrix(b.m.K, free, free);
        const Eigen::VectorXd ff = f(free);
        Eigen::SparseLU<SpMat> lu;
        lu.compute(Kff);
        Eigen::VectorXd uf = lu.info() == Eigen::Success ? Eigen::VectorXd(lu.solve(ff)) : Eigen::VectorXd();
        const double denom = Kff.norm() * (uf.size() ? uf.norm() : 0.0) + ff.norm();
        out.backward_error = uf.size() && uf.allFinite() ? (Kff * uf - ff).norm() / std::max(denom, 1e-300) : INFINITY;
        // ||Kff^-1|| from a few steps of inverse iteration (a lower bound that a free rigid
        // motion, a pivot at rounding level, drives to 1 / eps): the condition number bounds
        // the relative error of u by cond * backward error.
        double inverse = 0.0;
        if (lu.info() == Eigen::Success) {
            Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(Kff.rows(), 1.0, 2.0);
            v /= v.norm();
            for (int k = 0; k < 8 && std::isfinite(inverse); ++k) {
                v = lu.solve(v);
                inverse = v.norm();
                v /= inverse;
            }
        }
        out.condition = Kff.norm() * inverse;
        out.error_bound = out.condition * out.backward_error;
        // A rotor free to fall, tip or slide sideways has no static solution.
        if (!(out.backward_error <= 1e-10) || !(out.error_bound <= 1e-4))
            throw InputError("static analysis: the rotor is not held: its bearings and supports leave it free to "
                             "move in the horizontal or vertical plane; allowed: bearings or supports that hold it in "
                             "both planes (at least two positions, or one clamped)");
        u(free) = uf;
    }
    return u;
}

}  // namespace

StaticResult fe_static(const FeRotor& rotor, const StaticOptions& o) {
    if (!rotor.has_lateral())
        throw InputError(fmt::format("static analysis: the model's motion is {}; allowed: lateral or all (the "
                                     "weight bends the shaft)",
                                     to_string(rotor.motion)));
    if (!(o.gravity >= 0 && o.gravity <= kMaxGravity) ||
        (o.gravity != 0.0 && o.gravity < std::numeric_limits<double>::min()))
        throw InputError(fmt::format("static analysis: {} {}; allowed: 0 (no weight) or 2.2250738585072014e-308 to "
                                     "{:g} (m/s^2)",
                                     option_field("gravity"), o.gravity, kMaxGravity));
    FeRotor q = rotor;
    q.motion = FeMotion::lateral;   // the weight moves no axial or torsional DOF
    q.supports.clear();
    FreeBody b{q.assemble(), {}};
    for (int i = 0; i < b.m.size(); ++i) b.index[b.m.dofs.names[i]] = i;
    Holds h = holds_of(rotor, o, b);
    StaticResult out;
    const Eigen::VectorXd f = loads_of(rotor, o, b, out.weight);

    const Eigen::VectorXd u = solve_displacements(b, h, f, out);

    // Reactions: of the held DOFs, K u - f; of each constant bearing, its spring force.
    const Eigen::VectorXd Ku = b.m.K * u;
    const char* prefix[4] = {"x", "y", "tx", "ty"};
    for (const auto& [dof, owner] : h.owner) {
        StaticReaction& rr = h.reactions[owner];
        const double R = Ku(dof) - f(dof);
        for (int k = 0; k < 4; ++k)
            if (b.at(prefix[k], rr.node) == dof) (k == 0 ? rr.fx : k == 1 ? rr.fy : k == 2 ? rr.mx : rr.my) = R;
    }
    const auto pedestal_at = [&](int node) {
        for (std::size_t p = 0; p < rotor.pedestals.size(); ++p)
            if (rotor.pedestals[p].node == node) return static_cast<int>(p);
        return -1;
    };
    double sum_x = 0, sum_y = 0;
    for (std::size_t i = 0; i < rotor.bearings.size(); ++i) {
        const FeBearing& br = rotor.bearings[i];
        const int p = pedestal_at(br.node);
        const double dx = u(b.at("x", br.node)) - (p >= 0 ? u(b.at("px", br.node)) : 0.0);
        const double dy = u(b.at("y", br.node)) - (p >= 0 ? u(b.at("py", br.node)) : 0.0);
        const std::string name = i < o.bearing_names.size() ? o.bearing_names[i] : fmt::format("bearing {}", i + 1);
        StaticReaction rr{name, br.node, 0, -(br.kxx * dx + br.kxy * dy),
                          -(br.kyx * dx + br.kyy * dy), 0, 0};
        if (p < 0) sum_x += rr.fx, sum_y += rr.fy;   // on a pedestal: a force inside the supported body
        out.reactions.push_back(rr);
    }
    for (std::size_t i = 0; i < rotor.pedestals.size(); ++i) {
        const FePedestal& pd = rotor.pedestals[i];
        StaticReaction rr{fmt::format("pedestal {}", i + 1), pd.node, 0, -pd.kxx * u(b.at("px", pd.node)),
                          -pd.kyy * u(b.at("py", pd.node)), 0, 0};
        sum_x += rr.fx, sum_y += rr.fy;
        out.reactions.push_back(rr);
    }
    for (const StaticReaction& rr : h.reactions) {
        sum_x += rr.fx, sum_y += rr.fy;
        out.reactions.push_back(rr);
    }
    double applied = out.weight;
    for (const StaticLoad& l : o.loads) {
        sum_x += l.fx, sum_y += l.fy;
        applied += std::abs(l.fx) + std::abs(l.fy);
    }
    sum_y -= out.weight;
    out.balance_error = applied > 0 ? std::hypot(sum_x, sum_y) / applied : 0.0;

    const std::vector<double>& zs = b.m.node_z;
    for (StaticReaction& rr : out.reactions) rr.z = zs[rr.node];
    for (int n = 0; n < rotor.node_count(); ++n)
        out.nodes.push_back({n, zs[n], u(b.at("x", n)), u(b.at("y", n)), u(b.at("ty", n)), -u(b.at("tx", n))});
    add_sections(q, b, u, o.gravity, out);
    return out;
}

}  // namespace gyrokit
