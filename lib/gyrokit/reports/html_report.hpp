// A report (study/report_study.hpp) as one self-contained HTML page: no network, no
// script; its figures inline as SVG (io/svg_figure.hpp, each point's values on hover),
// its tables as HTML tables whose id is the table's key, a contents list, the notes of
// each analysis, the inputs' fingerprints and the version; printable (a print style
// sheet starts each section on a page and keeps figures and tables whole).
#pragma once

#include <gyrokit/study/report_study.hpp>

#include <string>

namespace gyrokit {

std::string html_report(const Report& report);

}  // namespace gyrokit
