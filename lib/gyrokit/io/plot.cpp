#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/output_file.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include <gyrokit/core/error.hpp>

namespace gyrokit {

namespace fs = std::filesystem;

namespace {

// A gnuplot string literal. Single-quoted where the text has no quote (nothing is
// special there); gnuplot 5.4 misreads two '' escapes in a row ("x''"), so text with
// quotes goes double-quoted, where only backslash and double quote need escaping. A
// line break would end the command, so it becomes a space.
std::string gp_quote(const std::string& s) {
    const bool single = s.find('\'') == std::string::npos;
    std::string q = single ? "'" : "\"";
    for (char ch : s) {
        if (ch == '\n' || ch == '\r')
            q += ' ';
        else if (!single && (ch == '\\' || ch == '"'))
            q += std::string("\\") + ch;
        else
            q += ch;
    }
    return q + (single ? "'" : "\"");
}

// A POSIX shell single-quoted word: ' is closed, escaped and reopened.
std::string sh_quote(const std::string& s) {
    std::string q = "'";
    for (char ch : s) q += ch == '\'' ? "'\\''" : std::string(1, ch);
    return q + "'";
}

// Scratch directory for the script, the image and gnuplot's stderr; removed
// however render_figure leaves.
struct TempDir {
    fs::path path;
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "gyrokit-plot-XXXXXX").string();
        if (!mkdtemp(tmpl.data()))
            throw Error(fmt::format("cannot create a temporary directory for gnuplot: {}", std::strerror(errno)));
        path = tmpl;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

std::string with_clause(const Series& s) {
    std::string w;
    if (s.style == "lines") w = "lines lw 1.5";
    else if (s.style == "thin") w = "lines lw 0.7";
    else if (s.style == "dashed") w = "lines dt 2 lw 1.5";
    else if (s.style == "dotted") w = "lines dt 3 lw 1.5";
    else if (s.style == "points") w = "points pt 7 ps 0.6";
    else if (s.style == "linespoints") w = "linespoints pt 7 ps 0.6 lw 1.5";
    else
        throw InputError(fmt::format("unknown plot style '{}' for series '{}'; allowed: lines, thin, "
                                     "dashed, dotted, points, linespoints", s.style, s.label));
    if (!s.color.empty()) w += " lc rgb " + gp_quote(s.color);
    return w + (s.label.empty() ? " notitle" : " title " + gp_quote(s.label));
}

// Appends the series as an inline data block. Points gnuplot cannot draw are
// dropped, and a blank line (a break in the line) marks the gap. Returns the
// number of points kept.
std::size_t append_block(std::string& script, const std::string& name, const Series& s, bool logx, bool logy) {
    std::string data;
    std::size_t kept = 0;
    bool gap = false;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (logy && s.y[i] <= 0) || (logx && s.x[i] <= 0)) {
            gap = kept > 0;
            continue;
        }
        if (gap) data += '\n';
        gap = false;
        data += fmt::format("{:.17g} {:.17g}\n", s.x[i], s.y[i]);
        ++kept;
    }
    if (kept) script += name + " << EOD\n" + data + "EOD\n";
    return kept;
}

std::string bound(std::optional<double> v) { return v ? fmt::format("{:.17g}", *v) : "*"; }

std::string range(std::optional<double> lo, std::optional<double> hi) {
    return "[" + bound(lo) + ":" + bound(hi) + "]";
}

// gnuplot cannot autoscale an axis without data, so an empty panel gets a fixed frame.
std::string empty_range(std::optional<double> lo, std::optional<double> hi, bool log) {
    const double a = lo ? *lo : hi ? (log ? *hi / 10 : *hi - 1) : (log ? 1 : 0);
    const double b = hi ? *hi : (log ? a * 10 : a + 1);
    return range(a, b);
}

void check_panel(const Panel& p, std::size_t k) {
    for (auto [name, v] : {std::pair{"xmin", p.xmin}, {"xmax", p.xmax}, {"ymin", p.ymin}, {"ymax", p.ymax}}) {
        if (v && !std::isfinite(*v))
            throw InputError(fmt::format("panel {}: {} must be finite, got {}", k + 1, name, *v));
        if (v && ((p.logy && name[0] == 'y') || (p.logx && name[0] == 'x')) && *v <= 0)
            throw InputError(fmt::format("panel {}: {} = {} on a log axis; it must be > 0", k + 1, name, *v));
    }
    for (const Series& s : p.series) {
        if (s.x.size() != s.y.size())
            throw InputError(fmt::format("panel {}: series '{}' has {} x values but {} y values", k + 1,
                                         s.label, s.x.size(), s.y.size()));
        if (!s.point_labels.empty() && s.point_labels.size() != s.x.size())
            throw InputError(fmt::format("panel {}: series '{}' has {} point labels for {} points; allowed: none or "
                                         "one per point",
                                         k + 1, s.label, s.point_labels.size(), s.x.size()));
    }
}

// The labelled points of a series as a data block of x, y and the quoted text (gnuplot's
// "with labels"); returns how many were kept.
std::size_t append_labels(std::string& script, const std::string& name, const Series& s, bool logx, bool logy) {
    std::string data;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < s.point_labels.size(); ++i) {
        if (s.point_labels[i].empty() || !std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) ||
            (logy && s.y[i] <= 0) || (logx && s.x[i] <= 0))
            continue;
        std::string text = s.point_labels[i];   // a data file's string: in double quotes, none inside
        std::replace(text.begin(), text.end(), '"', '\'');
        std::replace(text.begin(), text.end(), '\n', ' ');
        data += fmt::format("{:.17g} {:.17g} \"{}\"\n", s.x[i], s.y[i], text);
        ++kept;
    }
    if (kept) script += name + " << EOD\n" + data + "EOD\n";
    return kept;
}

