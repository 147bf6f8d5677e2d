#include <gyrokit/analysis/continuation.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace gyrokit {

using cd = std::complex<double>;

bool within_band(const Mode& m, double band, double real_tol) {
    return std::abs(m.lambda.imag()) <= real_tol ? std::abs(m.lambda) <= band : m.lambda.imag() <= band;
}

namespace {

PencilAction action_of(const SparsePencil& p) { return sparse_pencil_action(p); }

// Relative backward error of a left vector: |P(l)^H y| / ((|l|^2 |M| + |l| |C| + |K|) |y|).
double left_backward_error(const SparsePencil& p, const PencilAction& a, cd l, const Eigen::VectorXcd& y) {
    const cd c = std::conj(l);
    const Eigen::VectorXcd r = (c * c) * real_times(SparseMatrix(p.M.transpose()), y) +
                               c * real_times(SparseMatrix(p.C.transpose()), y) + real_times(SparseMatrix(p.K.transpose()), y);
    const double s = std::norm(l) * a.norm_M + std::abs(l) * a.norm_C + a.norm_K;
    return r.norm() / (s * y.norm());
}

struct Shared {
    std::shared_ptr<const GyroscopicSystem> model;
    ContinuationOptions opt;
    Eigen::MatrixXd Q;                              // n x r, orthonormal columns
    std::map<double, QuadraticSpectrum> anchors;   // the full solves, kept to the band
};

// The modes of a full solve within the band, with slopes.
QuadraticSpectrum keep_band(QuadraticSpectrum s, const Shared& sh, double w) {
    std::vector<Mode> kept;
    for (Mode& m : s.modes)
        if (within_band(m, sh.opt.band, s.real_tol)) kept.push_back(std::move(m));
    s.modes = std::move(kept);
    s.partial = true;
    set_slopes(s.modes, [&](double v) { return sh.model->sparse_at_speed(v); }, w, s.scale);
    if (!sh.opt.eig.left_vectors)
        for (Mode& m : s.modes) m.left.resize(0);
    return s;
}

QuadraticSpectrum full_solve(const Shared& sh, double w) {
    EigenOptions o = sh.opt.eig;
    o.left_vectors = true;
    return keep_band(solve_at_speed(*sh.model, w, o), sh, w);
}

// The reduced solve at w, or nothing where a pair fails verification.
std::optional<QuadraticSpectrum> reduced_solve(const Shared& sh, double w) {
    const GyroscopicSystem& sys = *sh.model;
    const SparsePencil p = sys.sparse_at_speed(w);
    const PencilAction action = action_of(p);
    QuadraticSpectrum out;
    out.scale = natural_frequency_scale(p.M.diagonal(), p.K.diagonal(), action.norm_M, action.norm_K);
    out.real_tol = 1e-7 * out.scale;
    out.partial = true;
    out.speed = w;
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
        if (!(m.backward_error <= sh.opt.tolerance) || m.left.size() == 0 ||
            !(left_backward_error(p, action, m.lambda, m.left) <= sh.opt.tolerance))
            return std::nullopt;
        if (m.lambda.imag() < 0.0) m.lambda = std::conj(m.lambda), m.right = m.right.conjugate(), m.left = m.left.conjugate();
        if (std::abs(m.lambda.imag()) <= out.real_tol) m.lambda = cd(m.lambda.real(), 0.0);
        // Two reduced eigenvalues refined onto one mode: the basis misses a mode there.
        for (const Mode& o : modes)
            if (std::abs(o.lambda - m.lambda) <= 1e-8 * std::abs(m.lambda) && mac(o.right, m.right) > 0.99)
                return std::nullopt;
        if (!within_band(m, sh.opt.band, out.real_tol)) continue;
        m.whirl = classify_whirl(m.lambda, m.right, sys.whirl_pairs, out.real_tol);
        modes.push_back(std::move(m));
    }
    split_rigid_body(modes, out.rigid_body, action, out.scale);
    separate_double_whirl(modes, sys.whirl_pairs, out.real_tol, action);
    const Eigen::VectorXd t = sparse_dof_scaling(p, out.scale);
    const SparsePencil scaled{t.asDiagonal() * p.M * t.asDiagonal(), t.asDiagonal() * p.C * t.asDiagonal(),
                              t.asDiagonal() * p.K * t.asDiagonal()};
    set_error_bounds(modes, action, action_of(scaled), t);
    sort_by_frequency(modes);
    set_slopes(modes, [&](double v) { return sys.sparse_at_speed(v); }, w, out.scale);
    if (!sh.opt.eig.left_vectors)
        for (Mode& m : modes) m.left.resize(0);
    out.modes = std::move(modes);
    out.method = fmt::format("continuation (reduced basis of {} vectors, verified)", Q.cols());
    return out;
}

}  // namespace

