// for_each_index on the threads kept for parallel loops: every index once, the
// first exception after all have run, loops inside loops and loops from several
// threads at once.
#include <gyrokit/core/parallel.hpp>

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace gyrokit;

TEST_CASE("for_each_index runs every index once on any number of threads", "[parallel]") {
    for (int threads : {1, 2, 3, 8}) {
        for (std::size_t n : {0, 1, 2, 7, 1000}) {
            std::vector<int> hits(n, 0);
            for (int round = 0; round < 20; ++round) for_each_index(n, threads, [&](std::size_t i) { ++hits[i]; });
            for (std::size_t i = 0; i < n; ++i) CHECK(hits[i] == 20);
        }
    }
}

TEST_CASE("for_each_index rethrows the first exception after every index has run", "[parallel]") {
    std::vector<std::atomic<int>> hits(100);
    CHECK_THROWS_WITH(for_each_index(hits.size(), 4,
                                     [&](std::size_t i) {
                                         ++hits[i];
                                         if (i % 10 == 3) throw std::runtime_error("index failed");
                                     }),
                      "index failed");
    for (const auto& h : hits) CHECK(h.load() == 1);
}

TEST_CASE("for_each_index inside a loop and from several threads at once", "[parallel]") {
    // Inner loops run on their caller where it is a kept thread; the outer ones of four
    // threads at once share the kept threads: all finish, each index once.
    std::vector<std::thread> callers;
    std::vector<long> sums(4, 0);
    for (int c = 0; c < 4; ++c)
        callers.emplace_back([&sums, c] {
            std::vector<long> part(50, 0);
            for_each_index(part.size(), 3, [&](std::size_t i) {
                std::vector<long> inner(20, 0);
                for_each_index(inner.size(), 3, [&](std::size_t j) { inner[j] = static_cast<long>(i * j); });
                part[i] = std::accumulate(inner.begin(), inner.end(), 0L);
            });
            sums[static_cast<std::size_t>(c)] = std::accumulate(part.begin(), part.end(), 0L);
        });
    for (std::thread& t : callers) t.join();
    // sum over i < 50, j < 20 of i j = (49 * 50 / 2) (19 * 20 / 2)
    for (long s : sums) CHECK(s == 1225L * 190L);
}

TEST_CASE("a loop gets helpers while another caller's long loop holds the kept threads", "[parallel]") {
    // A: two indices that wait until B is done, holding a kept thread (and A's caller).
    // B, from another thread: its two indices must run at once, one on a helper, which the
    // pool starts because its threads are busy (before, B's helper sat queued behind A).
    std::atomic<bool> b_done{false};
    std::atomic<int> a_running{0};
    std::thread a([&] {
        for_each_index(2, 2, [&](std::size_t) {
            ++a_running;
            while (!b_done) std::this_thread::yield();
        });
    });
    while (a_running < 2) std::this_thread::yield();   // A holds its caller and a kept thread
    std::atomic<int> arrived{0};
    bool together = true;
    for_each_index(2, 2, [&](std::size_t) {
        ++arrived;
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (arrived < 2 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        if (arrived < 2) together = false;
    });
    b_done = true;
    a.join();
    CHECK(together);
}

TEST_CASE("run_beside: workers on threads of their own beside the caller, joined before it returns", "[parallel]") {
    std::atomic<int> ran{0};
    std::vector<int> seen;
    run_beside(3, [&] { ++ran; }, [&] { seen.push_back(1); });
    CHECK(ran == 3);
    CHECK(seen.size() == 1);
    // The caller's exception after every worker has finished.
    std::atomic<bool> stop{false};
    std::atomic<int> finished{0};
    CHECK_THROWS_WITH(run_beside(
                          2,
                          [&] {
                              while (!stop) std::this_thread::yield();
                              ++finished;
                          },
                          [&] {
                              stop = true;
                              throw std::runtime_error("writer failed");
                          }),
                      "writer failed");
    CHECK(finished == 2);
}