std::string make_script(const Figure& fig, const std::string& terminal, const fs::path& out) {
    std::string script = fmt::format("set terminal {} size {},{} noenhanced background '#ffffff'\n", terminal,
                                     fig.width, fig.height_per_panel * static_cast<int>(fig.panels.size()));
    script += "set output " + gp_quote(out.string()) + "\n";

    // Data blocks first; each panel's plot command lists the ones it kept.
    std::vector<std::vector<std::string>> plots(fig.panels.size());
    for (std::size_t k = 0; k < fig.panels.size(); ++k) {
        const Panel& p = fig.panels[k];
        check_panel(p, k);
        for (std::size_t i = 0; i < p.series.size(); ++i) {
            const std::string clause = with_clause(p.series[i]);   // validates the style even if skipped
            const std::string name = fmt::format("$d{}_{}", k, i);
            if (append_block(script, name, p.series[i], p.logx, p.logy))
                plots[k].push_back(name + " using 1:2 with " + clause);
            const Series& s = p.series[i];
            const std::string colour = s.color.empty() ? std::string() : " lc rgb " + gp_quote(s.color);
            const std::string text = s.color.empty() ? std::string() : " tc rgb " + gp_quote(s.color);
            if (append_labels(script, name + "l", s, p.logx, p.logy)) {
                plots[k].push_back(name + "l using 1:2 with points pt 6 ps 0.9" + colour + " notitle");
                plots[k].push_back(name + "l using 1:2:3 with labels left offset char 0.7,0.5" + text + " notitle");
            }
        }
    }

    script += "set multiplot layout " + std::to_string(fig.panels.size()) + ",1";
    script += (fig.title.empty() ? "" : " title " + gp_quote(fig.title)) + "\n";
    // %g keeps log ticks short (1e-05, not 0.0000100); the key sits above the panel so it hides no curve.
    script += "set grid\nset format y '%g'\nset key outside top center horizontal\nset lmargin 12\n";
    for (std::size_t k = 0; k < fig.panels.size(); ++k) {
        const Panel& p = fig.panels[k];
        script += "unset logscale\nset autoscale\nset size noratio\nset format x '% h'\n";   // settings carry over between panels
        script += "set xlabel " + gp_quote(p.xlabel) + "\nset ylabel " + gp_quote(p.ylabel) + "\n";
        script += "set title " + gp_quote(p.title) + "\n";
        if (p.logy) script += "set logscale y\n";
        if (p.logx) script += "set logscale x\nset format x '%g'\n";
        if (p.equal_axes) script += "set size ratio -1\n";
        if (plots[k].empty()) {
            script += "set xrange " + empty_range(p.xmin, p.xmax, p.logx) + "\n";
            script += "set yrange " + empty_range(p.ymin, p.ymax, p.logy) + "\nplot NaN notitle\n";
            continue;
        }
        script += "set xrange " + range(p.xmin, p.xmax) + "\nset yrange " + range(p.ymin, p.ymax) + "\n";
        script += "plot ";
        for (std::size_t i = 0; i < plots[k].size(); ++i) script += (i ? ", \\\n     " : "") + plots[k][i];
        script += "\n";
    }
    return script + "unset multiplot\nunset output\n";
}

// gnuplot stops at the first error and prints it last; earlier lines are the
// echoed command and warnings.
std::string last_error_line(const fs::path& file) {
    std::ifstream in(file);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r^") != std::string::npos) last = line;
    return last.empty() ? "(no message on stderr)" : last;
}

}  // namespace

void check_figure(const Figure& fig, const std::string& name) {
    if (fig.panels.empty()) throw InputError(fmt::format("figure '{}' has no panels", name));
    if (fig.width <= 0 || fig.height_per_panel <= 0)
        throw InputError(fmt::format("figure '{}': width {} and height_per_panel {} must be positive", name,
                                     fig.width, fig.height_per_panel));
    for (std::size_t k = 0; k < fig.panels.size(); ++k) {
        check_panel(fig.panels[k], k);
        for (const Series& s : fig.panels[k].series) with_clause(s);   // an unknown style throws
    }
}

void render_figure(const Figure& fig, const std::string& path, const std::string& option) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    const std::string terminal = ext == ".svg" ? "svg" : ext == ".png" ? "pngcairo" : "";
    if (terminal.empty())
        throw InputError(fmt::format("cannot write figure '{}': unsupported extension '{}'; allowed: .svg .png",
                                     path, ext));
    check_figure(fig, path);

    TempDir dir;
    const fs::path script = dir.path / "plot.gp", image = dir.path / ("figure" + ext),
                   err = dir.path / "stderr.txt";
    {
        std::ofstream out(script);
        out << make_script(fig, terminal, image);
        if (!out.flush()) throw Error(fmt::format("cannot write the gnuplot script {}", script.string()));
    }

    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
        throw Error("gnuplot was not found on PATH; install the Debian package gnuplot-nox");
    const int status = std::system(
        ("gnuplot " + sh_quote(script.string()) + " >/dev/null 2>" + sh_quote(err.string())).c_str());
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw Error(fmt::format("gnuplot failed (exit status {}) rendering '{}': {}",
                                status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1, path,
                                last_error_line(err)));

    std::error_code ec;
    if (!fs::exists(image, ec) || fs::file_size(image, ec) == 0 || ec)
        throw Error(fmt::format("gnuplot exited normally but wrote no image for '{}'", path));
    // Rendered in the temp dir, then written through the output layer (claimed, replaced whole).
    std::ifstream in(image, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in && !in.eof()) throw Error(fmt::format("cannot read the image gnuplot wrote for '{}'", path));
    replace_file(path, bytes.str(), "figure", option);
}

}  // namespace gyrokit