SolverFactory continuation_solver(std::shared_ptr<const GyroscopicSystem> model, const std::vector<double>& speeds,
                                  const ContinuationOptions& opt, ContinuationReport* report) {
    if (!(opt.band > 0.0) || !std::isfinite(opt.band))
        throw InputError(fmt::format("continuation band {}: allowed: a finite frequency > 0 (rad/s)", opt.band));
    if (opt.anchor_stride < 1)
        throw InputError(fmt::format("anchor_stride {}: allowed: 1 or more", opt.anchor_stride));
    if (speeds.empty()) throw InputError("continuation: no speeds; allowed: one or more speeds >= 0");
    auto sh = std::make_shared<Shared>();
    sh->model = model;
    sh->opt = opt;
    const int n = model->size();
    ContinuationReport rep;
    rep.dofs = n;
    std::vector<double> anchors;
    for (size_t k = 0; k < speeds.size(); k += static_cast<size_t>(opt.anchor_stride)) anchors.push_back(speeds[k]);
    if (anchors.back() != speeds.back()) anchors.push_back(speeds.back());
    rep.anchors = anchors;
    EigenOptions full = opt.eig;
    full.left_vectors = true;
    const SolverFactory dense = dense_solver(*model, full);
    std::vector<QuadraticSpectrum> solved = solve_speeds(dense, anchors, opt.workers);

    // The basis: real and imaginary parts of the right and left vectors of every
    // mode within twice the band (modes that enter the band between anchors are
    // near it at an anchor), and of the rigid-body eigenvalues.
    std::vector<Eigen::VectorXd> columns;
    const auto add = [&](const Eigen::VectorXcd& v) {
        if (v.size() != n) return;
        for (const Eigen::VectorXd& c : {Eigen::VectorXd(v.real()), Eigen::VectorXd(v.imag())})
            if (c.norm() > 1e-8 * v.norm()) columns.push_back(c / c.norm());
    };
    for (const QuadraticSpectrum& s : solved) {
        for (const Mode& m : s.modes)
            if (within_band(m, 2.0 * opt.band, s.real_tol)) add(m.right), add(m.left);
        for (const Mode& m : s.rigid_body) add(m.right), add(m.left);
    }
    Eigen::MatrixXd V(n, static_cast<Eigen::Index>(columns.size()));
    for (size_t j = 0; j < columns.size(); ++j) V.col(static_cast<Eigen::Index>(j)) = columns[j];
    int r = 0;
    if (V.cols() > 0) {
        Eigen::BDCSVD<Eigen::MatrixXd> svd(V, Eigen::ComputeThinU);
        const Eigen::VectorXd& sv = svd.singularValues();
        while (r < sv.size() && sv(r) > 1e-12 * sv(0)) ++r;
        sh->Q = svd.matrixU().leftCols(r);
    }
    rep.basis = r;
    rep.used = r > 0 && r <= opt.max_basis_fraction * n;
    if (report) *report = rep;
    if (!rep.used) return dense_solver(*model, opt.eig);
    for (size_t k = 0; k < anchors.size(); ++k) sh->anchors[anchors[k]] = keep_band(std::move(solved[k]), *sh, anchors[k]);

    SolverFactory f;
    f.make = [sh]() -> SpectrumSolver {
        return [sh](double w) {
            throw_if_interrupted();
            if (const auto it = sh->anchors.find(w); it != sh->anchors.end()) return it->second;
            if (std::optional<QuadraticSpectrum> s = reduced_solve(*sh, w)) return std::move(*s);
            QuadraticSpectrum s = full_solve(*sh, w);
            s.notes.push_back("continuation: a pair failed verification on the reduced basis at some speeds; "
                              "those speeds were solved in full");
            return s;
        };
    };
    return f;
}

}  // namespace gyrokit
