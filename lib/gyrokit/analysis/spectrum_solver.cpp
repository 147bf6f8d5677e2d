#include <gyrokit/analysis/spectrum_solver.hpp>

#include <gyrokit/analysis/continuation.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace gyrokit {

WorkerDied::WorkerDied(long long task_index, int signal_number)
    : Error(fmt::format("a worker process died (signal {}) while solving task {}", signal_number, task_index)),
      task(task_index), signal(signal_number) {}

std::vector<QuadraticSpectrum> solve_speeds_unchecked(const SolverFactory& make, const std::vector<double>& speeds,
                                                      Workers workers,
                                                      const std::function<void(size_t, size_t)>& progress);

SolverFactory dense_solver(const GyroscopicSystem& sys, const EigenOptions& eig) {
    sys.validate("dense solver: the system");
    if (sys.size() > kDenseLimit)
        throw InputError(fmt::format("solver 'dense': the model has {} DOFs, above the dense limit of {}; allowed: "
                                     "sparse or auto (choose_solver)",
                                     sys.size(), kDenseLimit));
    // The solvers share ownership of one copy: a temporary system outlives the call.
    const auto model = std::make_shared<const GyroscopicSystem>(sys);
    SolverFactory f;
    f.make = [model, eig]() -> SpectrumSolver {
                return [model, eig](double w) {
                    throw_if_interrupted();
                    EigenOptions o = eig;
                    o.left_vectors = true;   // for the slopes
                    QuadraticSpectrum s = solve_at_speed(*model, w, o);
                    set_slopes(s.modes, [&](double v) { return model->sparse_at_speed(v); }, w, s.scale);
                    if (!eig.left_vectors)
                        for (Mode& m : s.modes) m.left.resize(0);
                    return s;
                };
            };
    f.continued = [model, eig](const std::vector<double>& speeds, double band, Workers workers) {
        ContinuationOptions o;
        o.band = band;
        o.eig = eig;
        o.workers = workers;
        return continuation_solver(model, speeds, o);
    };
    return f;
}

