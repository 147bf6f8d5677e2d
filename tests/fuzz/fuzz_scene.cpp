// Scene files of every model type (gyrostat, matrices, fluid_rotor, fe_rotor):
// parse_scene on arbitrary text, files resolved against data/.
#include "fuzz_common.hpp"

#include <gyrokit/scene/scene.hpp>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz::expect_gyrokit_errors_only([&] { gyrokit::parse_scene(text, "fuzz.toml", GYROKIT_DATA_DIR); });
    return 0;
}
