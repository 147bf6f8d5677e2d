// Stage 1 of the dense solve by QZ: the scaled companion form of each uncoupled
// DOF group through LAPACK's dggev3 (or dggev), eigenpairs back in the original
// coordinates with their backward errors on the whole pencil.
#include "gyrokit/eig/detail/dense_stages.hpp"

#include "gyrokit/eig/lapack.hpp"

#include <algorithm>
#include <cmath>

namespace gyrokit::dense {

using cd = std::complex<double>;

namespace {

// `scaling` and `scale`: a group's, the whole pencil's (qz_eigenpairs).
QuadraticSpectrum solve_qz(const QuadraticPencil& original, bool want_left, bool classic,
                           const CompanionScaling* scaling = nullptr, double scale = 0.0, bool reversible = true) {
    const int n = static_cast<int>(original.M.rows());
    const PencilAction action = action_of(original);   // backward errors refer to the original problem
    Companion c = scaling ? companion(original, *scaling) : companion(original);
    const Eigen::VectorXd& t = c.t;
    const double gamma = c.gamma;
    GeneralizedEigen ge = lapack_dggev(std::move(c.A), std::move(c.B), want_left, classic);

    QuadraticSpectrum s;
    s.scale = scale > 0.0 ? scale : natural_scale(original);
    s.real_tol = 1e-7 * s.scale;   // about sqrt(eps) times the scale: rigid-body pairs land here
    for (int j = 0; j < 2 * n; ++j) {
        const cd alpha = ge.alpha(j);
        const double beta = ge.beta(j);
        if (infinite(alpha, beta)) {
            ++s.infinite_count;
            continue;
        }
        Mode m;
        m.lambda = gamma * alpha / beta;
        if (m.lambda.imag() < -1e-7 * std::max(std::abs(m.lambda), s.scale)) continue;  // conjugate
        // Either block of [mu x; x] gives x; keep the one with the smaller backward error.
        // Back to the original coordinates; backward errors refer to the original problem.
        const Eigen::VectorXcd top = t.asDiagonal() * ge.right.col(j).head(n);
        const Eigen::VectorXcd bottom = t.asDiagonal() * ge.right.col(j).tail(n);
        const double et = backward_error(action, m.lambda, top), eb = backward_error(action, m.lambda, bottom);
        const bool use_top = top.norm() > 0.0 && (bottom.norm() == 0.0 || et < eb);
        m.right = unit_vector(use_top ? top : bottom);
        m.backward_error = backward_error(action, m.lambda, m.right);
        if (want_left) m.left = unit_vector(t.asDiagonal() * ge.left.col(j).head(n));
        s.modes.push_back(std::move(m));
    }
    // Eigenvalues at infinity beyond what M's null space allows are finite ones
    // beyond the scaled pencil's resolution: taken from the reversed pencil.
    if (reversible && s.infinite_count > 0) {
        const int lost = s.infinite_count - infinite_limit(original);
        if (lost > 0) {
            for (Mode& m : largest_by_reversal(original, lost, want_left, classic)) {
                s.infinite_count -= m.lambda.imag() == 0.0 ? 1 : 2;
                s.modes.push_back(std::move(m));
            }
        }
    }
    return s;
}

}  // namespace

std::vector<Mode> largest_by_reversal(const QuadraticPencil& p, int lost, bool want_left, bool classic) {
    const QuadraticPencil reversed{p.K, p.C, p.M};
    QuadraticSpectrum r = solve_qz(reversed, want_left, classic, nullptr, 0.0, false);
    std::sort(r.modes.begin(), r.modes.end(),
              [](const Mode& a, const Mode& b) { return std::abs(a.lambda) < std::abs(b.lambda); });
    const PencilAction action = action_of(p);
    std::vector<Mode> out;
    int counted = 0;
    for (Mode& m : r.modes) {
        if (counted >= lost) break;
        if (!(std::abs(m.lambda) > 1e-12 * r.scale)) continue;   // nu = 0: lambda truly infinite
        const bool real = std::abs(m.lambda.imag()) <= 1e-7 * std::abs(m.lambda);
        counted += real ? 1 : 2;
        // nu in the upper half plane is lambda = 1/nu in the lower: its conjugate.
        m.lambda = real ? cd(1.0 / m.lambda.real(), 0.0) : std::conj(1.0 / m.lambda);
        if (!real) {
            m.right = m.right.conjugate();
            if (want_left) m.left = m.left.conjugate();
        }
        m.backward_error = backward_error(action, m.lambda, m.right);
        out.push_back(std::move(m));
    }
    return out;
}

// Every uncoupled group by solve_qz (the QZ's cost is cubic in the size: ROSS's
// 42 DOFs as groups of 28, 7 and 7 cost a third), the vectors zero outside their
// group, backward errors on the whole pencil; as solve_qz where all are coupled.
QuadraticSpectrum qz_eigenpairs(const QuadraticPencil& p, bool want_left, bool classic) {
    const std::vector<std::vector<Eigen::Index>> groups = uncoupled_groups(p);
    if (groups.size() <= 1) return solve_qz(p, want_left, classic);
    const Eigen::Index n = p.M.rows();
    const PencilAction action = action_of(p);
    QuadraticSpectrum s;
    s.scale = natural_scale(p);
    s.real_tol = 1e-7 * s.scale;
    const CompanionScaling whole = companion_scaling(p);
    for (const std::vector<Eigen::Index>& g : groups) {
        CompanionScaling own = whole;
        own.t = Eigen::VectorXd(whole.t(g));
        QuadraticSpectrum part = solve_qz(restricted(p, g), want_left, classic, &own, s.scale);
        s.infinite_count += part.infinite_count;
        for (Mode& m : part.modes) {
            Eigen::VectorXcd x = Eigen::VectorXcd::Zero(n), y = Eigen::VectorXcd::Zero(want_left ? n : 0);
            for (size_t k = 0; k < g.size(); ++k) {
                x[g[k]] = m.right[static_cast<Eigen::Index>(k)];
                if (want_left) y[g[k]] = m.left[static_cast<Eigen::Index>(k)];
            }
            m.right = std::move(x);
            m.left = std::move(y);
            m.backward_error = backward_error(action, m.lambda, m.right);
            s.modes.push_back(std::move(m));
        }
    }
    return s;
}

}  // namespace gyrokit::dense
