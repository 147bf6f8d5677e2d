#include <gyrokit/core/input_file.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>

#include <cctype>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace gyrokit {

namespace fs = std::filesystem;

void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) {
        if (fs::is_symlink(fs::symlink_status(path, ec)))
            throw InputError(fmt::format("{}: {} is a symbolic link that leads nowhere (or in a loop); expected a {}",
                                         path, what, what));
        throw InputError(fmt::format("{}: {} not found", path, what));
    }
    if (fs::is_directory(st)) throw InputError(fmt::format("{}: is a directory; expected a {}", path, what));
    if (!fs::is_regular_file(st))
        throw InputError(fmt::format("{}: is not a regular file (a device, FIFO or socket); expected a {}", path, what));
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw InputError(fmt::format("{}: cannot read the size of the {} ({})", path, what, ec.message()));
    if (size > max_bytes)
        throw InputError(fmt::format("{}: the {} has {} bytes; allowed: at most {} bytes", path, what, size, max_bytes));
}

void check_toml_depth(const std::string& text, const std::string& origin) {
    enum class In { Code, Basic, Literal, MultiBasic, MultiLiteral, Comment };
    In in = In::Code;
    int depth = 0, dots = 0, line = 1;
    const auto fail = [&](const std::string& what) {
        throw InputError(fmt::format("{}: line {}: {} more than {} levels deep; allowed: at most {}", origin, line, what,
                                     kMaxTomlDepth, kMaxTomlDepth));
    };
    const size_t n = text.size();
    for (size_t i = 0; i < n; ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            dots = 0;
            if (in == In::Comment || in == In::Basic || in == In::Literal) in = In::Code;
            continue;
        }
        switch (in) {
        case In::Comment: break;
        case In::Basic:
            if (c == '\\') ++i;
            else if (c == '"') in = In::Code;
            break;
        case In::Literal:
            if (c == '\'') in = In::Code;
            break;
        case In::MultiBasic:
            if (c == '\\') ++i;
            else if (text.compare(i, 3, "\"\"\"") == 0) in = In::Code, i += 2;
            break;
        case In::MultiLiteral:
            if (text.compare(i, 3, "'''") == 0) in = In::Code, i += 2;
            break;
        case In::Code:
            if (c == '#') in = In::Comment;
            else if (text.compare(i, 3, "\"\"\"") == 0) in = In::MultiBasic, i += 2;
            else if (text.compare(i, 3, "'''") == 0) in = In::MultiLiteral, i += 2;
            else if (c == '"') in = In::Basic;
            else if (c == '\'') in = In::Literal;
            else if (c == '[' || c == '{') {
                if (++depth > kMaxTomlDepth) fail("arrays, tables or inline tables nested");
            } else if (c == ']' || c == '}') {
                depth = std::max(0, depth - 1);
            } else if (c == '.') {
                // A decimal point lies between digits; a key's dot does not.
                const bool number = i > 0 && i + 1 < n && std::isdigit(static_cast<unsigned char>(text[i - 1])) &&
                                    std::isdigit(static_cast<unsigned char>(text[i + 1]));
                if (!number && ++dots > kMaxTomlDepth) fail("a dotted key");
            }
            break;
        }
    }
}

std::string read_toml_text(const std::string& path, const std::string& what) {
    std::string text = *read_input(path, what, kMaxTextInputBytes);
    check_toml_depth(text, path);
    return text;
}

}  // namespace gyrokit
