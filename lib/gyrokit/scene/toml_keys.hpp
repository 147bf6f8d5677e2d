// Typed, range-checked access to the keys of one TOML table. Every error is an
// InputError naming the file, the table, the key, the value and what is allowed.
// Shared by all readers of the library (scenes, balancer scenes, sweeps); it holds
// toml++, so it is not installed (lib/CMakeLists.txt).
#pragma once

#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <toml++/toml.h>

namespace gyrokit {

// TOML text parsed, a syntax error an InputError naming `origin`, the line and the column:
// the one parse of every reader (scenes, balancer scenes, sweeps).
inline toml::table parse_toml(const std::string& text, const std::string& origin) {
    try {
        return toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        const auto& b = e.source().begin;
        throw InputError(fmt::format("{}: line {}, column {}: {}", origin, b.line, b.column, e.description()));
    }
}

class TomlKeys {
public:
    TomlKeys(const std::string& file, std::string table, const toml::table& t) : file_(file), table_(std::move(table)), t_(t) {}

    // Rejects keys outside `allowed`.
    void only(const std::set<std::string>& allowed) const {
        for (const auto& [k, v] : t_) {
            const std::string key(k.str());
            if (!allowed.count(key)) {
                std::string list;
                for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
                // A key of any length is named by its first 60 characters.
                const std::string shown = key.size() > 60 ? key.substr(0, 60) + "..." : key;
                throw InputError(fmt::format("{}: [{}] unknown key '{}'; allowed: {}", file_, table_, shown, list));
            }
        }
    }
    bool has(const std::string& key) const { return t_.contains(key); }

    // A number with lower bound `min` (strict if `strict`).
    double number(const std::string& key, std::optional<double> fallback, double min, bool strict,
                  const char* unit) const {
        const toml::node* n = t_.get(key);
        if (!n) {
            if (fallback) return *fallback;
            throw InputError(fmt::format("{}: [{}] key '{}' is missing; required: a number {} {} ({})", file_,
                                         table_, key, strict ? ">" : ">=", min, unit));
        }
        std::optional<double> v = n->value<double>();
        if (!v || !(n->is_floating_point() || n->is_integer()))
            throw InputError(fmt::format("{}: [{}] {} is not a number; allowed: a number {} {} ({})", file_, table_,
                                         key, strict ? ">" : ">=", min, unit));
        if (!std::isfinite(*v) || (strict ? *v <= min : *v < min))
            throw InputError(fmt::format("{}: [{}] {} = {}: out of range; allowed: {} {} ({})", file_, table_, key,
                                         *v, strict ? ">" : ">=", min, unit));
        refuse_subnormal(key, *v);
        return *v;
    }
    // A subnormal double (0 < |v| < 2.2e-308) has lost precision, and its products
    // underflow: never a meaningful parameter, and never silently used.
    void refuse_subnormal(const std::string& key, double v) const {
        if (v != 0.0 && std::fabs(v) < std::numeric_limits<double>::min())
            throw InputError(fmt::format("{}: [{}] {} = {}: a subnormal number, which has lost precision; allowed: "
                                         "magnitudes of at least {}",
                                         file_, table_, key, v, std::numeric_limits<double>::min()));
    }
    double any_number(const std::string& key, const char* unit) const {
        const toml::node* n = t_.get(key);
        if (!n) throw InputError(fmt::format("{}: [{}] key '{}' is missing; required: a finite number ({})", file_,
                                             table_, key, unit));
        std::optional<double> v = n->value<double>();
        if (!v || !std::isfinite(*v))
            throw InputError(fmt::format("{}: [{}] {} must be a finite number ({})", file_, table_, key, unit));
        refuse_subnormal(key, *v);
        return *v;
    }
    long long integer(const std::string& key, long long fallback, long long min, long long max) const {
        const toml::node* n = t_.get(key);
        if (!n) return fallback;
        if (!n->is_integer())
            throw InputError(fmt::format("{}: [{}] {} must be a whole number in [{}, {}]", file_, table_, key, min, max));
        const long long v = *n->value<long long>();
        if (v < min || v > max)
            throw InputError(fmt::format("{}: [{}] {} = {}: out of range; allowed: [{}, {}]", file_, table_, key, v,
                                         min, max));
        return v;
    }
    std::string choice(const std::string& key, const std::string& fallback, const std::set<std::string>& allowed) const {
        const toml::node* n = t_.get(key);
        if (!n) return fallback;
        std::optional<std::string> v = n->value<std::string>();
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        if (!v && allowed.empty())
            throw InputError(fmt::format("{}: [{}] {} must be a string", file_, table_, key));
        if (!v || (!allowed.empty() && !allowed.count(*v)))
            throw InputError(fmt::format("{}: [{}] {} = {}: allowed: {}", file_, table_, key,
                                         v ? "'" + *v + "'" : std::string("(not a string)"), list));
        return *v;
    }
    const toml::table& table() const { return t_; }
    const std::string& file() const { return file_; }
    // A string, `fallback` where the key is absent.
    std::string text(const std::string& key, const std::string& fallback) const {
        const toml::node* n = t_.get(key);
        if (!n) return fallback;
        std::optional<std::string> v = n->value<std::string>();
        if (!v || !n->is_string()) throw InputError(fmt::format("{}: [{}] {} must be a string", file_, table_, key));
        return *v;
    }
    std::string where(const std::string& key) const { return fmt::format("{}: [{}] {}", file_, table_, key); }

private:
    std::string file_, table_;
    const toml::table& t_;
};

}  // namespace gyrokit
