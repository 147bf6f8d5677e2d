#include <gyrokit/core/length_unit.hpp>

#include <gyrokit/core/error.hpp>

#include <fmt/format.h>

namespace gyrokit {

LengthUnit LengthUnit::parse(const std::string& name) {
    if (name == "m") return {"m", 1.0};
    if (name == "mm") return {"mm", 1e-3};
    throw InputError(fmt::format("length_unit = '{}': allowed: \"m\" or \"mm\"", name));
}

}  // namespace gyrokit
