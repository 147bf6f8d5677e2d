#include <gyrokit/core/error.hpp>

#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace gyrokit {

namespace {

constexpr char kOpen = '\x1e', kClose = '\x1f';
// Marks a field named as a noun ("run_up needs acceleration"): no " =" after it.
constexpr char kNoun = '~';

// Calls out(text piece) and field(name) in order; a mark is a field only when it
// closes and holds a snake_case name (a stray byte in a quoted path stays text).
template <class Text, class Field>
void scan(const std::string& s, Text out, Field field) {
    std::size_t at = 0;
    while (at < s.size()) {
        const std::size_t open = s.find(kOpen, at);
        if (open == std::string::npos) break;
        const std::size_t close = s.find(kClose, open + 1);
        const std::size_t first = open + 1 < s.size() && s[open + 1] == kNoun ? open + 2 : open + 1;
        bool name = close != std::string::npos && close > first;
        for (std::size_t i = first; name && i < close; ++i)
            name = (s[i] >= 'a' && s[i] <= 'z') || s[i] == '_';
        if (!name) {
            out(s.substr(at, open + 1 - at));
            at = open + 1;
            continue;
        }
        out(s.substr(at, open - at));
        field(s.substr(open + 1, close - open - 1));   // a noun keeps its mark
        at = close + 1;
    }
    out(s.substr(at));
}

}  // namespace

std::string spell_fields(const std::string& text, const FieldSpelling& spell) {
    std::string r;
    scan(
        text, [&](const std::string& piece) { r += piece; },
        [&](const std::string& marked) {
            const bool noun = marked[0] == kNoun;
            const std::string name = noun ? marked.substr(1) : marked;
            std::string words = spell ? spell(name) : std::string();
            if (words.empty()) words = name + " =";
            if (noun && words.size() > 2 && words.compare(words.size() - 2, 2, " =") == 0) words.resize(words.size() - 2);
            r += words;
        });
    return r;
}

std::string option_field(const std::string& name) { return kOpen + name + kClose; }

std::string option_noun(const std::string& name) { return std::string(1, kOpen) + kNoun + name + kClose; }

Error::Error(const std::string& text) : std::runtime_error(spell_fields(text, {})), text_(text) {}

std::string Error::message(const FieldSpelling& spell) const { return spell_fields(text_, spell); }

std::vector<std::string> Error::fields() const {
    std::vector<std::string> names;
    scan(text_, [](const std::string&) {}, [&](const std::string& name) {
        names.push_back(name[0] == kNoun ? name.substr(1) : name);
    });
    return names;
}

void check_parameter(bool ok, const std::string& origin, const char* key, double v, const char* allowed) {
    if (!ok) throw InputError(fmt::format("{}: {} = {}: out of range; allowed: {}", origin, key, v, allowed));
    if (v != 0.0 && std::fabs(v) < std::numeric_limits<double>::min())
        throw InputError(fmt::format("{}: {} = {}: a subnormal number, which has lost precision; allowed: magnitudes "
                                     "of at least {}",
                                     origin, key, v, std::numeric_limits<double>::min()));
}

}  // namespace gyrokit
