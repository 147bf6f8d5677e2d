// The projected pencil Q^T P(w) Q on a basis of the anchors' vectors, each pair
// lifted to the full model, refined and verified (ContinuationOptions::along_branches
// false). docs/numerics.md ("Continuation").
#include <gyrokit/solve/detail/continuation_parts.hpp>

#include <fmt/format.h>

namespace gyrokit::continuation_detail {

// The reduced solve at w, or nothing where a pair fails verification.
std::optional<QuadraticSpectrum> reduced_solve(const Shared& sh, double w) {
    const GyroscopicSystem& sys = *sh.model;
    const SparsePencil p = sys.sparse_at_speed(w);
    const PencilAction action = action_of(p);
    QuadraticSpectrum out = empty_spectrum(p, action, w);
    const Eigen::MatrixXd& Q = sh.Q;
    const QuadraticPencil reduced{Q.transpose() * (p.M * Q), Q.transpose() * (p.C * Q), Q.transpose() * (p.K * Q)};
    QuadraticSpectrum r = solve_quadratic(reduced, {sh.opt.eig.method, false}, {});
    std::vector<Mode> candidates;
    for (auto* list : {&r.modes, &r.rigid_body})
        for (Mode& m : *list)
            // A margin for the reduced eigenvalue's error: the band is applied again after refinement.
            if (within_band(m, 1.05 * sh.opt.band, out.real_tol)) candidates.push_back(std::move(m));
    std::vector<Mode> modes;
    for (Mode& m : candidates) {
        m.right = Q * m.right;
        m.left.resize(0);
        refine_eigenpair(p, action, m, sh.opt.tolerance, out.scale);
        if (!verified(p, action, m, sh.opt.tolerance, out.real_tol)) return std::nullopt;
        // Two reduced eigenvalues refined onto one mode: the basis misses a mode there.
        if (lands_on_another(modes, m)) return std::nullopt;
        if (!within_band(m, sh.opt.band, out.real_tol)) continue;
        modes.push_back(std::move(m));
    }
    out = finish(frame_of(sh), p, action, std::move(out), std::move(modes), w);
    if (!sh.opt.eig.left_vectors)
        for (Mode& m : out.modes) m.left.resize(0);
    out.method = fmt::format("continuation (reduced basis of {} vectors, verified)", Q.cols());
    return out;
}

}  // namespace gyrokit::continuation_detail
