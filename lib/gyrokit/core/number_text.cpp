#include <gyrokit/core/number_text.hpp>

#include <gyrokit/core/error.hpp>

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

// The value from_chars reads from all of `text`, finite (a subnormal one included).
std::optional<double> finite_decimal(const std::string& text) {
    double v = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v, std::chars_format::general);
    if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(v)) return std::nullopt;
    return v;
}

bool subnormal(double v) { return v != 0.0 && std::abs(v) < std::numeric_limits<double>::min(); }

}  // namespace

std::optional<double> decimal_number(const std::string& text) {
    const std::optional<double> v = finite_decimal(text);
    if (v && subnormal(*v)) return std::nullopt;
    return v;
}

double parse_decimal(const std::string& text, const std::string& option, const std::string& allowed) {
    const std::optional<double> v = finite_decimal(text);
    if (v && subnormal(*v))
        throw InputError(fmt::format("{} '{}': a subnormal number, which has lost precision; allowed: {} (0, or "
                                     "magnitudes of at least 2.2250738585072014e-308)",
                                     option, text, allowed));
    if (!v) throw InputError(fmt::format("{} '{}': allowed: {}", option, text, allowed));
    return *v;
}

}  // namespace gyrokit
