// A result file written whole or not at all: a reader (or a crash) never sees half
// of it, and an old file stays until the new one is complete.
#pragma once

#include <string>

namespace gyrokit {

// `text` written to `path`: to a temporary file beside it, then renamed over it.
// InputError naming the path, `what` is written and why, if it cannot be.
void replace_file(const std::string& path, const std::string& text, const std::string& what);

}  // namespace gyrokit
