#include <gyrokit/core/error.hpp>

namespace gyrokit {

namespace {

constexpr char kOpen = '\x1e', kClose = '\x1f';

// Calls out(text piece) and field(name) in order; a mark is a field only when it
// closes and holds a snake_case name (a stray byte in a quoted path stays text).
template <class Text, class Field>
void scan(const std::string& s, Text out, Field field) {
    std::size_t at = 0;
    while (at < s.size()) {
        const std::size_t open = s.find(kOpen, at);
        if (open == std::string::npos) break;
        const std::size_t close = s.find(kClose, open + 1);
        bool name = close != std::string::npos && close > open + 1;
        for (std::size_t i = open + 1; name && i < close; ++i)
            name = (s[i] >= 'a' && s[i] <= 'z') || s[i] == '_';
        if (!name) {
            out(s.substr(at, open + 1 - at));
            at = open + 1;
            continue;
        }
        out(s.substr(at, open - at));
        field(s.substr(open + 1, close - open - 1));
        at = close + 1;
    }
    out(s.substr(at));
}

}  // namespace

std::string spell_fields(const std::string& text, const FieldSpelling& spell) {
    std::string r;
    scan(
        text, [&](const std::string& piece) { r += piece; },
        [&](const std::string& name) {
            const std::string words = spell ? spell(name) : std::string();
            r += words.empty() ? name + " =" : words;
        });
    return r;
}

std::string option_field(const std::string& name) { return kOpen + name + kClose; }

Error::Error(const std::string& text) : std::runtime_error(spell_fields(text, {})), text_(text) {}

std::string Error::message(const FieldSpelling& spell) const { return spell_fields(text_, spell); }

std::vector<std::string> Error::fields() const {
    std::vector<std::string> names;
    scan(text_, [](const std::string&) {}, [&](const std::string& name) { names.push_back(name); });
    return names;
}

}  // namespace gyrokit
