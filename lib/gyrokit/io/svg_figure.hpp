// A Figure drawn as SVG text by the library itself, for pages that hold their figures
// inline (the HTML report, reports/html_report.hpp): no gnuplot, no script, and every
// data point carries an SVG <title> with its series and values, which a browser shows
// on hover. The same Figure goes to gnuplot for --plot files (plot.hpp); this drawing
// follows its rules: panels stacked, first on top; NaN/inf points, and values <= 0 on a
// log axis, dropped and the line broken there; equal_axes true to shape.
#pragma once

#include <gyrokit/io/plot.hpp>

#include <string>
#include <vector>

namespace gyrokit {

// Tick values over [lo, hi]: 1, 2 or 5 times a power of ten apart, about `target` of
// them (linear), or the powers of ten inside (log, lo > 0; one per decade, thinned to at
// most `target`, or lo and hi themselves where no power lies inside).
std::vector<double> axis_ticks(double lo, double hi, bool log, int target = 6);

// The figure as one <svg> element (UTF-8, no XML declaration: it sits inside HTML as it
// is, or alone in a .svg file). Hover titles are kept for at most kSvgTitledPoints points
// per series (evenly spread where a series has more). InputError where plot() would
// refuse the figure (no panels, x and y of different lengths, an unknown style, a bad size).
// `id` prefixes the element ids (the panels' clip paths): distinct for each figure of a page.
std::string svg_figure(const Figure& figure, const std::string& id = "figure");

constexpr int kSvgTitledPoints = 400;

// Text as XML/HTML character data or an attribute value: & < > " escaped, a line break a space.
std::string markup_escape(const std::string& text);

}  // namespace gyrokit
