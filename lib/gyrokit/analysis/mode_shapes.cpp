#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/mode_shapes.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/constants.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <map>
#include <string>
#include <cmath>

namespace gyrokit {

Orbit orbit_of(std::complex<double> u, std::complex<double> v) {
    const std::complex<double> i(0.0, 1.0);
    const std::complex<double> f = 0.5 * (u + i * v), b = 0.5 * (std::conj(u) + i * std::conj(v));
    Orbit o;
    o.major = std::abs(f) + std::abs(b);
    o.minor = std::abs(std::abs(f) - std::abs(b));
    o.phase = std::abs(u) > 0.0 ? std::arg(u) : 0.0;
    if (o.major == 0.0) return o;
    // |f e^{it} + b e^{-it}| is largest where both circles point the same way:
    // arg f + t = arg b - t. A circle has no major axis: angle 0.
    const double small = kWhirlTolerance * o.major;
    double a = std::abs(f) > small && std::abs(b) > small ? 0.5 * (std::arg(f) + std::arg(b)) : 0.0;
    const double pi = kPi;
    while (a > pi / 2) a -= pi;
    while (a <= -pi / 2) a += pi;
    o.angle = a;
    if (o.minor <= kWhirlTolerance * o.major)
        o.whirl = Whirl::Planar;
    else
        o.whirl = std::abs(f) > std::abs(b) ? Whirl::Forward : Whirl::Backward;
    return o;
}

ModeShape mode_shape(const Mode& m, const GyroscopicSystem& sys) {
    const int n = sys.size();
    if (m.right.size() != n)
        throw Error("mode_shape: the eigenvector has " + std::to_string(m.right.size()) + " entries, the system " +
                    std::to_string(n) + " DOFs");
    ModeShape s;
    s.mode = m;
    // Reference: the largest entry among the DOFs in metres, unless those hold only
    // rounding (a pure tilt mode), else the largest of all. Entries equal to 1e-9
    // (x and y of a circular orbit) are a tie: the first DOF wins, not the rounding.
    const double top = m.right.size() ? m.right.cwiseAbs().maxCoeff() : 0.0;
    const auto largest_of = [&](bool metres_only) {
        const auto counts = [&](int i) { return !metres_only || sys.dofs.units[static_cast<size_t>(i)] == "m"; };
        double largest = -1.0;
        for (int i = 0; i < n; ++i)
            if (counts(i)) largest = std::max(largest, std::abs(m.right(i)));
        for (int i = 0; i < n; ++i)
            if (counts(i) && std::abs(m.right(i)) >= (1.0 - kTieTolerance) * largest) {
                s.reference = i;
                break;
            }
        return largest;
    };
    double largest = -1.0;
    if (static_cast<int>(sys.dofs.units.size()) == n) largest = largest_of(true);
    if (largest < kWhirlTolerance * top) largest = largest_of(false);
    s.shape = largest > 0.0 ? Eigen::VectorXcd(m.right / m.right(s.reference)) : m.right;
    const bool has_nodes = static_cast<int>(sys.dofs.nodes.size()) == n;
    // A pair whose entries are below 1e-9 of the largest entry of its unit is at rest (a node
    // of the mode, zero by symmetry): its computed orbit is rounding, and its angle
    // and phase would be noise. It is given as no motion.
    const auto unit_of = [&](int i) { return sys.dofs.units.empty() ? std::string() : sys.dofs.units[static_cast<size_t>(i)]; };
    std::map<std::string, double> largest_in;   // over every DOF of the unit, paired or not
    for (int i = 0; i < n; ++i) {
        double& l = largest_in[unit_of(i)];
        l = std::max(l, std::abs(s.shape(i)));
    }
    for (const auto& [u, v] : sys.whirl_pairs) {
        PairOrbit p;
        p.u = u;
        p.v = v;
        p.name = sys.dofs.names[static_cast<size_t>(u)] + "/" + sys.dofs.names[static_cast<size_t>(v)];
        if (!sys.dofs.units.empty()) p.unit = sys.dofs.units[static_cast<size_t>(u)];
        if (has_nodes) {
            p.node = sys.dofs.nodes[static_cast<size_t>(u)];
            if (p.node >= 0) p.z = sys.node_z[static_cast<size_t>(p.node)];
        }
        const bool at_rest =
            std::max(std::abs(s.shape(u)), std::abs(s.shape(v))) <= kRestTolerance * largest_in[unit_of(u)];
        p.orbit = at_rest ? Orbit{} : orbit_of(s.shape(u), s.shape(v));
        s.orbits.push_back(p);
    }
    // Along the axis: by node (pairs without a node last), the model's order within a node.
    std::stable_sort(s.orbits.begin(), s.orbits.end(), [](const PairOrbit& a, const PairOrbit& b) {
        const int na = a.node < 0 ? INT_MAX : a.node, nb = b.node < 0 ? INT_MAX : b.node;
        return na < nb;
    });
    return s;
}

std::vector<ModeShape> mode_shapes(const QuadraticSpectrum& s, const GyroscopicSystem& sys) {
    std::vector<ModeShape> out;
    out.reserve(s.modes.size());
    for (const auto& m : s.modes) {
        out.push_back(mode_shape(m, sys));
        out.back().number = static_cast<int>(out.size());
    }
    return out;
}

std::vector<ModeShape> mode_shapes(const GyroscopicSystem& sys, double w, const SolverOptions& options,
                                   std::vector<std::string>* notes) {
    if (!std::isfinite(w) || w < 0.0)
        throw InputError("mode shapes: speed = " + std::to_string(w) + " rad/s; allowed: a finite number >= 0");
    const SolverChoice plan = choose_solver(sys, options);
    QuadraticSpectrum spectrum = plan.make()(w);
    // The meaning of K: the K lowest by frequency (a sparse window may hold one more where
    // its edge cuts a double eigenvalue).
    if (const std::size_t all = keep_lowest_modes(spectrum, options.modes); all > spectrum.modes.size() && notes)
        notes->push_back(fmt::format("the {} lowest by frequency of the {} modes computed ({} 0 lists all)",
                                     options.modes, all, option_field("modes")));
    if (notes) {
        notes->insert(notes->end(), plan.notes.begin(), plan.notes.end());
        notes->insert(notes->end(), spectrum.notes.begin(), spectrum.notes.end());
    }
    return mode_shapes(spectrum, sys);
}

}  // namespace gyrokit
