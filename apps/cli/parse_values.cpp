// The CLI's own value syntax: speeds and orders, harmonic lists, probes.
#include "cli/common.hpp"
#include <gyrokit/core/number_text.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>

namespace gyrokit::cli {

std::vector<Probe> parse_probes(const std::string& text, const GyroscopicSystem& sys) {
    std::vector<Probe> out;
    std::size_t start = 0;
    while (!text.empty() && start <= text.size()) {
        const std::size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        start = end + 1;
        const std::size_t at = item.find('@');
        int node = 0;
        double angle = 0.0;
        try {
            std::size_t a = 0;
            if (at == std::string::npos) throw std::invalid_argument(item);
            node = std::stoi(item.substr(0, at), &a);
            const std::optional<double> x = decimal_number(item.substr(at + 1));
            if (a != at || !x || std::abs(*x) > 360.0) throw std::invalid_argument(item);
            angle = *x;
        } catch (const std::exception&) {
            throw InputError(fmt::format("--probes '{}': allowed: NODE@ANGLE items separated by commas, e.g. "
                                         "12@45,12@-45 (angle in degrees from +x towards +y, -360 to 360)",
                                         item));
        }
        for (const Probe& p : out)
            if (p.name == item) throw InputError(fmt::format("--probes: '{}' is listed twice; allowed: each once", item));
        try {
            out.push_back(probe_at_node(sys, item, node, angle));
        } catch (const InputError& e) {
            throw InputError(fmt::format("--probes {}: {}", item, e.what()));
        }
    }
    return out;
}

namespace {

// A finite number >= 0 spelled out completely, or nothing.
std::optional<double> nonnegative(const std::string& text) {
    const std::optional<double> v = decimal_number(text);
    if (v && *v >= 0.0) return v;
    return std::nullopt;
}

}  // namespace

double parse_speed(const std::string& text, const std::string& option, const SpeedUnit& u) {
    if (const auto v = nonnegative(text)) return *v / u.factor;
    throw InputError(fmt::format("{} '{}': allowed: a finite number >= 0 ({})", option, text, u.name));
}

double parse_number(const std::string& text, const std::string& option) {
    if (const auto v = decimal_number(text)) return *v;
    throw InputError(fmt::format("{} '{}': allowed: a number", option, text));
}

std::vector<int> parse_harmonics(const std::string& text, const std::vector<int>& fallback,
                                 const std::string& option) {
    if (text.empty()) return fallback;
    std::vector<int> h;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        long v = 0;
        try {
            size_t pos = 0;
            v = std::stol(item, &pos);
            if (pos != item.size() || v < 1 || v > 1000) throw std::out_of_range(item);
        } catch (const std::exception&) {
            throw InputError(fmt::format("{} '{}': allowed: whole numbers in [1, 1000] separated by commas", option,
                                         text));
        }
        if (std::find(h.begin(), h.end(), static_cast<int>(v)) != h.end())
            throw InputError(fmt::format("{} '{}': {} is listed twice; allowed: each value once", option, text, v));
        h.push_back(static_cast<int>(v));
        start = end + 1;
    }
    return h;
}

}  // namespace gyrokit::cli
