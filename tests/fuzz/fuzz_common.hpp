// Shared by the fuzz targets: an input as a file (the readers take paths) and
// the rule that bad input may only end in gyrokit's own errors.
#pragma once

#include <gyrokit/core/error.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace fuzz {

// The input written to a file of this process (one path per target and process).
inline std::string as_file(const uint8_t* data, size_t size, const char* suffix) {
    static const std::string path = "/tmp/gyrokit_fuzz_" + std::to_string(getpid()) + suffix;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return path;
    if (size > 0) std::fwrite(data, 1, size, f);
    std::fclose(f);
    return path;
}

// Runs `f`; a gyrokit::Error (InputError, SolverError) is the expected answer
// to bad input. Anything else escapes and the fuzzer reports it: a crash, a
// sanitizer finding, an exception of another type, a hang (-timeout).
template <class F>
void expect_gyrokit_errors_only(F&& f) {
    try {
        f();
    } catch (const gyrokit::Error&) {
    }
}

}  // namespace fuzz
