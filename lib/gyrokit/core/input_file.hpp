// The checks every input file passes before it is read: it exists and is a
// regular file (a directory, a device such as /dev/zero or a FIFO would read
// nothing or never end) of bounded size, so that a wrong path is one clear
// line and never a hang or gigabytes of memory.
#pragma once

#include <cstdint>
#include <string>

namespace gyrokit {

// Scenes, sweep files and other TOML inputs.
constexpr std::uintmax_t kMaxTextInputBytes = 64ull << 20;    // 64 MiB
// Matrix Market files, bearing tables and result files.
constexpr std::uintmax_t kMaxDataInputBytes = 4ull << 30;     // 4 GiB

// InputError naming `path`, what it is and what was expected (`what`, e.g.
// "scene file"), unless it is a regular file of at most `max_bytes`. The file's
// content is never quoted.
void check_input_file(const std::string& path, const std::string& what, std::uintmax_t max_bytes);

// The whole text of a TOML input after check_input_file, with its nesting checked:
// at most kMaxTomlDepth levels of arrays and inline tables and of dotted key
// parts on one line (the parser recurses per level: a 50,000-level header would
// overflow the stack).
constexpr int kMaxTomlDepth = 64;
std::string read_toml_text(const std::string& path, const std::string& what);
void check_toml_depth(const std::string& text, const std::string& origin);

}  // namespace gyrokit
