#include <gyrokit/solve/spectrum_solver.hpp>

#include <gyrokit/solve/continuation.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/core/parallel.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

#include <fmt/format.h>

namespace gyrokit {

SolverWork WorkCounter::snapshot() const {
    SolverWork w;
    w.full_solves = full_solves.load();
    w.eigenvalue_checks = eigenvalue_checks.load();
    w.window_solves = window_solves.load();
    w.steps = steps.load();
    w.split_steps = split_steps.load();
    w.local_solves = local_solves.load();
    w.followed = followed.load();
    w.joined = joined.load();
    w.cluster_steps = cluster_steps.load();
    return w;
}

SolverFactory::SolverFactory(Make make, int dofs, std::shared_ptr<WorkCounter> work)
    : make_(std::move(make)), dofs_(dofs) {
    if (work) work_ = std::move(work);
}

namespace {
[[noreturn]] void missing(const char* what) {
    throw std::logic_error(std::string("SolverFactory: this solver has no ") + what);
}
}  // namespace

SpectrumSolver SolverFactory::operator()() const {
    if (!make_) missing("solver (a default-constructed factory)");
    return make_();
}

SpectrumSolver SolverFactory::centred(double nu) const {
    if (!centred_) missing("centred window (has_centred)");
    return centred_(nu);
}

std::optional<Mode> SolverFactory::follow(const Mode& from, double w, std::complex<double> predicted,
                                          double reach) const {
    if (!follow_) missing("mode following (can_follow)");
    return follow_(from, w, predicted, reach);
}

SolverFactory SolverFactory::continued(const std::vector<double>& speeds, const ContinuationOptions& opt,
                                       ContinuationReport* report) const {
    if (!continued_) missing("continuation (can_continue)");
    return continued_(speeds, opt, report);
}

SolverFactory SolverFactory::resized(int modes) const {
    if (!resize_) missing("window to resize (can_resize)");
    return resize_(modes);
}

SparsePencil SolverFactory::pencil(double w) const {
    if (!pencil_) missing("pencil (has_pencil)");
    return pencil_(w);
}

SpectrumSolver SolverFactory::walk(int threads) const {
    if (!walk_) missing("walk (walks)");
    return walk_(threads);
}

SolverFactory dense_solver(const GyroscopicSystem& sys, const EigenOptions& eig) {
    sys.validate("dense solver: the system");
    if (sys.size() > kDenseLimit)
        throw InputError(fmt::format("{} 'dense': the model has {} DOFs, above the dense limit of {}; allowed: "
                                     "sparse or auto (choose_solver)",
                                     option_field("solver"), sys.size(), kDenseLimit));
    // The solvers share ownership of one copy: a temporary system outlives the call.
    const auto model = std::make_shared<const GyroscopicSystem>(sys);
    const auto work = std::make_shared<WorkCounter>();
    SolverFactory f([model, eig, work]() -> SpectrumSolver {
                return [model, eig, work](double w) {
                    throw_if_interrupted();
                    ++work->full_solves;
                    EigenOptions o = eig;
                    o.left_vectors = true;   // for the slopes
                    QuadraticSpectrum s = solve_at_speed(*model, w, o);
                    set_slopes(s.modes, [&](double v) { return model->sparse_at_speed(v); }, w, s.scale);
                    if (!eig.left_vectors)
                        for (Mode& m : s.modes) m.left.resize(0);
                    return s;
                };
            }, model->size(), work);
    f.with_pencil([model](double w) { return model->sparse_at_speed(w); });
    f.with_continuation([model, eig](const std::vector<double>& speeds, const ContinuationOptions& opt,
                                     ContinuationReport* report) {
        ContinuationOptions o = opt;
        o.eig = eig;
        return continuation_solver(model, speeds, o, report);
    });
    return f;
}

namespace {

// A - B without the entries that are equal in both (M, and most of K, do not change
// with speed: their products then cost nothing). Where A and B share their pattern (a
// model's pencils at two speeds), entry by entry on the value arrays.
SparseMatrix change(const SparseMatrix& A, const SparseMatrix& B) {
    SparseMatrix d;
    if (A.isCompressed() && B.isCompressed() && A.rows() == B.rows() && A.cols() == B.cols() &&
        A.nonZeros() == B.nonZeros() &&
        std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, B.outerIndexPtr()) &&
        std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), B.innerIndexPtr())) {
        d = A;
        Eigen::Map<Eigen::ArrayXd>(d.valuePtr(), d.nonZeros()) -= Eigen::Map<const Eigen::ArrayXd>(B.valuePtr(), B.nonZeros());
    } else {
        d = A - B;
    }
    d.prune(0.0);
    return d;
}

}  // namespace

