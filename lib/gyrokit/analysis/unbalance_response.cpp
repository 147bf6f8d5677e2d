#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/analysis/unbalance_response.hpp>

#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/core/error.hpp>

#include <Eigen/SparseLU>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <numeric>

namespace gyrokit {

namespace {

// An exactly singular dynamic stiffness gives a huge or non-finite solution
// with a large residual: an undamped resonance on the grid, or (with damping) a
// frequency so high that w C is below the rounding of K - w^2 M; a dynamic
// stiffness with entries beyond double precision is a frequency out of range.
void check_solution(double norm_S, double norm_wC, double residual, const Eigen::VectorXcd& Z, const Eigen::VectorXcd& f,
                    double w) {
    if (!std::isfinite(norm_S))
        throw InputError(fmt::format("frequency {:.6g} rad/s: the dynamic stiffness K - w^2 M leaves double "
                                     "precision's range there; allowed: frequencies at which it is finite",
                                     w));
    if (Z.allFinite() && residual <= 1e-8 * (norm_S * Z.norm() + f.norm())) return;
    if (norm_wC > 0.0 && norm_wC < 1e-8 * norm_S)
        throw SolverError(fmt::format("the dynamic stiffness is numerically singular at {:.6g} rad/s: the damping "
                                      "term w C is {:.1e} of K - w^2 M there, below what double precision resolves, "
                                      "so the response cannot be vouched for; move the grid below that frequency",
                                      w, norm_wC / norm_S));
    throw SolverError(fmt::format("the dynamic stiffness is singular at {} rad/s (an undamped resonance): "
                                  "the response is unbounded; add damping or move the grid",
                                  w));
}

}  // namespace

Eigen::VectorXcd dynamic_response(const GyroscopicSystem& sys, double spin, double w, const Eigen::VectorXcd& f,
                                  SolverKind kind) {
    using cd = std::complex<double>;
    const cd l(0.0, w);
    Eigen::VectorXcd Z;
    double norm_S = 0.0, norm_wC = 0.0, residual = 0.0;
    if (resolve_solver_kind(sys.size(), kind) == SolverKind::Dense) {
        const QuadraticPencil q = sys.at_speed(spin);
        const Eigen::MatrixXcd S = q.evaluate(l);
        Z = Eigen::PartialPivLU<Eigen::MatrixXcd>(S).solve(f);
        norm_S = S.norm();
        norm_wC = std::abs(w) * q.C.norm();
        residual = (S * Z - f).norm();
    } else {
        const SparsePencil p = sys.sparse_at_speed(spin);
        const Eigen::SparseMatrix<cd> S = (l * l) * p.M.cast<cd>() + l * p.C.cast<cd>() + p.K.cast<cd>();
        Eigen::SparseLU<Eigen::SparseMatrix<cd>, Eigen::COLAMDOrdering<int>> lu;
        lu.compute(S);
        Z = lu.info() == Eigen::Success ? Eigen::VectorXcd(lu.solve(f))
                                        : Eigen::VectorXcd::Constant(sys.size(), cd(NAN, NAN));
        norm_S = S.norm();
        norm_wC = std::abs(w) * p.C.norm();
        residual = (S * Z - f).norm();
    }
    check_solution(norm_S, norm_wC, residual, Z, f, w);
    return Z;
}

Eigen::VectorXcd unbalance_response(const GyroscopicSystem& sys, double w, SolverKind kind) {
    if (sys.unbalance.size() == 0)
        throw InputError("the model defines no unbalance load; the response is zero");
    if (w == 0.0) return Eigen::VectorXcd::Zero(sys.size());   // no force at standstill
    return dynamic_response(sys, w, w, sys.unbalance_force(w), kind);
}

ResponseCurve unbalance_response(const ResponseSolver& solve, int size, const std::vector<double>& speeds,
                                 const std::vector<int>& dofs) {
    ResponseCurve c;
    c.speeds = speeds;
    c.dofs = dofs;
    if (c.dofs.empty()) {
        c.dofs.resize(static_cast<size_t>(size));
        std::iota(c.dofs.begin(), c.dofs.end(), 0);
    }
    c.Z.resize(static_cast<Eigen::Index>(speeds.size()), static_cast<Eigen::Index>(c.dofs.size()));
    for (size_t i = 0; i < speeds.size(); ++i) {
        throw_if_interrupted();
        const Eigen::VectorXcd z = solve(speeds[i]);
        for (size_t k = 0; k < c.dofs.size(); ++k)
            c.Z(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = z(c.dofs[k]);
    }
    return c;
}

ResponseCurve unbalance_response(const GyroscopicSystem& sys, const std::vector<double>& speeds) {
    return unbalance_response([&](double w) { return unbalance_response(sys, w); }, sys.size(), speeds);
}

std::vector<ResponseMaximum> response_maxima(const ResponseCurve& c, const std::vector<ResponseExtremum>& extrema) {
    std::vector<ResponseMaximum> out;
    const Eigen::Index last = c.Z.rows() - 1;
    for (Eigen::Index col = 0; col < c.Z.cols(); ++col) {
        ResponseMaximum m;
        m.dof = c.dofs[static_cast<size_t>(col)];
        for (const Eigen::Index i : {Eigen::Index(0), last}) {
            if (i < 0) continue;
            const double a = std::abs(c.Z(i, col));
            if (a > m.amplitude || (i == 0 && m.amplitude == 0.0))
                m.amplitude = a, m.speed = c.speeds[static_cast<size_t>(i)];
        }
        for (const auto& e : extrema)
            if (e.dof == m.dof && e.peak && e.amplitude > m.amplitude)
                m.amplitude = e.amplitude, m.speed = e.speed, m.refined = true, m.bounded = e.bounded;
        out.push_back(m);
    }
    return out;
}

std::vector<ResponseExtremum> response_extrema(const GyroscopicSystem& sys, const ResponseCurve& c) {
    return response_extrema([&](double w) { return unbalance_response(sys, w); }, c);
}

namespace {

// Near a resonance |Z| ~ C / sqrt((w - w0)^2 + g^2) (g = zeta w0). Brent returns a
// speed w within its resolution r of w0, so sqrt((w - w0)^2 + g^2) is what the peak
// height says about g; with h = 10 r,
//   (1/A(w+h)^2 + 1/A(w-h)^2) / 2 - 1/A(w)^2 = h^2 / C^2,
// so the peak is resolved (its half-width above h) where that difference stays
// below 1/A(w)^2. A singular solve within h: unresolved.
template <class Amplitudes>
bool peak_is_resolved(Amplitudes& amplitudes, Eigen::Index col, double w) {
    const double h = 10.0 * smooth_minimum_resolution(w);
    const Eigen::VectorXd a = amplitudes(w), lo = amplitudes(w - h), hi = amplitudes(w + h);
    if (!a.size() || !lo.size() || !hi.size()) return false;
    if (!(lo(col) > 0.0 && hi(col) > 0.0)) return true;   // an exact zero beside it: no resonance
    const double inv = 1.0 / (a(col) * a(col));
    const double spread = 0.5 * (1.0 / (lo(col) * lo(col)) + 1.0 / (hi(col) * hi(col))) - inv;
    return spread < inv;
}

}  // namespace

std::vector<ResponseExtremum> response_extrema(const ResponseSolver& solve, const ResponseCurve& c, bool peaks_only) {
    // |Z| of the curve's DOFs at each speed solved (empty: singular there).
    std::map<double, Eigen::VectorXd> solved;
    const auto amplitudes = [&](double w) -> const Eigen::VectorXd& {
        auto it = solved.find(w);
        if (it != solved.end()) return it->second;
        Eigen::VectorXd a;
        throw_if_interrupted();
        try {
            const Eigen::VectorXcd Z = solve(w);
            a.resize(static_cast<Eigen::Index>(c.dofs.size()));
            for (size_t k = 0; k < c.dofs.size(); ++k) a(static_cast<Eigen::Index>(k)) = std::abs(Z(c.dofs[k]));
        } catch (const SolverError&) {   // exactly on an undamped resonance
        }
        return solved.emplace(w, std::move(a)).first->second;
    };
    std::vector<ResponseExtremum> out;
    const Eigen::Index ns = c.Z.rows();
    // A DOF whose response is zero (by symmetry) shows rounding noise: its wiggles are no peaks.
    const double floor = 1e-9 * (c.Z.size() ? c.Z.cwiseAbs().maxCoeff() : 0.0);
    for (Eigen::Index col = 0; col < c.Z.cols(); ++col) {
        const int k = c.dofs[static_cast<size_t>(col)];
        for (Eigen::Index i = 1; i + 1 < ns; ++i) {
            const double a0 = std::abs(c.Z(i - 1, col)), a1 = std::abs(c.Z(i, col)), a2 = std::abs(c.Z(i + 1, col));
            const bool peak = a1 > a0 && a1 >= a2, dip = a1 < a0 && a1 <= a2;
            if (!peak && !(dip && !peaks_only)) continue;
            if (std::max({a0, a1, a2}) <= floor) continue;
            const double s = peak ? -1.0 : 1.0;
            const auto f = [&](double w) {
                const Eigen::VectorXd& a = amplitudes(w);
                return a.size() ? s * a(col) : s * std::numeric_limits<double>::infinity();
            };
            // A peak is smooth (Brent); an antiresonance may be a V-shaped kink at zero (golden section).
            const double lo = c.speeds[static_cast<size_t>(i - 1)], hi = c.speeds[static_cast<size_t>(i + 1)];
            const double w = peak ? find_smooth_minimum(f, lo, c.speeds[static_cast<size_t>(i)], hi, 1e-12)
                                  : find_minimum(f, lo, hi, 1e-12);
            ResponseExtremum e{k, peak, w, s * f(w)};
            if (peak) e.bounded = peak_is_resolved(amplitudes, col, w);
            if (!e.bounded) e.amplitude = std::numeric_limits<double>::infinity();
            out.push_back(e);
        }
    }
    return out;
}

}  // namespace gyrokit
