// f(0) ... f(n - 1) on up to `threads` threads: each index once, in no fixed
// order, so f must write only its own index's results. The first exception
// thrown is rethrown after every thread has finished.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace gyrokit {

template <class F>
void for_each_index(std::size_t n, int threads, const F& f) {
    const std::size_t t = std::min(n, static_cast<std::size_t>(std::max(1, threads)));
    if (t <= 1) {
        for (std::size_t i = 0; i < n; ++i) f(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex lock;
    const auto work = [&]() {
        try {
            for (std::size_t i = next++; i < n; i = next++) f(i);
        } catch (...) {
            const std::lock_guard<std::mutex> g(lock);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    try {
        for (std::size_t k = 1; k < t; ++k) pool.emplace_back(work);
    } catch (...) {   // no more threads: the ones started and this one do the work
    }
    work();
    for (std::thread& th : pool) th.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace gyrokit
