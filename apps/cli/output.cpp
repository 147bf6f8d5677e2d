// What the commands print besides their tables: plots, the CSV note, progress bars.
#include "cli/common.hpp"
#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <unistd.h>

namespace gyrokit::cli {

CLI::Option* add_output_option(CLI::App* c, const std::string& name, std::string& value, const std::string& help,
                               bool folder) {
    return c->add_option(name, value, help)->group(kOutputGroup)->type_name(folder ? "DIR" : "FILE");
}

void claim_outputs(const CLI::App& command) {
    RunFiles* run = current_run();
    if (!run) return;
    for (const CLI::Option* opt : command.get_options()) {
        if (opt->get_group() != kOutputGroup || opt->count() == 0 || opt->get_type_name() == "DIR") continue;
        for (const auto& value : opt->results()) run->claim_output(value, opt->get_name());
    }
}

void check_plot_path(const std::string& path, const std::string& option) {
    if (path.empty()) return;
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext != ".svg" && ext != ".png")
        throw InputError(fmt::format("{} '{}': unsupported extension '{}'; allowed: .svg, .png", option, path, ext));
}

void plot_if(const std::string& path, const Figure& f, const std::string& option) {
    if (path.empty()) return;
    render_figure(f, path, option);
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
