#include <gyrokit/eig/quadratic_eigensolver.hpp>

#include <gyrokit/core/error.hpp>
#include "gyrokit/eig/detail/dense_stages.hpp"
#include "gyrokit/eig/lapack.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>

namespace gyrokit {

using cd = std::complex<double>;
using namespace dense;

void split_rigid_body(std::vector<Mode>& modes, std::vector<Mode>& rigid_body, const PencilAction& pencil,
                      double scale) {
    std::vector<Mode> kept;
    for (auto& m : modes) (is_rigid_body(m.lambda, m.right, pencil, scale) ? rigid_body : kept).push_back(std::move(m));
    modes = std::move(kept);
}

double QuadraticSpectrum::max_backward_error() const {
    double e = 0.0;
    for (const auto& m : modes) e = std::max(e, m.backward_error);
    return e;
}

double backward_error(const QuadraticPencil& p, cd lambda, const Eigen::VectorXcd& x) {
    return backward_error(action_of(p), lambda, x);
}

namespace {

void require_finite(const QuadraticPencil& p) {
    if (!p.M.allFinite() || !p.C.allFinite() || !p.K.allFinite())
        throw InputError("the pencil has a NaN or infinite coefficient");
}

// Stage 1: the raw eigenpairs (upper half plane and real axis, both vectors).
QuadraticSpectrum eigenpairs(const QuadraticPencil& p, EigenMethod method) {
    QuadraticSpectrum s = method == EigenMethod::StateMatrix
                              ? state_matrix_eigenpairs(p)
                              : qz_eigenpairs(p, true, method == EigenMethod::ClassicQZ);
    s.method = method == EigenMethod::ScaledQZ    ? "scaled QZ"
               : method == EigenMethod::ClassicQZ ? "scaled classic QZ"
                                                  : "state matrix";
    return s;
}

// Stage 2 (QZ): an answer QZ cannot stand behind is no answer. Every eigenvalue
// infinite for an M that is not zero, or a pair far from any eigenpair (QZ's are
// about 1e-15), happen only where the pencil's scales span more than double
// precision resolves (a speed of 1e150 rad/s on a rotor whose |K| is 1e4). The
// state-matrix method says instead which eigenvalues it cannot vouch for.
void refuse_unresolvable(const QuadraticSpectrum& s, const QuadraticPencil& p) {
    double worst = 0.0;
    for (const Mode& m : s.modes) worst = std::max(worst, m.backward_error);
    const bool all_infinite = s.modes.empty() && s.infinite_count > 0 && p.M.norm() > 0.0;
    // How far the damping-gyroscopic term outweighs the balance of mass and stiffness
    // at the natural frequency g: beyond 1e12 (1e150 rad/s on a rotor) no scaling
    // brings the terms to one level, and a pair with a large backward error is
    // rounding, not a mode. A small term (light damping, a liquid's tiny masses)
    // is no such case: its pairs stay, with bounds that say what they are worth.
    const double g = s.scale;
    const double spread = g * p.C.norm() / (g * g * p.M.norm() + p.K.norm());
    if (all_infinite || !std::isfinite(spread) || (spread > 1e12 && !(worst <= kDenseVerifyTolerance)))
        throw SolverError(fmt::format(
            "the eigensolver cannot vouch for this pencil: {}; its coefficients span more than double precision "
            "resolves (|M| = {:.3g}, |C| = {:.3g}, |K| = {:.3g}); allowed: speeds and parameters whose pencil "
            "stays within about 1e12 of its natural scale",
            all_infinite ? fmt::format("all {} eigenvalues came out infinite", s.infinite_count)
                         : fmt::format("an eigenpair with backward error {:.2g}, above {:.0e}", worst,
                                       kDenseVerifyTolerance),
            p.M.norm(), p.C.norm(), p.K.norm()));
}

// Stage 3: one of each conjugate pair (the upper half plane), eigenvalues within
// the real-axis tolerance put on it, each mode's whirl.
void keep_upper_half_plane(QuadraticSpectrum& s, const std::vector<std::pair<int, int>>& whirl_pairs) {
    std::vector<Mode> kept;
    for (auto& m : s.modes) {
        if (std::abs(m.lambda) <= s.real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        if (m.lambda.imag() < -s.real_tol) continue;
        m.whirl = classify_whirl(m.lambda, m.right, whirl_pairs, s.real_tol);
        kept.push_back(std::move(m));
    }
    s.modes = std::move(kept);
}

// Stage 7: a printed eigenvalue lies within its printed bound; one whose bound
// exceeds kVouchTolerance of its modulus (and the real-axis tolerance) is not
// vouched for, and the spectrum says so.
void note_unvouched(QuadraticSpectrum& s, EigenMethod method) {
    const auto loose = std::count_if(s.modes.begin(), s.modes.end(), [&](const Mode& m) {
        return !(m.error_bound <= std::max(kVouchTolerance * std::abs(m.lambda), s.real_tol));
    });
    if (loose > 0)
        s.notes.push_back(fmt::format("{} of {} eigenvalues have an error bound above {} of their modulus: the {} "
                                      "method cannot vouch for them{}",
                                      loose, s.modes.size(), kVouchTolerance, s.method,
                                      method == EigenMethod::StateMatrix
                                          ? "; use the QZ method (" + option_field("method") + " qz)"
                                          : " (see the error_bound column)"));
}

}  // namespace

namespace {

// The dense solve by one method, stage by stage.
QuadraticSpectrum solve_by(const QuadraticPencil& p, EigenMethod method, bool left_vectors,
                           const std::vector<std::pair<int, int>>& whirl_pairs) {
    // 1. Raw eigenpairs with left and right vectors (both give the error bounds).
    QuadraticSpectrum s = eigenpairs(p, method);
    // 2. Refuse what no scaling resolves.
    if (method != EigenMethod::StateMatrix) refuse_unresolvable(s, p);
    // 3. The upper half plane, real eigenvalues on the axis, whirl.
    keep_upper_half_plane(s, whirl_pairs);
    // 4. Error bounds on the DOF-scaled pencil (as QZ solves it): stiff supports do
    //    not inflate them. Left vectors then kept only where asked for.
    const PencilAction action = action_of(p);
    const Eigen::VectorXd t = dof_scaling(p);
    set_error_bounds(s.modes, action, scaled_norms(p, t), t);
    if (!left_vectors)
        for (Mode& m : s.modes) m.left.resize(0);
    // 5. Rigid-body eigenvalues apart from the modes.
    split_rigid_body(s.modes, s.rigid_body, action, s.scale);
    // 6. The two whirls of a double eigenvalue (an isotropic rotor) separated.
    separate_double_whirl(s.modes, whirl_pairs, s.real_tol, action);
    // 7. By frequency; what is not vouched for said.
    sort_by_frequency(s.modes);
    note_unvouched(s, method);
    return s;
}

// Auto keeps the state matrix's spectrum only where every pair (modes and rigid-body
// eigenvalues) is verified on the quadratic to the sparse solver's tolerance and every
// mode's bound is within kVouchTolerance of its modulus: the real-axis tolerance, which
// vouches for a small eigenvalue on a stiff pencil, is not enough here, as QZ may bound
// such a mode more tightly (a double pair at standstill on 1e20 N/m supports: 3e-6
// relative by the state matrix) (docs/numerics.md, "The default dense method").
bool state_spectrum_holds(const QuadraticSpectrum& s) {
    const auto verified = [](const Mode& m) { return m.backward_error <= kStateVerifyTolerance; };
    const auto vouched = [](const Mode& m) { return m.error_bound <= kVouchTolerance * std::abs(m.lambda); };
    return s.notes.empty() && std::all_of(s.modes.begin(), s.modes.end(), verified) &&
           std::all_of(s.modes.begin(), s.modes.end(), vouched) &&
           std::all_of(s.rigid_body.begin(), s.rigid_body.end(), verified);
}

}  // namespace

QuadraticSpectrum solve_quadratic(const QuadraticPencil& p, const EigenOptions& opt,
                                  const std::vector<std::pair<int, int>>& whirl_pairs) {
    require_finite(p);
    if (opt.method != EigenMethod::Auto) return solve_by(p, opt.method, opt.left_vectors, whirl_pairs);
    // Auto: the state matrix where it is the faster (from kAutoStateDofs DOFs: 0.42 of
    // QZ's time at 240, docs/benchmarks.md) and its answer holds; QZ where M is singular
    // to rounding, a pair stays unverified or a bound loose, and on small pencils. A
    // pencil of uncoupled groups (the two planes of a rotor at standstill) goes to QZ group
    // by group: smaller solves, and each vector stays in its group, where the state
    // matrix's reduction mixes the groups at rounding level (a pair split across two
    // planes by less than its bound would then read as whirling instead of planar).
    if (p.M.rows() >= kAutoStateDofs && uncoupled_groups(p).size() <= 1) {
        try {
            QuadraticSpectrum s = solve_by(p, EigenMethod::StateMatrix, opt.left_vectors, whirl_pairs);
            if (state_spectrum_holds(s)) return s;
        } catch (const SolverError&) {
            // M (scaled) singular: QZ solves such pencils.
        }
    }
    return solve_by(p, EigenMethod::ScaledQZ, opt.left_vectors, whirl_pairs);
}

namespace {

// The eigenvalues from the state matrix where M is positive definite and well
// conditioned: with T M T = L L^T (t = dof_scaling) and z = L^T x / t, the matrix
// [0, I; -L^-1 K L^-T / g^2, -L^-1 C L^-T / g] in mu = lambda / g (g the natural scale),
// whose QR without vectors costs about 60 % of the QZ's (ROSS's 42 DOFs: 1.4 against
// 2.4 ms). Empty where M is not symmetric positive definite with an estimated
// reciprocal condition above 1e-8 (then QZ): a badly conditioned M would cost the
// small eigenvalues their accuracy.
std::optional<Eigen::VectorXcd> state_matrix_values(const QuadraticPencil& original, double g,
                                                    const Eigen::VectorXd* scaling = nullptr) {
    const Eigen::Index n = original.M.rows();
    const Eigen::VectorXd t = scaling ? *scaling : dof_scaling(original);
    const Eigen::MatrixXd M = t.asDiagonal() * original.M * t.asDiagonal();
    if (!(original.M == original.M.transpose())) return std::nullopt;   // LLT reads one triangle
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success || !(llt.rcond() > 1e-8)) return std::nullopt;
    const auto congruent = [&](const Eigen::MatrixXd& X) {   // L^-1 T X T L^-T
        Eigen::MatrixXd Y = llt.matrixL().solve(t.asDiagonal() * X * t.asDiagonal());
        return Eigen::MatrixXd(llt.matrixL().solve(Y.transpose()).transpose());
    };
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -congruent(original.K) / (g * g);
    A.bottomRightCorner(n, n) = -congruent(original.C) / g;
    return Eigen::VectorXcd(g * lapack_dgeev_values(std::move(A)));
}

// Every finite eigenvalue of p to `keep`: the state matrix where M allows, else QZ.
// `scaling`: a group's, the whole pencil's (as solve_qz_by_groups).
template <class Keep>
void all_eigenvalues(const QuadraticPencil& p, double g, const Keep& keep, const CompanionScaling* scaling = nullptr) {
    if (const std::optional<Eigen::VectorXcd> values = state_matrix_values(p, g, scaling ? &scaling->t : nullptr)) {
        for (const cd l : *values) keep(l);
        return;
    }
    Companion c = scaling ? companion(p, *scaling) : companion(p);
    // Without vectors the classic QZ is the faster up to about 400 DOFs (ROSS's 42:
    // 2.4 against 4.1 ms; 100: 21 against 32 ms; 336: 0.77 against 0.81 s).
    const bool classic = p.M.rows() <= kClassicValuesLimit;
    const GeneralizedEigen ge = lapack_dggev_values(std::move(c.A), std::move(c.B), classic);
    int at_infinity = 0;
    for (Eigen::Index j = 0; j < ge.alpha.size(); ++j) {
        if (!infinite(ge.alpha(j), ge.beta(j))) keep(c.gamma * ge.alpha(j) / ge.beta(j));
        else ++at_infinity;
    }
    // Finite eigenvalues beyond the scaled pencil's resolution (as the full solve).
    if (at_infinity > 0)
        for (const Mode& m : largest_by_reversal(p, at_infinity - infinite_limit(p), false, classic)) keep(m.lambda);
}

}  // namespace

EigenvalueSet quadratic_eigenvalues(const QuadraticPencil& p) {
    if (!p.M.allFinite() || !p.C.allFinite() || !p.K.allFinite())
        throw InputError("the pencil has a NaN or infinite coefficient");
    EigenvalueSet e;
    e.scale = natural_scale(p);
    e.real_tol = 1e-7 * e.scale;   // as solve_qz
    const auto keep = [&](cd l) {   // the upper half plane and the real axis, as the full solve keeps them
        if (l.imag() >= -e.real_tol) e.values.push_back(l);
    };
    // Each uncoupled group on its own (as solve_qz_by_groups), scaled by the whole's scale.
    const std::vector<std::vector<Eigen::Index>> groups = uncoupled_groups(p);
    if (groups.size() > 1) {
        const CompanionScaling whole = companion_scaling(p);
        for (const std::vector<Eigen::Index>& g : groups) {
            CompanionScaling own = whole;
            own.t = Eigen::VectorXd(whole.t(g));
            all_eigenvalues(restricted(p, g), e.scale, keep, &own);
        }
        return e;
    }
    all_eigenvalues(p, e.scale, keep);
    return e;
}

QuadraticSpectrum solve_at_speed(const GyroscopicSystem& sys, double w, const EigenOptions& opt) {
    return solve_quadratic(sys.at_speed(w), opt, sys.whirl_pairs);
}

}  // namespace gyrokit
