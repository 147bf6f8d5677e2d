// Sweep files of design studies (the seeds name data/ scenes by absolute path).
#include "fuzz_common.hpp"

#include <gyrokit/screening/sweep.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzz::as_file(data, size, ".toml");
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::read_sweep(path); });
    return 0;
}
