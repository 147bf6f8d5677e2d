#include <gyrokit/core/parallel.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include <unistd.h>

namespace gyrokit::detail {

namespace {

// One parallel loop: the indices are taken in turn by whoever works on it; the
// caller waits until every index is done. Helpers that come after the last index
// was taken touch only this object (kept alive by their reference), never f.
struct Loop {
    std::size_t n = 0;
    const std::function<void(std::size_t)>* f = nullptr;
    std::atomic<std::size_t> next{0}, done{0};
    std::mutex lock;
    std::condition_variable finished;
    std::exception_ptr failure;

    void work() {
        for (std::size_t i = next++; i < n; i = next++) {
            try {
                (*f)(i);
            } catch (...) {
                const std::lock_guard<std::mutex> g(lock);
                if (!failure) failure = std::current_exception();
            }
            if (++done == n) {
                const std::lock_guard<std::mutex> g(lock);
                finished.notify_all();
            }
        }
    }
};

thread_local bool in_pool = false;

// What a kept thread releases when it goes to sleep (its thread-local caches).
// Never destroyed, as the pool: its threads outlive the static destructors at exit.
std::vector<void (*)()>& idle_hooks() {
    static auto* hooks = new std::vector<void (*)()>;
    return *hooks;
}
std::mutex& hooks_lock() {
    static auto* m = new std::mutex;
    return *m;
}

// Threads that wait for loops to help with; never destroyed (detached, they end
// with the process). Owned by the process that made them: a forked worker process
// has none of them and starts its own threads per loop.
class Pool {
public:
    static Pool& instance() {
        static Pool* pool = new Pool;
        return *pool;
    }

    bool usable() const { return ::getpid() == owner_; }

    void offer(const std::shared_ptr<Loop>& loop, std::size_t helpers) {
        {
            const std::lock_guard<std::mutex> g(lock_);
            // Enough threads for the loops queued and this one: a thread busy with a long
            // loop (another caller's) is not one this loop can count on.
            const std::size_t idle = idle_.load(), queued = waiting_.load();
            std::size_t free = idle > queued ? idle - queued : 0;
            try {
                while (free < helpers && started_ < kMaxThreads) {
                    std::thread(&Pool::serve, this).detach();
                    ++started_;
                    ++free;
                }
            } catch (...) {   // no more threads: those there and the caller do the work
            }
            for (std::size_t k = 0; k < helpers; ++k) queue_.push_back(loop);
            waiting_ += helpers;
        }
        wake_.notify_all();
    }

private:
    static constexpr std::size_t kMaxThreads = 256;

    void serve() {
        in_pool = true;
        ++idle_;
        for (;;) {
            // A loop often follows the last within microseconds (the steps of a walk):
            // look for one for a while before sleeping, since waking a thread costs
            // about as long as a small loop.
            for (int k = 0; k < kSpins && waiting_.load(std::memory_order_relaxed) == 0; ++k) std::this_thread::yield();
            if (waiting_.load() == 0) {   // going to sleep: nothing kept for the next loop
                const std::lock_guard<std::mutex> g(hooks_lock());
                for (void (*release)() : idle_hooks()) release();
            }
            std::shared_ptr<Loop> loop;
            {
                std::unique_lock<std::mutex> g(lock_);
                wake_.wait(g, [&] { return !queue_.empty(); });
                loop = std::move(queue_.front());
                queue_.pop_front();
                --waiting_;
                --idle_;
            }
            loop->work();
            ++idle_;
        }
    }
    static constexpr int kSpins = 2000;
    std::atomic<std::size_t> waiting_{0};
    std::atomic<std::size_t> idle_{0};   // threads not in a loop's work (waiting, or looking for one)

    const pid_t owner_ = ::getpid();
    std::mutex lock_;
    std::condition_variable wake_;
    std::deque<std::shared_ptr<Loop>> queue_;
    std::size_t started_ = 0;
};

}  // namespace

void on_idle(void (*release)()) {
    const std::lock_guard<std::mutex> g(hooks_lock());
    idle_hooks().push_back(release);
}

void run_parallel(std::size_t n, int threads, const std::function<void(std::size_t)>& f) {
    const std::size_t t = std::min(n, static_cast<std::size_t>(std::max(1, threads)));
    auto loop = std::make_shared<Loop>();
    loop->n = n;
    loop->f = &f;
    std::vector<std::thread> own;   // a worker process's (no pool there)
    if (t > 1 && !in_pool) {
        Pool& pool = Pool::instance();
        if (pool.usable()) {
            pool.offer(loop, t - 1);
        } else {
            try {
                for (std::size_t k = 1; k < t; ++k) own.emplace_back([loop] { loop->work(); });
            } catch (...) {   // no more threads: the ones started and this one do the work
            }
        }
    }
    loop->work();
    // The last indices are the helpers': wait for them awake a while (waking a
    // sleeping thread costs about as long as one index of a small model's step).
    for (int k = 0; k < 2000 && loop->done.load() != n; ++k) std::this_thread::yield();
    {
        std::unique_lock<std::mutex> g(loop->lock);
        loop->finished.wait(g, [&] { return loop->done.load() == n; });
    }
    for (std::thread& th : own) th.join();
    if (loop->failure) std::rethrow_exception(loop->failure);
}

}  // namespace gyrokit::detail

namespace gyrokit {

void run_beside(int threads, const std::function<void()>& f, const std::function<void()>& on_caller) {
    std::vector<std::thread> own;
    try {
        for (int k = 0; k < std::max(1, threads); ++k) own.emplace_back(f);
    } catch (const std::system_error&) {   // fewer threads: those started do the work
        if (own.empty()) throw Error("cannot start a worker thread (the system's limit); use fewer jobs");
    }
    std::exception_ptr failure;
    try {
        on_caller();
    } catch (...) {
        failure = std::current_exception();
    }
    for (std::thread& th : own) th.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace gyrokit
