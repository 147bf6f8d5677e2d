// f(0) ... f(n - 1) on up to `threads` threads: each index once, in no fixed
// order, so f must write only its own index's results. The first exception
// thrown is rethrown after every index has finished. The calling thread takes
// part; the others come from threads kept for such loops (starting threads for
// every loop would cost as much as a small model's whole step along the
// branches), and a loop inside one of theirs runs on its caller alone.
#pragma once

#include <cstddef>
#include <functional>

namespace gyrokit {

namespace detail {
void run_parallel(std::size_t n, int threads, const std::function<void(std::size_t)>& f);
// `release` runs on each kept thread that goes to sleep (no loop for a while):
// for thread-local caches, which a thread that ends would free.
void on_idle(void (*release)());
}

// Workers that last a whole run: f() on `threads` threads of their own while the caller
// runs on_caller() (e.g. writing their results in order as they come); every thread is
// joined before it returns, and on_caller's exception is rethrown then (on_caller tells
// the workers to stop before it throws). Not the kept pool: a run would hold its threads
// from every other loop for its whole length. Where no thread can be started, Error.
void run_beside(int threads, const std::function<void()>& f, const std::function<void()>& on_caller);

template <class F>
void for_each_index(std::size_t n, int threads, const F& f) {
    if (threads <= 1 || n <= 1) {
        for (std::size_t i = 0; i < n; ++i) f(i);
        return;
    }
    detail::run_parallel(n, threads, std::function<void(std::size_t)>(std::cref(f)));
}

}  // namespace gyrokit