void set_slopes(std::vector<Mode>& modes, const std::function<SparsePencil(double)>& pencil, double w,
                double scale, int threads, const SparsePencil* at_w) {
    using cd = std::complex<double>;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (modes.empty()) return;
    // Central differences (forward ones next to standstill, where a table holds its
    // end row below zero): exact for the terms linear and quadratic in w up to
    // rounding of order eps |P| / h, the average slope across a table's kink.
    const double h = 1e-4 * std::max(std::abs(w), scale > 0.0 ? scale : 1.0);
    const bool forward = w - h < 0.0;
    const SparsePencil p = at_w ? SparsePencil{} : pencil(w);
    const SparsePencil& pw = at_w ? *at_w : p;
    const SparsePencil hi = pencil(w + h), lo = forward ? SparsePencil{} : pencil(w - h);
    const SparsePencil& low = forward ? pw : lo;
    const double span = forward ? h : 2.0 * h;
    // The differences once for all modes (the products below are per mode).
    const SparseMatrix dM = change(hi.M, low.M), dC = change(hi.C, low.C), dK = change(hi.K, low.K);
    for_each_index(modes.size(), threads, [&](size_t i) {
        Mode& m = modes[i];
        m.slope = {nan, 0.0};
        if (m.left.size() != m.right.size() || m.right.size() == 0) return;
        // A double eigenvalue's vectors are any basis of its plane: no slope of its own,
        // unless the pair's vectors are the directions in which it splits (below).
        const auto partners_of = [&](const Mode& a) {
            std::vector<const Mode*> out;
            for (const Mode& o : modes)
                if (&o != &a && std::abs(o.lambda - a.lambda) <= 1e-6 * std::abs(a.lambda)) out.push_back(&o);
            return out;
        };
        const std::vector<const Mode*> partners = partners_of(m);
        // A double: each the other's only partner (not a cluster), both with left vectors.
        if (partners.size() > 1 ||
            (partners.size() == 1 && (partners[0]->left.size() != m.right.size() || partners_of(*partners[0]).size() != 1)))
            return;
        const cd l = m.lambda;
        const auto dP = [&](const Eigen::VectorXcd& x) -> Eigen::VectorXcd {   // dP/dw x
            return ((l * l) * real_times(dM, x) + l * real_times(dC, x) + real_times(dK, x)) / span;
        };
        const auto dlP = [&](const Eigen::VectorXcd& x) -> Eigen::VectorXcd {   // P'(lambda) x
            return (2.0 * l) * real_times(pw.M, x) + real_times(pw.C, x);
        };
        if (partners.empty()) {
            // y^H P'(lambda) x and y^H (dP/dw) x as sums over the matrices' entries.
            const Eigen::VectorXcd &x = m.right, &y = m.left;
            const cd den = (2.0 * l) * real_bilinear(pw.M, y, x) + real_bilinear(pw.C, y, x);
            if (std::abs(den) == 0.0) return;
            const cd num = ((l * l) * real_bilinear(dM, y, x) + l * real_bilinear(dC, y, x) + real_bilinear(dK, y, x)) / span;
            m.slope = -num / den;
        } else {
            // The pair splits as the eigenvalues of S = -(Y^H P' X)^-1 (Y^H dP/dw X) (first
            // order for a semisimple double eigenvalue). If S is diagonal to 1e-2 of the
            // split, X's columns are the splitting directions and each has slope S_ii.
            const Mode& o = *partners[0];
            Eigen::Matrix2cd A, B;
            const Eigen::VectorXcd* X[2] = {&m.right, &o.right};
            const Eigen::VectorXcd* Y[2] = {&m.left, &o.left};
            for (int c = 0; c < 2; ++c) {
                const Eigen::VectorXcd a = dlP(*X[c]), b = dP(*X[c]);
                for (int r = 0; r < 2; ++r) A(r, c) = Y[r]->dot(a), B(r, c) = Y[r]->dot(b);
            }
            // Nearly parallel vectors (left or right) make A singular to rounding: no split then.
            if (!(std::abs(A.determinant()) > 1e-8 * A.squaredNorm())) return;
            const Eigen::Matrix2cd S = -A.inverse() * B;
            const double split = std::abs(S(0, 0) - S(1, 1));
            if (!(split > 0.0) || !(std::max(std::abs(S(0, 1)), std::abs(S(1, 0))) <= 1e-2 * split)) return;
            m.slope = S(0, 0);
        }
        if (!std::isfinite(m.slope.real()) || !std::isfinite(m.slope.imag())) m.slope = {nan, 0.0};
    });
}

