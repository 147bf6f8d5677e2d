#include <gyrokit/io/svg_figure.hpp>

#include <gyrokit/core/error.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>

namespace gyrokit {

namespace {

// The colours of series without their own, in order (gnuplot's first eight).
const char* const kPalette[] = {"#9400d3", "#009e73", "#56b4e9", "#e69f00", "#f0e442", "#0072b2", "#e51e10", "#000000"};

constexpr double kLeft = 78, kRight = 24, kBottom = 48, kTitle = 22, kLegendRow = 16, kFigureTitle = 26;

std::string xml(const std::string& text) { return markup_escape(text); }

}  // namespace

std::string markup_escape(const std::string& text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\n': out += ' '; break;
            default: out += c;
        }
    }
    return out;
}

namespace {

bool drawable(double x, double y, const Panel& p) {
    return std::isfinite(x) && std::isfinite(y) && !(p.logx && x <= 0) && !(p.logy && y <= 0);
}

struct Range {
    double lo = 0, hi = 1;
};

// One axis' range: the limits given, else the data's, widened to the ticks around it.
Range axis_range(std::optional<double> lo, std::optional<double> hi, double dlo, double dhi, bool log) {
    if (!(dlo <= dhi)) dlo = log ? 1 : 0, dhi = log ? 10 : 1;   // no data
    double a = lo.value_or(dlo), b = hi.value_or(dhi);
    if (a > b) std::swap(a, b);
    if (!std::isfinite(b - a) || !std::isfinite(a) || !std::isfinite(b)) a = log ? 1 : -1, b = log ? 10 : 1;
    if (b - a <= 1e-12 * std::max(std::fabs(a), std::fabs(b))) {   // one value, up to rounding
        a = log ? a / 10 : a - std::max(1.0, std::fabs(a) * 0.1);
        b = log ? b * 10 : b + std::max(1.0, std::fabs(b) * 0.1);
    }
    if (log) {
        if (!lo) a = std::pow(10.0, std::floor(std::log10(a) + 1e-12));
        if (!hi) b = std::pow(10.0, std::ceil(std::log10(b) - 1e-12));
    } else {
        const std::vector<double> t = axis_ticks(a, b, false);
        const double step = t.size() > 1 ? t[1] - t[0] : (b - a);
        if (!lo) a = std::floor(a / step + 1e-9) * step;
        if (!hi) b = std::ceil(b / step - 1e-9) * step;
    }
    return {a, b};
}

struct Frame {
    double left, top, width, height;
    Range x, y;
    bool logx, logy;
    double px(double v) const {
        const double f = logx ? (std::log10(v) - std::log10(x.lo)) / (std::log10(x.hi) - std::log10(x.lo))
                              : (v - x.lo) / (x.hi - x.lo);
        return clamp(left + f * width);
    }
    // Far outside the frame (the clip path hides it) but finite: no inf in the page.
    static double clamp(double v) { return std::min(1e6, std::max(-1e6, v)); }
    double py(double v) const {
        const double f = logy ? (std::log10(v) - std::log10(y.lo)) / (std::log10(y.hi) - std::log10(y.lo))
                              : (v - y.lo) / (y.hi - y.lo);
        return clamp(top + height - f * height);
    }
};

// Equal axes: the axis with fewer units per pixel widened about its middle.
void equalize(Frame& f) {
    const double sx = (f.x.hi - f.x.lo) / f.width, sy = (f.y.hi - f.y.lo) / f.height;
    if (sx > sy) {
        const double mid = 0.5 * (f.y.lo + f.y.hi), half = 0.5 * sx * f.height;
        f.y = {mid - half, mid + half};
    } else {
        const double mid = 0.5 * (f.x.lo + f.x.hi), half = 0.5 * sy * f.width;
        f.x = {mid - half, mid + half};
    }
}

std::string dash_of(const std::string& style) {
    if (style == "dashed") return " stroke-dasharray=\"7,4\"";
    if (style == "dotted") return " stroke-dasharray=\"2,3\"";
    return "";
}

double width_of(const std::string& style) { return style == "thin" ? 0.7 : 1.5; }

// The legend entries laid out in rows across the panel: each entry's (x, row).
std::vector<std::pair<double, int>> legend_layout(const Panel& p, double width, int& rows) {
    std::vector<std::pair<double, int>> at;
    double x = 0;
    rows = 0;
    for (const Series& s : p.series) {
        if (s.label.empty()) {
            at.push_back({-1, -1});
            continue;
        }
        const double w = 34 + 6.2 * static_cast<double>(s.label.size());
        if (rows == 0 || (x + w > width && x > 0)) ++rows, x = 0;
        at.push_back({x, rows - 1});
        x += w + 12;
    }
    return at;
}

void draw_axes(std::string& out, const Panel& p, const Frame& f) {
    out += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
                       "stroke=\"#000\" stroke-width=\"1\"/>\n",
                       f.left, f.top, f.width, f.height);
    for (const double t : axis_ticks(f.x.lo, f.x.hi, p.logx)) {
        const double x = f.px(t);
        out += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#ddd\"/>"
                           "<text x=\"{0:.1f}\" y=\"{3:.1f}\" text-anchor=\"middle\">{4:g}</text>\n",
                           x, f.top, f.top + f.height, f.top + f.height + 16, t);
    }
    for (const double t : axis_ticks(f.y.lo, f.y.hi, p.logy)) {
        const double y = f.py(t);
        out += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
                           "<text x=\"{3:.1f}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:g}</text>\n",
                           f.left, y, f.left + f.width, f.left - 6, y + 4, t);
    }
    out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\">{}</text>\n", f.left + f.width / 2,
                       f.top + f.height + 36, xml(p.xlabel));
    out += fmt::format("<text transform=\"translate({:.1f},{:.1f}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
                       f.left - 58, f.top + f.height / 2, xml(p.ylabel));
}

