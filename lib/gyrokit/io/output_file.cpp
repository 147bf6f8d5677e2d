#include <gyrokit/io/output_file.hpp>

#include <gyrokit/core/error.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

namespace gyrokit {

void replace_file(const std::string& path, const std::string& text, const std::string& what) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.close();
        if (!out) {
            const std::string why = std::strerror(errno);
            std::remove(tmp.c_str());
            throw InputError(fmt::format("{}: cannot write the {} ({})", path, what, why));
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw InputError(fmt::format("{}: cannot write the {} ({})", path, what, ec.message()));
    }
}

}  // namespace gyrokit