QuadraticSpectrum to_spectrum(SparseSpectrum s, const SparsePencil& p) {
    QuadraticSpectrum q;
    q.modes = std::move(s.modes);
    q.rigid_body = std::move(s.rigid_body);
    q.notes = std::move(s.notes);
    q.method = "ARPACK shift-invert";
    q.iterations = s.iterations;
    q.refined = s.refined;
    q.scale = natural_frequency_scale(p.M.diagonal(), p.K.diagonal(), p.M.norm(), p.K.norm());
    q.real_tol = 1e-7 * q.scale;
    q.partial = true;
    return q;
}

namespace {

// The sparse factory whose solvers count their work in `work`.
SolverFactory sparse_factory(std::function<SparsePencil(double)> pencil, std::vector<std::pair<int, int>> whirl_pairs,
                             const SparseEigenOptions& opt, bool reuse, std::shared_ptr<WorkCounter> work, int dofs) {
    const SolverFactory::Walk walk = [pencil, whirl_pairs, opt, reuse, work](int threads) -> SpectrumSolver {
        // The state vectors [lambda x; x] of the last speed's modes, summed: a
        // start vector rich in the wanted invariant subspace.
        auto start = std::make_shared<Eigen::VectorXcd>();
        // Rigid-body eigenvalues seen in the window at the last speed: asked for at once.
        auto rigid = std::make_shared<int>(0);
        // The last speed's window with left vectors and slopes: the next speed continues its
        // modes along their branches (a few factorizations each) where every one verifies.
        auto last = std::make_shared<std::optional<QuadraticSpectrum>>();
        return [pencil, whirl_pairs, opt, reuse, start, rigid, last, threads, work](double w) {
            throw_if_interrupted();
            const auto keep = [&](QuadraticSpectrum q) {
                *last = q;
                if (!opt.left_vectors)
                    for (Mode& m : q.modes) m.left.resize(0);
                return q;
            };
            // A moving window (shift_order != 0) takes other modes in at each speed: solved afresh.
            if (reuse && opt.shift_order == 0.0 && *last)
                if (std::optional<QuadraticSpectrum> q =
                        continue_window(pencil, whirl_pairs, **last, w, opt.verify_tolerance, threads)) {
                    ++work->steps;
                    return keep(std::move(*q));
                }
            ++work->window_solves;
            const SparsePencil p = pencil(w);
            SparseEigenOptions o = opt;
            o.shift += std::complex<double>(0.0, opt.shift_order * w);   // continued along nu + k w
            if (reuse) o.start = *start;
            o.left_vectors = true;   // for the slopes
            if (*rigid > 0) o.reserve = std::max(o.reserve, *rigid + 2);
            SparseSpectrum s = solve_quadratic_sparse(p, o, whirl_pairs);
            *rigid = static_cast<int>(s.rigid_body.size());
            QuadraticSpectrum q = to_spectrum(std::move(s), p);
            q.speed = w;
            set_slopes(q.modes, pencil, w, q.scale);
            if (reuse && !q.modes.empty()) {
                // Real and imaginary parts of [lambda x; x] span each mode and its
                // conjugate (ARPACK wants both); a small random part keeps the
                // Krylov space from closing on them before it holds all it needs.
                const Eigen::Index n = p.M.rows();
                Eigen::VectorXcd v = Eigen::VectorXcd::Zero(2 * n);
                for (const Mode& m : q.modes) {
                    Eigen::VectorXcd z(2 * n);
                    z.head(n) = m.lambda / std::max(1.0, std::abs(m.lambda)) * m.right;
                    z.tail(n) = m.right / std::max(1.0, std::abs(m.lambda));
                    z /= z.norm();
                    v += z.real().cast<std::complex<double>>() + z.imag().cast<std::complex<double>>();
                }
                v /= v.norm();
                const Eigen::VectorXcd r = fixed_random_vector(2 * n).cast<std::complex<double>>();
                *start = v + 0.01 * r / r.norm();
            }
            return keep(std::move(q));
        };
    };
    SolverFactory f([walk]() { return walk(1); }, dofs, work);
    f.not_thread_safe();
    f.with_pencil(pencil);
    // The same window of another size; Arnoldi vectors as asked where they still suffice
    // (at least the automatic count for that size), else automatic.
    f.with_window(opt.modes, [pencil, whirl_pairs, opt, reuse, work, dofs](int modes) {
        SparseEigenOptions o = opt;
        o.modes = modes;
        // ARPACK needs more than twice the window (and a reserve): automatic below that.
        if (o.lanczos_vectors > 0 && o.lanczos_vectors < std::max(2 * (2 * modes + 2) + 1, 30)) o.lanczos_vectors = 0;
        return sparse_factory(pencil, whirl_pairs, o, reuse, work, dofs);
    });
    // A window centred on one mode's frequency, where a root search follows that mode
    // (counted with the sweep's work).
    f.with_centred([pencil, whirl_pairs, opt, work, dofs](double nu) {
        SparseEigenOptions o = opt;
        o.shift = {0.0, nu};
        o.shift_order = 0.0;
        return sparse_factory(pencil, whirl_pairs, o, true, work, dofs)();
    });
    f.with_follow([pencil, whirl_pairs, tol = opt.verify_tolerance, work](const Mode& from, double w,
                                                                           std::complex<double> predicted, double reach) {
        ++work->followed;
        return follow_mode(pencil, whirl_pairs, from, w, predicted, reach, tol);
    });
    // Without state carried from speed to speed, or with a moving window, the
    // speeds are independent: blocks of them go to the workers.
    if (reuse && opt.shift_order == 0.0) f.with_walk(walk);
    return f;
}

}  // namespace

SolverFactory sparse_solver(std::function<SparsePencil(double)> pencil, std::vector<std::pair<int, int>> whirl_pairs,
                            const SparseEigenOptions& opt, bool reuse, int dofs) {
    return sparse_factory(std::move(pencil), std::move(whirl_pairs), opt, reuse, std::make_shared<WorkCounter>(), dofs);
}

SolverFactory sparse_solver(const GyroscopicSystem& sys, const SparseEigenOptions& opt, bool reuse) {
    sys.validate("sparse solver: the system");
    const auto model = std::make_shared<const GyroscopicSystem>(sys);
    return sparse_solver([model](double w) { return model->sparse_at_speed(w); }, sys.whirl_pairs, opt, reuse,
                         model->size());
}

}  // namespace gyrokit
