// Matrix Market files: the dense, sparse and vector readers on the same bytes.
#include "fuzz_common.hpp"

#include <gyrokit/io/matrix_market.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzz::as_file(data, size, ".mtx");
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::read_matrix_market_sparse(path); });
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::read_matrix_market(path); });
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::read_matrix_market_vector(path); });
    return 0;
}
