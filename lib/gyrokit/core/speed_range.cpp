#include <gyrokit/core/speed_range.hpp>

#include <gyrokit/core/constants.hpp>
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/number_text.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <sstream>

namespace gyrokit {

SpeedRange SpeedRange::parse(const std::string& text, const std::string& option) {
    std::istringstream in(text);
    std::string a, b, c;
    if (!std::getline(in, a, ':') || !std::getline(in, b, ':') || !std::getline(in, c) || a.empty() ||
        b.empty() || c.empty())
        throw InputError(fmt::format("{} '{}': expected FROM:TO:N, e.g. 0:60:601", option, text));
    SpeedRange r;
    try {
        size_t pc = 0;
        const std::optional<double> fa = decimal_number(a), fb = decimal_number(b);
        if (!fa || !fb) throw std::invalid_argument("not a decimal number");
        r.from = *fa;
        r.to = *fb;
        const long n = std::stol(c, &pc);
        if (pc != c.size()) throw std::invalid_argument("trailing");
        if (n < 1 || n > 10000000) throw std::out_of_range("count");
        r.count = static_cast<int>(n);
    } catch (const std::exception&) {
        throw InputError(fmt::format("{} '{}': expected FROM:TO:N with numbers FROM, TO and a whole "
                                     "number N in [1, 10000000]",
                                     option, text));
    }
    r.validate(option + " '" + text + "'");   // as written: the message quotes the user's numbers
    return r;
}

void SpeedRange::validate(const std::string& origin) const {
    if (!std::isfinite(from) || !std::isfinite(to))
        throw InputError(fmt::format("{}: speeds must be finite numbers", origin));
    if (from < 0.0)
        throw InputError(fmt::format("{}: FROM = {} is negative; allowed: 0 <= FROM <= TO", origin, from));
    if (from > to)
        throw InputError(fmt::format("{}: FROM = {} is greater than TO = {}; allowed: FROM <= TO", origin, from, to));
    if (count < 1) throw InputError(fmt::format("{}: N = {} points; allowed: N >= 1", origin, count));
    if (count == 1 && from != to)
        throw InputError(fmt::format("{}: one point needs FROM = TO; allowed for FROM < TO: N >= 2", origin));
    if (count >= 2 && from == to)
        throw InputError(fmt::format("{}: FROM = TO = {} with N = {} points; allowed: FROM < TO", origin, from, count));
    // Points closer than rounding would repeat: a sweep needs distinct speeds.
    if (count >= 2 && !((to - from) / (count - 1) > 1e-12 * std::max(1.0, to)))
        throw InputError(fmt::format("{}: the step (TO - FROM)/(N - 1) = {:.3g} is below 1e-12 of max(1, TO) = {:.6g}; "
                                     "allowed: a step that keeps the {} speeds distinct",
                                     origin, (to - from) / (count - 1), std::max(1.0, to), count));
}

std::vector<double> SpeedRange::points() const {
    std::vector<double> w(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i)
        w[static_cast<size_t>(i)] = count == 1 ? from : from + (to - from) * i / (count - 1);
    if (count > 1) w.back() = to;
    return w;
}

SpeedUnit SpeedUnit::parse(const std::string& name) {
    // Case does not matter: Hz, hz and HZ are one unit.
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (lower == "rad/s") return {"rad/s", 1.0};
    if (lower == "hz") return {"Hz", 1.0 / (2.0 * kPi)};
    if (lower == "rpm") return {"rpm", 60.0 / (2.0 * kPi)};
    throw InputError(fmt::format("{} '{}' is unknown; allowed: rad/s, Hz, rpm", option_field("units"), name));
}

std::string SpeedUnit::per_second() const { return name == "rad/s" ? "rad/s^2" : name + "/s"; }

std::string SpeedUnit::column(const std::string& base) const {
    std::string suffix;
    for (const char ch : name) suffix += ch == '/' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return base + "_" + suffix;
}

}  // namespace gyrokit
