// Figures (Campbell diagrams, stability charts, responses) rendered by an
// external gnuplot, so the library links no plotting code.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct Series {
    std::vector<double> x, y;
    std::string label;           // legend entry ("" = no legend entry)
    std::string style = "lines"; // "lines", "thin" (a thinner line), "dashed", "dotted", "points", "linespoints"
    std::string color;           // e.g. "#d62728"; "" = gnuplot default
    // Text written next to points (a speed on a polar plot): empty, or one per point
    // ("" for none); a labelled point is also drawn as a marker.
    std::vector<std::string> point_labels = {};
};

struct Panel {
    std::string xlabel, ylabel, title;
    bool logy = false;
    std::vector<Series> series;
    std::optional<double> ymin, ymax, xmin, xmax;   // unset = autoscale
    bool equal_axes = false;     // one unit is as long on x as on y (orbits are drawn true to shape)
    bool logx = false;           // a log x axis (x <= 0 dropped, as y <= 0 on a log y axis)
};

struct Figure {
    std::string title;
    std::vector<Panel> panels;   // stacked vertically (multiplot), first on top
    int width = 900, height_per_panel = 380;
};

// Renders `fig` with gnuplot into `path`; the extension picks the terminal:
// .svg -> svg, .png -> pngcairo. Text is drawn literally (no enhanced-text
// markup). Series with empty x are skipped; NaN/inf points, and y <= 0 on a
// log axis, are dropped and break the line there. Panels without data are
// drawn as empty frames. The file at `path` is written through an OutputFile
// (`option` names it in errors): claimed in the run, replaced only on success.
// Throws InputError for an unsupported extension, an unknown style, x/y of
// different lengths, no panels, a bad size or bad axis limits, or a path the run
// reads; Error if gnuplot is missing, fails (its error message is included) or
// writes no file.
void render_figure(const Figure& fig, const std::string& path, const std::string& option = "path");

// The checks every drawing of a figure makes first (render_figure, svg_figure):
// InputError naming `name` for no panels, a bad size, bad axis limits, x and y of
// different lengths or an unknown style.
void check_figure(const Figure& fig, const std::string& name);

}  // namespace gyrokit
