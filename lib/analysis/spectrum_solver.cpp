#include "analysis/spectrum_solver.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

namespace gyrokit {

SolverFactory dense_solver(const GyroscopicSystem& sys, const EigenOptions& eig) {
    return [&sys, eig]() -> SpectrumSolver { return [&sys, eig](double w) { return solve_at_speed(sys, w, eig); }; };
}

QuadraticSpectrum to_spectrum(SparseSpectrum s, const SparsePencil& p) {
    QuadraticSpectrum q;
    q.modes = std::move(s.modes);
    const double scale = std::sqrt(p.K.norm() / p.M.norm());
    q.scale = std::isfinite(scale) && scale > 0 ? scale : 1.0;
    q.real_tol = 1e-7 * q.scale;
    q.partial = true;
    return q;
}

SolverFactory sparse_solver(std::function<SparsePencil(double)> pencil, std::vector<std::pair<int, int>> whirl_pairs,
                            const SparseEigenOptions& opt, bool reuse) {
    return [pencil, whirl_pairs, opt, reuse]() -> SpectrumSolver {
        // The state vectors [lambda x; x] of the last speed's modes, summed: a
        // start vector rich in the wanted invariant subspace.
        auto start = std::make_shared<Eigen::VectorXcd>();
        return [pencil, whirl_pairs, opt, reuse, start](double w) {
            const SparsePencil p = pencil(w);
            SparseEigenOptions o = opt;
            if (reuse) o.start = *start;
            SparseSpectrum s = solve_quadratic_sparse(p, o, whirl_pairs);
            if (reuse && !s.modes.empty()) {
                const Eigen::Index n = p.M.rows();
                Eigen::VectorXcd v = Eigen::VectorXcd::Zero(2 * n);
                for (const Mode& m : s.modes) {
                    v.head(n) += m.lambda * m.right / std::max(1.0, std::abs(m.lambda));
                    v.tail(n) += m.right / std::max(1.0, std::abs(m.lambda));
                }
                *start = v;
            }
            return to_spectrum(std::move(s), p);
        };
    };
}

SolverFactory sparse_solver(const SparseGyroscopicSystem& sys, const SparseEigenOptions& opt, bool reuse) {
    return sparse_solver([&sys](double w) { return sys.at_speed(w); }, sys.whirl_pairs, opt, reuse);
}

SolverFactory sparse_solver(const GyroscopicSystem& sys, const SparseEigenOptions& opt, bool reuse) {
    return sparse_solver([&sys](double w) { return to_sparse(sys.at_speed(w)); }, sys.whirl_pairs, opt, reuse);
}

std::vector<QuadraticSpectrum> solve_speeds(const SolverFactory& make, const std::vector<double>& speeds, int threads,
                                            const std::function<void(size_t, size_t)>& progress) {
    const size_t n = speeds.size();
    std::vector<QuadraticSpectrum> out(n);
    const size_t t = std::clamp<size_t>(threads < 1 ? 1 : static_cast<size_t>(threads), 1, std::max<size_t>(n, 1));
    std::atomic<size_t> done{0};
    std::mutex report;
    std::exception_ptr failure;
    const auto work = [&](size_t first, size_t last) {
        try {
            SpectrumSolver solve = make();
            for (size_t i = first; i < last; ++i) {
                {
                    std::lock_guard<std::mutex> lock(report);
                    if (failure) return;
                }
                out[i] = solve(speeds[i]);
                const size_t d = ++done;
                if (progress) {
                    std::lock_guard<std::mutex> lock(report);
                    progress(d, n);
                }
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(report);
            if (!failure) failure = std::current_exception();
        }
    };
    if (t == 1) {
        work(0, n);
    } else {
        std::vector<std::thread> pool;
        for (size_t k = 0; k < t; ++k) pool.emplace_back(work, k * n / t, (k + 1) * n / t);
        for (auto& th : pool) th.join();
    }
    if (failure) std::rethrow_exception(failure);
    return out;
}

}  // namespace gyrokit
