// Bearing coefficient tables (CSV against speed) for a 4-DOF model.
#include "fuzz_common.hpp"

#include <gyrokit/io/bearing_csv.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzz::as_file(data, size, ".csv");
    fuzz::expect_gyrokit_errors_only([&] {
        const gyrokit::BearingTable t = gyrokit::read_bearing_csv(path, 4);
        t.at(0.0);
        t.at(1e300);
    });
    return 0;
}