// One series: its line (broken where points are dropped), its points, and a hover title
// on at most kSvgTitledPoints of them.
void draw_series(std::string& out, const Panel& p, const Frame& f, const Series& s, const std::string& color) {
    bool line = s.style != "points", dots = s.style == "points" || s.style == "linespoints";
    std::size_t drawn = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i) drawn += drawable(s.x[i], s.y[i], p) ? 1 : 0;
    if (drawn == 1) dots = true;   // a lone point draws no line: a marker shows it
    std::vector<std::size_t> kept;
    std::string run;
    const auto flush = [&] {
        if (line && run.find(' ') != std::string::npos)
            out += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{} points=\"{}\"/>\n", color,
                               width_of(s.style), dash_of(s.style), run);
        run.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!drawable(s.x[i], s.y[i], p)) {
            flush();
            continue;
        }
        run += fmt::format("{}{:.2f},{:.2f}", run.empty() ? "" : " ", f.px(s.x[i]), f.py(s.y[i]));
        kept.push_back(i);
    }
    flush();
    const std::size_t every = kept.size() > static_cast<std::size_t>(kSvgTitledPoints)
                                  ? (kept.size() + kSvgTitledPoints - 1) / kSvgTitledPoints
                                  : 1;
    const std::string name = s.label.empty() ? std::string() : xml(s.label) + ": ";
    for (std::size_t k = 0; k < kept.size(); ++k) {
        const bool titled = k % every == 0;
        if (!dots && !titled) continue;
        const std::size_t i = kept[k];
        out += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"{}\">", f.px(s.x[i]), f.py(s.y[i]),
                           dots ? 2.5 : 3.5, dots ? color : std::string("transparent"));
        if (titled) out += fmt::format("<title>{}{} = {:.6g}, {} = {:.6g}</title>", name, xml(p.xlabel), s.x[i],
                                       xml(p.ylabel), s.y[i]);
        out += "</circle>\n";
    }
    // Labelled points: a ring and the text beside it.
    for (std::size_t i = 0; i < s.point_labels.size(); ++i) {
        if (s.point_labels[i].empty() || !drawable(s.x[i], s.y[i], p)) continue;
        out += fmt::format("<circle cx=\"{0:.2f}\" cy=\"{1:.2f}\" r=\"3.5\" fill=\"none\" stroke=\"{2}\"/>"
                           "<text x=\"{3:.1f}\" y=\"{4:.1f}\" font-size=\"10\" fill=\"{2}\">{5}</text>\n",
                           f.px(s.x[i]), f.py(s.y[i]), color, f.px(s.x[i]) + 6.0, f.py(s.y[i]) - 5.0,
                           xml(s.point_labels[i]));
    }
}

// The data's extent on each axis, over the drawable points.
void extent(const Panel& p, double& xlo, double& xhi, double& ylo, double& yhi) {
    xlo = ylo = std::numeric_limits<double>::infinity();
    xhi = yhi = -xlo;
    for (const Series& s : p.series)
        for (std::size_t i = 0; i < s.x.size(); ++i)
            if (drawable(s.x[i], s.y[i], p)) {
                xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]);
                ylo = std::min(ylo, s.y[i]), yhi = std::max(yhi, s.y[i]);
            }
}