void set_slopes(std::vector<Mode>& modes, const std::function<SparsePencil(double)>& pencil, double w,
                double scale) {
    using cd = std::complex<double>;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (modes.empty()) return;
    // Central differences (forward ones next to standstill, where a table holds its
    // end row below zero): exact for the terms linear and quadratic in w up to
    // rounding of order eps |P| / h, the average slope across a table's kink.
    const double h = 1e-4 * std::max(std::abs(w), scale > 0.0 ? scale : 1.0);
    const bool forward = w - h < 0.0;
    const SparsePencil p = pencil(w), hi = pencil(w + h), lo = pencil(forward ? w : w - h);
    const double span = forward ? h : 2.0 * h;
    for (Mode& m : modes) {
        m.slope = {nan, 0.0};
        if (m.left.size() != m.right.size() || m.right.size() == 0) continue;
        // A double eigenvalue's vectors are any basis of its plane: no slope of its own.
        bool single = true;
        for (const Mode& o : modes)
            if (&o != &m && std::abs(o.lambda - m.lambda) <= 1e-6 * std::abs(m.lambda)) single = false;
        if (!single) continue;
        const cd l = m.lambda;
        const Eigen::VectorXcd& x = m.right;
        const Eigen::VectorXcd dPx = ((l * l) * ((hi.M - lo.M) * x) + l * ((hi.C - lo.C) * x) + (hi.K - lo.K) * x) / span;
        const Eigen::VectorXcd dlPx = (2.0 * l) * (p.M * x) + p.C * x;
        const cd den = m.left.dot(dlPx);   // y^H P'(lambda) x
        if (std::abs(den) == 0.0) continue;
        m.slope = -m.left.dot(dPx) / den;
        if (!std::isfinite(m.slope.real()) || !std::isfinite(m.slope.imag())) m.slope = {nan, 0.0};
    }
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

SolverFactory sparse_solver(std::function<SparsePencil(double)> pencil, std::vector<std::pair<int, int>> whirl_pairs,
                            const SparseEigenOptions& opt, bool reuse) {
    SolverFactory f;
    f.thread_safe = false;
    // A window centred on one mode's frequency, where a root search follows that mode.
    f.centred = [pencil, whirl_pairs, opt](double nu) {
        SparseEigenOptions o = opt;
        o.shift = {0.0, nu};
        o.shift_order = 0.0;
        return sparse_solver(pencil, whirl_pairs, o, true).make();
    };
    f.follow = [pencil, whirl_pairs, tol = opt.verify_tolerance](const Mode& from, double w,
                                                                  std::complex<double> predicted, double reach) {
        return follow_mode(pencil, whirl_pairs, from, w, predicted, reach, tol);
    };
    f.make = [pencil, whirl_pairs, opt, reuse]() -> SpectrumSolver {
        // The state vectors [lambda x; x] of the last speed's modes, summed: a
        // start vector rich in the wanted invariant subspace.
        auto start = std::make_shared<Eigen::VectorXcd>();
        // Rigid-body eigenvalues seen in the window at the last speed: asked for at once.
        auto rigid = std::make_shared<int>(0);
        return [pencil, whirl_pairs, opt, reuse, start, rigid](double w) {
            throw_if_interrupted();
            const SparsePencil p = pencil(w);
            SparseEigenOptions o = opt;
            o.shift += std::complex<double>(0.0, opt.shift_order * w);   // continued along nu + k w
            if (reuse) o.start = *start;
            o.left_vectors = true;   // for the slopes
            if (*rigid > 0) o.reserve = std::max(o.reserve, *rigid + 2);
            SparseSpectrum s = solve_quadratic_sparse(p, o, whirl_pairs);
            *rigid = static_cast<int>(s.rigid_body.size());
            QuadraticSpectrum q = to_spectrum(std::move(s), p);
            set_slopes(q.modes, pencil, w, q.scale);
            if (!opt.left_vectors)
                for (Mode& m : q.modes) m.left.resize(0);
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
            return q;
        };
    };
    return f;
}

SolverFactory sparse_solver(const GyroscopicSystem& sys, const SparseEigenOptions& opt, bool reuse) {
    sys.validate("sparse solver: the system");
    const auto model = std::make_shared<const GyroscopicSystem>(sys);
    return sparse_solver([model](double w) { return model->sparse_at_speed(w); }, sys.whirl_pairs, opt, reuse);
}

SolverKind parse_solver_kind(const std::string& name) {
    if (name == "auto") return SolverKind::Auto;
    if (name == "dense") return SolverKind::Dense;
    if (name == "sparse") return SolverKind::Sparse;
    throw InputError(fmt::format("solver '{}': allowed: auto, dense, sparse", name));
}

std::string to_string(SolverKind k) {
    switch (k) {
    case SolverKind::Auto: return "auto";
    case SolverKind::Dense: return "dense";
    case SolverKind::Sparse: return "sparse";
    }
    return "auto";
}

SolverKind resolve_solver_kind(int dofs, SolverKind requested, int modes) {
    if (requested != SolverKind::Auto) return requested;
    return dofs > (modes == kModesInRange ? kAutoDenseInRangeDofs : kAutoSparseDofs) ? SolverKind::Sparse
                                                                                     : SolverKind::Dense;
}

SolverChoice choose_solver(const GyroscopicSystem& sys, const SolverOptions& opt) {
    if (opt.modes < kModesInRange)
        throw InputError(fmt::format("modes = {}: allowed: 0 (all modes; the sparse solver: {}) or more", opt.modes,
                                     kDefaultSparseModes));
    if (opt.target && !std::isfinite(*opt.target))
        throw InputError("target is not a finite number; allowed: a frequency in rad/s");
    if (!std::isfinite(opt.target_order))
        throw InputError("target_order is not a finite number; allowed: a multiple of the speed");
    if (opt.lanczos_vectors < 0)
        throw InputError(fmt::format("lanczos_vectors = {}: allowed: 0 (automatic) or more", opt.lanczos_vectors));
    const int n = sys.size();
    SolverChoice c;
    c.kind = resolve_solver_kind(n, opt.kind, opt.modes);
    if (c.kind == SolverKind::Dense) {
        c.modes = std::max(0, opt.modes);   // every mode is computed; a target does not matter
        c.make = dense_solver(sys, opt.eig);
        return c;
    }
    SparseEigenOptions so;
    so.modes = opt.modes > 0 ? opt.modes : kDefaultSparseModes;
    if (opt.modes <= 0)
        c.notes.push_back(fmt::format("the sparse solver computes {} modes near the target; set modes for another "
                                      "number",
                                      so.modes));
    so.shift = {0.0, opt.target.value_or(0.0)};
    so.shift_order = opt.target_order;
    so.lanczos_vectors = opt.lanczos_vectors;
    so.left_vectors = opt.eig.left_vectors;
    c.modes = so.modes;
    c.make = sparse_solver(sys, so, opt.reuse);
    return c;
}

namespace {

// Spectra through a file: the worker process writes, the parent reads.
template <class T>
void put(std::FILE* f, const T& v) {
    if (std::fwrite(&v, sizeof(T), 1, f) != 1) throw Error("cannot write a worker's result file");
}
template <class T>
T get(std::FILE* f) {
    T v{};
    if (std::fread(&v, sizeof(T), 1, f) != 1) throw Error("a worker's result file ended early");
    return v;
}

void put_vector(std::FILE* f, const Eigen::VectorXcd& v) {
    put<long long>(f, v.size());
    if (v.size() && std::fwrite(v.data(), sizeof(std::complex<double>), static_cast<size_t>(v.size()), f) !=
                        static_cast<size_t>(v.size()))
        throw Error("cannot write a worker's result file");
}
Eigen::VectorXcd get_vector(std::FILE* f) {
    Eigen::VectorXcd v(get<long long>(f));
    if (v.size() && std::fread(v.data(), sizeof(std::complex<double>), static_cast<size_t>(v.size()), f) !=
                        static_cast<size_t>(v.size()))
        throw Error("a worker's result file ended early");
    return v;
}

void put_string(std::FILE* f, const std::string& text) {
    put<long long>(f, static_cast<long long>(text.size()));
    if (!text.empty() && std::fwrite(text.data(), 1, text.size(), f) != text.size())
        throw Error("cannot write a worker's result file");
}
std::string get_string(std::FILE* f) {
    std::string text(static_cast<size_t>(get<long long>(f)), ' ');
    if (!text.empty() && std::fread(text.data(), 1, text.size(), f) != text.size())
        throw Error("a worker's result file ended early");
    return text;
}

void put_modes(std::FILE* f, const std::vector<Mode>& modes) {
    put<long long>(f, static_cast<long long>(modes.size()));
    for (const Mode& m : modes) {
        put(f, m.lambda);
        put(f, m.backward_error);
        put(f, m.error_bound);
        put(f, static_cast<int>(m.whirl));
        put(f, m.slope);
        put_vector(f, m.right);
        put_vector(f, m.left);
    }
}
std::vector<Mode> get_modes(std::FILE* f) {
    std::vector<Mode> modes(static_cast<size_t>(get<long long>(f)));
    for (Mode& m : modes) {
        m.lambda = get<std::complex<double>>(f);
        m.backward_error = get<double>(f);
        m.error_bound = get<double>(f);
        m.whirl = static_cast<Whirl>(get<int>(f));
        m.slope = get<std::complex<double>>(f);
        m.right = get_vector(f);
        m.left = get_vector(f);
    }
    return modes;
}

void put_spectrum(std::FILE* f, const QuadraticSpectrum& s) {
    put_modes(f, s.modes);
    put_modes(f, s.rigid_body);
    put<long long>(f, static_cast<long long>(s.notes.size()));
    for (const auto& note : s.notes) put_string(f, note);
    put(f, s.infinite_count);
    put(f, s.scale);
    put(f, s.real_tol);
    put(f, s.partial);
    put(f, s.speed);
    put(f, s.speed_bound);
    put_string(f, s.method);
    put(f, s.iterations);
    put(f, s.refined);
}
QuadraticSpectrum get_spectrum(std::FILE* f) {
    QuadraticSpectrum s;
    s.modes = get_modes(f);
    s.rigid_body = get_modes(f);
    s.notes.resize(static_cast<size_t>(get<long long>(f)));
    for (auto& note : s.notes) note = get_string(f);
    s.infinite_count = get<int>(f);
    s.scale = get<double>(f);
    s.real_tol = get<double>(f);
    s.partial = get<bool>(f);
    s.speed = get<double>(f);
    s.speed_bound = get<double>(f);
    s.method = get_string(f);
    s.iterations = get<int>(f);
    s.refined = get<int>(f);
    return s;
}

// Blocks of tasks in forked workers. A worker writes 1 + its spectra, or 0 +
// the error kind (1 input, 2 solver, 3 other, 4 interrupted) + message, to its file.
std::vector<QuadraticSpectrum> run_in_processes(const SolverFactory& make, size_t n, size_t workers,
                                                const WorkerTask& task,
                                                const std::function<void(size_t, size_t)>& progress) {
    // A counter all workers share, for the progress bar.
    void* shared = mmap(nullptr, sizeof(std::atomic<size_t>), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (shared == MAP_FAILED) throw Error("cannot map memory for the worker processes");
    auto* done = new (shared) std::atomic<size_t>(0);
    // Each worker's current task, for the report of a worker that dies.
    void* current_map = mmap(nullptr, workers * sizeof(std::atomic<long long>), PROT_READ | PROT_WRITE,
                             MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (current_map == MAP_FAILED) {
        munmap(shared, sizeof(std::atomic<size_t>));
        throw Error("cannot map memory for the worker processes");
    }
    auto* current = static_cast<std::atomic<long long>*>(current_map);
    for (size_t k = 0; k < workers; ++k) new (current + k) std::atomic<long long>(-1);
    std::vector<std::FILE*> files;
    std::vector<pid_t> pids;
    // A worker that cannot start stops and reaps the ones already running.
    const auto abandon = [&](const std::string& why) {
        for (pid_t pid : pids) kill(pid, SIGKILL);
        for (pid_t pid : pids) waitpid(pid, nullptr, 0);
        for (std::FILE* f : files) std::fclose(f);
        munmap(shared, sizeof(std::atomic<size_t>));
        munmap(current_map, workers * sizeof(std::atomic<long long>));
        throw Error(why);
    };
    std::fflush(nullptr);
    for (size_t k = 0; k < workers; ++k) {
        std::FILE* f = std::tmpfile();
        if (!f) abandon(fmt::format("cannot create a temporary file for worker process {} of {}; use fewer jobs",
                                    k + 1, workers));
        const pid_t parent = getpid();
        const pid_t pid = fork();
        if (pid < 0) {
            std::fclose(f);
            abandon(fmt::format("cannot start worker process {} of {} (fork failed); use fewer jobs", k + 1, workers));
        }
        if (pid == 0) {
            // A worker dies with its parent (a service manager's SIGTERM, the OOM killer's
            // SIGKILL): never an orphan that holds the parent's pipes open and keeps computing.
            prctl(PR_SET_PDEATHSIG, SIGKILL);
            if (getppid() != parent) _exit(1);   // the parent died before the line above
            int status = 0;
            try {
                SpectrumSolver solve = make();
                std::vector<QuadraticSpectrum> part;
                for (size_t i = k * n / workers; i < (k + 1) * n / workers; ++i) {
                    throw_if_interrupted();
                    current[k] = static_cast<long long>(i);
                    part.push_back(task(solve, i));
                    const size_t d = ++*done;
                    if (progress) progress(d, n);
                }
                put<char>(f, 1);
                for (const auto& s : part) put_spectrum(f, s);
            } catch (const std::exception& e) {
                const int kind = dynamic_cast<const InputError*>(&e)    ? 1
                                 : dynamic_cast<const SolverError*>(&e) ? 2
                                 : dynamic_cast<const Interrupted*>(&e) ? 4
                                                                        : 3;
                const std::string what = e.what();
                try {
                    put<char>(f, 0);
                    put(f, kind);
                    put_string(f, what);
                } catch (...) {   // the parent then reports the file as ended early
                }
                status = 1;
            }
            if (std::fflush(f) != 0) status = 2;
            _exit(status);
        }
        files.push_back(f);
        pids.push_back(pid);
    }
    // Every worker is reaped; one killed by a signal is reported with its task.
    // Polled, so that an interrupt requested in the parent alone (request_interrupt
    // from another thread, a handler that does not reach the workers) stops them at once.
    std::exception_ptr crash;
    bool stopped = false;
    for (size_t k = 0; k < workers; ++k) {
        int status = 0;
        while (true) {
            const pid_t r = waitpid(pids[k], &status, WNOHANG);
            if (r == pids[k] || (r < 0 && errno != EINTR)) break;
            if (!stopped && interrupt_requested()) {
                stopped = true;
                for (size_t j = k; j < workers; ++j) kill(pids[j], SIGKILL);   // the ones not yet reaped
            }
            struct timespec pause {0, 10'000'000};
            nanosleep(&pause, nullptr);
        }
        if (stopped) continue;
        if (!crash && WIFSIGNALED(status))
            crash = std::make_exception_ptr(WorkerDied(static_cast<long long>(current[k]), WTERMSIG(status)));
        else if (!crash && WIFEXITED(status) && WEXITSTATUS(status) == 2)
            crash = std::make_exception_ptr(Error("a worker process could not write its results (disk full?)"));
    }
    munmap(current_map, workers * sizeof(std::atomic<long long>));
    if (stopped) {
        munmap(shared, sizeof(std::atomic<size_t>));
        for (std::FILE* f : files) std::fclose(f);
        throw Interrupted();
    }
    if (crash) {
        munmap(shared, sizeof(std::atomic<size_t>));
        for (std::FILE* f : files) std::fclose(f);
        std::rethrow_exception(crash);
    }
    munmap(shared, sizeof(std::atomic<size_t>));
    std::vector<QuadraticSpectrum> out(n);
    std::exception_ptr failure;
    for (size_t k = 0; k < workers; ++k) {
        std::FILE* f = files[k];
        try {
            std::rewind(f);
            if (get<char>(f) == 1) {
                for (size_t i = k * n / workers; i < (k + 1) * n / workers; ++i) out[i] = get_spectrum(f);
            } else {
                const int kind = get<int>(f);
                const std::string what = get_string(f);
                if (kind == 1) throw InputError(what);
                if (kind == 2) throw SolverError(what);
                if (kind == 4) throw Interrupted();
                throw Error(what);
            }
        } catch (...) {
            if (!failure) failure = std::current_exception();
        }
        std::fclose(f);
    }
    if (failure) std::rethrow_exception(failure);
    return out;
}

}  // namespace

std::vector<QuadraticSpectrum> run_on_workers(const SolverFactory& make, size_t n, Workers workers,
                                              const WorkerTask& task,
                                              const std::function<void(size_t, size_t)>& progress) {
    std::vector<QuadraticSpectrum> out(n);
    const int threads = workers.count;
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
                throw_if_interrupted();
                out[i] = task(solve, i);
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
    const bool processes = workers.kind == WorkerKind::Processes ||
                           (workers.kind == WorkerKind::Auto && !make.thread_safe);
    if (t > 1 && processes) return run_in_processes(make, n, t, task, progress);
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

std::vector<QuadraticSpectrum> solve_speeds(const SolverFactory& make, const std::vector<double>& speeds,
                                            Workers workers, const std::function<void(size_t, size_t)>& progress) {
    try {
        return solve_speeds_unchecked(make, speeds, workers, progress);
    } catch (const WorkerDied& e) {
        if (e.task < 0 || static_cast<size_t>(e.task) >= speeds.size()) throw;
        throw Error(fmt::format("a worker process died (signal {}) while solving speed {} rad/s", e.signal,
                                speeds[static_cast<size_t>(e.task)]));
    }
}

std::vector<QuadraticSpectrum> solve_speeds_unchecked(const SolverFactory& make, const std::vector<double>& speeds,
                                                      Workers workers,
                                                      const std::function<void(size_t, size_t)>& progress) {
    return run_on_workers(
        make, speeds.size(), workers,
        [&](SpectrumSolver& solve, size_t i) {
            QuadraticSpectrum s = solve(speeds[i]);
            s.speed = speeds[i];
            return s;
        },
        progress);
}

}  // namespace gyrokit
