// Screening result files as --resume and --merge read them, for the sweep
// data/screen_centrifuge.toml.
#include "fuzz_common.hpp"

#include <gyrokit/screening/screening.hpp>
#include <gyrokit/screening/sweep.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const gyrokit::Sweep sweep = gyrokit::read_sweep(std::string(GYROKIT_DATA_DIR) + "/screen_centrifuge.toml");
    const std::string path = fuzz::as_file(data, size, ".csv");
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::merge_results(sweep, {path}, false); });
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::merge_results(sweep, {path}, true); });
    return 0;
}