void draw_panel(std::string& out, const Panel& p, double top, double width, double height, const std::string& id) {
    int rows = 0;
    const std::vector<std::pair<double, int>> legend = legend_layout(p, width - kLeft - kRight, rows);
    const double head = (p.title.empty() ? 8.0 : kTitle + 4) + rows * kLegendRow;
    Frame f{kLeft, top + head, width - kLeft - kRight, std::max(40.0, height - head - kBottom), {}, {}, p.logx,
            p.logy};
    double xlo, xhi, ylo, yhi;
    extent(p, xlo, xhi, ylo, yhi);
    f.x = axis_range(p.xmin, p.xmax, xlo, xhi, p.logx);
    f.y = axis_range(p.ymin, p.ymax, ylo, yhi, p.logy);
    if (p.equal_axes && !p.logx && !p.logy) equalize(f);
    if (!p.title.empty())
        out += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"middle\" font-weight=\"bold\">{}</text>\n",
                           width / 2, top + kTitle - 4, xml(p.title));
    draw_axes(out, p, f);
    out += fmt::format("<clipPath id=\"{0}\"><rect x=\"{1:.1f}\" y=\"{2:.1f}\" width=\"{3:.1f}\" height=\"{4:.1f}\"/>"
                       "</clipPath>\n<g clip-path=\"url(#{0})\">\n",
                       id, f.left, f.top, f.width, f.height);
    for (std::size_t i = 0; i < p.series.size(); ++i) {
        const Series& s = p.series[i];
        draw_series(out, p, f, s, s.color.empty() ? kPalette[i % 8] : s.color);
    }
    out += "</g>\n";
    const double legend_top = top + (p.title.empty() ? 8.0 : kTitle + 4);
    for (std::size_t i = 0; i < p.series.size(); ++i) {
        if (legend[i].second < 0) continue;
        const Series& s = p.series[i];
        const std::string color = s.color.empty() ? kPalette[i % 8] : s.color;
        const double x = kLeft + legend[i].first, y = legend_top + legend[i].second * kLegendRow + 8;
        out += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" "
                           "stroke-width=\"{}\"{}/><text x=\"{:.1f}\" y=\"{:.1f}\">{}</text>\n",
                           x, y, x + 26, y, color, s.style == "points" ? 5.0 : width_of(s.style), dash_of(s.style),
                           x + 32, y + 4, xml(s.label));
    }
}

}  // namespace

std::vector<double> axis_ticks(double lo, double hi, bool log, int target) {
    std::vector<double> t;
    if (!(std::isfinite(lo) && std::isfinite(hi)) || !(hi > lo) || target < 2) return t;
    if (log) {
        if (!(lo > 0)) return t;
        const int a = static_cast<int>(std::ceil(std::log10(lo) - 1e-9)), b = static_cast<int>(std::floor(std::log10(hi) + 1e-9));
        const int stride = std::max(1, (b - a + 1 + target) / (target + 1));   // at most target + 1 ticks
        for (int e = a; e <= b; e += stride) t.push_back(std::pow(10.0, e));
        if (t.empty()) t = {lo, hi};
        return t;
    }
    const double raw = (hi - lo) / target;
    const int e = static_cast<int>(std::floor(std::log10(raw)));
    const double mag = std::pow(10.0, e);
    double m = 10.0;
    for (const double c : {1.0, 2.0, 5.0})
        if (c * mag >= raw * (1 - 1e-9)) {   // a span of 1.2000000000000002 keeps the step of 1.2
            m = c;
            break;
        }
    const double step = m * mag;
    // k m 10^e as the nearest double to the decimal: (k m) / 10^-e, both exact integers.
    const double inv = e < 0 ? std::pow(10.0, -e) : 0.0;
    // At most a few dozen: a span that rounding alone makes (below 1e-12 of the values)
    // has no ticks of its own (axis_range widens it first).
    const double k0 = std::ceil(lo / step - 1e-9);
    for (int i = 0; i <= 4 * target; ++i) {
        const double k = k0 + i;
        if (k * step > hi + 1e-9 * step) break;
        t.push_back(k == 0 ? 0.0 : e < 0 ? (k * m) / inv : k * m * mag);
    }
    return t;
}

std::string svg_figure(const Figure& fig, const std::string& id) {
    check_figure(fig, fig.title.empty() ? std::string("(untitled)") : fig.title);
    const double head = fig.title.empty() ? 0.0 : kFigureTitle;
    const double width = fig.width, height = head + fig.height_per_panel * static_cast<double>(fig.panels.size());
    std::string out = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" "
                                  "height=\"{1}\" font-family=\"sans-serif\" font-size=\"12\">\n"
                                  "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n",
                                  width, height);
    if (!fig.title.empty())
        out += fmt::format("<text x=\"{:.1f}\" y=\"18\" text-anchor=\"middle\" font-size=\"14\" "
                           "font-weight=\"bold\">{}</text>\n",
                           width / 2, xml(fig.title));
    for (std::size_t k = 0; k < fig.panels.size(); ++k)
        draw_panel(out, fig.panels[k], head + fig.height_per_panel * static_cast<double>(k), width,
                   fig.height_per_panel, fmt::format("{}-p{}", id, k));
    return out + "</svg>\n";
}

}  // namespace gyrokit
