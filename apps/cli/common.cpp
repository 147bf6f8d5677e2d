#include "cli/common.hpp"

#include "core/error.hpp"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <unistd.h>

namespace gyrokit::cli {

void add_common(CLI::App* c, Common& o, bool with_speeds) {
    c->add_option("scene", o.scene, "scene file (TOML)")->required();
    c->add_option("--format", o.format, "output format: table, csv or json")->capture_default_str();
    c->add_option("--units", o.units, "unit of speeds and frequencies on the command line and in the output: "
                                      "rad/s, Hz or rpm")->capture_default_str();
    c->add_option("--method", o.method, "eigensolver: qz (scaled QZ, default) or state (M^-1 state matrix)")
        ->capture_default_str();
    if (with_speeds) c->add_option("--speeds", o.speeds, "speed range FROM:TO:N (overrides the scene's [speeds])");
}

TableFormat parse_format(const Common& o) { return parse_table_format(o.format); }

Context open_scene(const Common& o, bool need_speeds) {
    Context c;
    c.format = parse_format(o);
    c.unit = SpeedUnit::parse(o.units);
    c.eig.method = parse_eigen_method(o.method);
    check_plot_path(o.plot);
    c.scene = load_scene(o.scene);
    if (!o.speeds.empty()) {
        c.speeds = SpeedRange::parse(o.speeds, "--speeds", c.unit.factor).points();
    } else if (c.scene.speeds) {
        c.speeds = c.scene.speeds->points();
    } else if (need_speeds) {
        throw InputError(o.scene + ": no speed range; give --speeds FROM:TO:N or a [speeds] table in the scene");
    }
    return c;
}

double parse_speed(const std::string& text, const std::string& option, const SpeedUnit& u) {
    try {
        size_t pos = 0;
        const double v = std::stod(text, &pos);
        if (pos == text.size() && std::isfinite(v) && v >= 0.0) return v / u.factor;
    } catch (const std::exception&) {
    }
    throw InputError(fmt::format("{} '{}': allowed: a finite number >= 0 ({})", option, text, u.name));
}

std::vector<int> parse_harmonics(const std::string& text, const std::vector<int>& fallback) {
    if (text.empty()) return fallback;
    std::vector<int> h;
    size_t start = 0;
    while (start <= text.size()) {
        const size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        try {
            size_t pos = 0;
            const long v = std::stol(item, &pos);
            if (pos != item.size() || v < 1 || v > 1000) throw std::out_of_range(item);
            h.push_back(static_cast<int>(v));
        } catch (const std::exception&) {
            throw InputError(fmt::format("--harmonics '{}': allowed: whole numbers in [1, 1000] separated by commas",
                                         text));
        }
        start = end + 1;
    }
    return h;
}

void check_plot_path(const std::string& path) {
    if (path.empty()) return;
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext != ".svg" && ext != ".png")
        throw InputError(fmt::format("--plot '{}': unsupported extension '{}'; allowed: .svg, .png", path, ext));
}

void plot_if(const std::string& path, const Figure& f) {
    if (path.empty()) return;
    render_figure(f, path);
    std::cerr << "wrote " << path << "\n";
}

std::function<void(size_t, size_t)> progress_bar(const std::string& what) {
    if (!isatty(STDERR_FILENO)) return {};
    return [what](size_t done, size_t total) {
        const int width = 40, filled = static_cast<int>(width * done / std::max<size_t>(total, 1));
        std::cerr << "\r" << what << " [" << std::string(static_cast<size_t>(filled), '#')
                  << std::string(static_cast<size_t>(width - filled), ' ') << "] " << done << "/" << total
                  << (done == total ? "\n" : "") << std::flush;
    };
}

}  // namespace gyrokit::cli
