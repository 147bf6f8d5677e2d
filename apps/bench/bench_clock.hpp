// Wall time since a start, for the benchmarks' and the family's timings.
#pragma once

#include <chrono>

namespace gyrokit::bench {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace gyrokit::bench
