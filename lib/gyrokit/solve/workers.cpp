#include <gyrokit/solve/workers.hpp>

#include <gyrokit/solve/spectrum_solver.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/parallel.hpp>
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

int worker_count(int jobs, std::vector<std::string>* notes) {
    if (jobs < 0)
        throw InputError(fmt::format("{} {}: allowed: 0 (all cores) or a count", option_field("jobs"), jobs));
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    if (jobs == 0) return cores;
    if (jobs > cores && notes)
        notes->push_back(fmt::format("{} {} capped to the {} cores of this machine", option_field("jobs"), jobs, cores));
    return std::min(jobs, cores);
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

// The worker process k: solves its block of tasks and writes them (or its error) to f,
// then exits; it never returns into the parent's code.
[[noreturn]] void run_worker(const SolverFactory& make, size_t n, size_t workers, size_t k, const WorkerTask& task,
                             const std::function<void(size_t, size_t)>& progress, std::FILE* f,
                             std::atomic<size_t>* done, std::atomic<long long>* current, pid_t parent) {
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
        // The marked text, so that the parent's error names option fields as its own would.
        const auto* ge = dynamic_cast<const Error*>(&e);
        const std::string what = ge ? ge->marked_text() : std::string(e.what());
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

// Every worker is reaped; one killed by a signal is reported with its task (the first
// such failure is returned). Polled, so that an interrupt requested in the parent alone
// (request_interrupt from another thread, a handler that does not reach the workers)
// stops them at once: `stopped` is then set.
std::exception_ptr reap_workers(const std::vector<pid_t>& pids, const std::atomic<long long>* current,
                                bool& stopped) {
    const size_t workers = pids.size();
    std::exception_ptr crash;
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
    return crash;
}

// The workers' files read back in task order; the first worker's error is rethrown.
// Closes the files.
std::vector<QuadraticSpectrum> read_worker_results(const std::vector<std::FILE*>& files, size_t n) {
    const size_t workers = files.size();
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
        if (pid == 0) run_worker(make, n, workers, k, task, progress, f, done, current, parent);
        files.push_back(f);
        pids.push_back(pid);
    }
    // Every worker is reaped; one killed by a signal is reported with its task.
    bool stopped = false;
    const std::exception_ptr crash = reap_workers(pids, current, stopped);
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
    return read_worker_results(files, n);
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
                           (workers.kind == WorkerKind::Auto && !make.thread_safe());
    if (t > 1 && processes) return run_in_processes(make, n, t, task, progress);
    // One contiguous block of speeds per thread: each thread makes one solver.
    for_each_index(t, static_cast<int>(t), [&](size_t k) { work(k * n / t, (k + 1) * n / t); });
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
    if (make.walks()) {
        SpectrumSolver solve = make.walk(std::max(1, workers.count));
        std::vector<QuadraticSpectrum> out(speeds.size());
        for (size_t i = 0; i < speeds.size(); ++i) {
            throw_if_interrupted();
            out[i] = solve(speeds[i]);
            out[i].speed = speeds[i];
            if (progress) progress(i + 1, speeds.size());
        }
        return out;
    }
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
