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

template <class F>
void for_each_index(std::size_t n, int threads, const F& f) {
    if (threads <= 1 || n <= 1) {
        for (std::size_t i = 0; i < n; ++i) f(i);
        return;
    }
    detail::run_parallel(n, threads, std::function<void(std::size_t)>(std::cref(f)));
}

}  // namespace gyrokit
