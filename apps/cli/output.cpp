// What the commands print besides their tables: plots, the CSV note, progress bars.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <unistd.h>

namespace gyrokit::cli {

void check_plot_path(const std::string& path, const std::string& option) {
    if (path.empty()) return;
    const std::filesystem::path p(path);
    const std::string ext = p.extension().string();
    if (ext != ".svg" && ext != ".png")
        throw InputError(fmt::format("{} '{}': unsupported extension '{}'; allowed: .svg, .png", option, path, ext));
    // Before the analysis runs, not after it: a long run must not end in a picture it cannot write.
    const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec) || ::access(dir.c_str(), W_OK) != 0)
        throw InputError(fmt::format("{} '{}': the folder '{}' does not exist or is not writable; allowed: a file in "
                                     "a writable folder",
                                     option, path, dir.string()));
}

void plot_if(const std::string& path, const Figure& f) {
    if (path.empty()) return;
    render_figure(f, path);
    std::cerr << "wrote " << path << "\n";
}

void write_result(std::ostream& out, const std::vector<Table>& ts, TableFormat f, const std::string& table) {
    std::vector<std::string> left_out;
    gyrokit::write_result(out, ts, f, table, "--table", left_out);
    if (left_out.empty()) return;
    std::string keys;
    for (const auto& k : left_out) keys += (keys.empty() ? "" : ", ") + k;
    std::cerr << "note: CSV holds one table (" << ts.front().key << "); the others with --table " << keys << "\n";
}

namespace {

void draw_bar(const std::string& what, double fraction, const std::string& count, bool last) {
    const int width = 40, filled = static_cast<int>(width * std::clamp(fraction, 0.0, 1.0));
    std::cerr << "\r" << what << " [" << std::string(static_cast<size_t>(filled), '#')
              << std::string(static_cast<size_t>(width - filled), ' ') << "] " << count << (last ? "\n" : "")
              << std::flush;
}

}  // namespace

std::function<void(size_t, size_t)> progress_bar(const std::string& what) {
    if (!isatty(STDERR_FILENO)) return {};
    return [what](size_t done, size_t total) {
        draw_bar(what, static_cast<double>(done) / static_cast<double>(std::max<size_t>(total, 1)),
                 std::to_string(done) + "/" + std::to_string(total), done == total);
    };
}

std::function<void(double)> fraction_bar(const std::string& what) {
    if (!isatty(STDERR_FILENO)) return {};
    return [what](double f) { draw_bar(what, f, fmt::format("{:3.0f} %", 100.0 * f), f >= 1.0); };
}

}  // namespace gyrokit::cli
