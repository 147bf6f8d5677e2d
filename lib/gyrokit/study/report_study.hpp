// The document an engineer hands over (gyrokit report, gk.report): the analyses a scene
// supports, run with the scene's own settings and the library's defaults, each a section
// of tables and figures: the model and its drawing, the undamped critical speed map, the
// Campbell diagram with the critical speeds and their amplification factors, the mode
// shapes at the critical speeds, stability, the API unbalance cases and Level I (where
// the scene has [api] data), and the run: every note, the inputs' fingerprints, the
// versions. An analysis that fails leaves its section with the error and what to change;
// the others still run. reports/html_report.hpp writes it as one self-contained page
// (docs/report.md).
#pragma once

#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>
#include <gyrokit/scene/scene.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gyrokit {

struct ReportSection {
    std::string key;                   // stable id: model, map, campbell, modes, stability, api_unbalance, level1, run
    std::string title;
    std::vector<std::string> text;     // paragraphs before the tables
    std::vector<Table> tables;
    std::vector<Figure> figures;
    std::string failed;                // "": ran; else why this analysis gave no result
    Diagnostics diagnostics;           // its notes and warnings
};

struct ReportInput {
    std::string path;
    std::string fingerprint;           // FNV-1a of its bytes, 16 hex digits
};

struct Report {
    std::string title;
    std::vector<ReportSection> sections;
    std::vector<ReportInput> inputs;
    std::string version;               // gyrokit's
    std::string unit;                  // of every speed the report prints
    std::string generated;             // when: UTC, ISO 8601
    std::string settings;              // the sweep the analyses share: speeds, lines, modes, f_cut
    std::string build;                 // the libraries and compiler gyrokit was built with
};

// The critical speeds (lowest first) whose mode shapes a report draws unless asked.
constexpr int kReportModeShapes = 4;

struct ReportRequest {
    std::optional<std::string> unit;   // rad/s, Hz or rpm; default: the scene's [speeds] units
    int mode_shapes = kReportModeShapes;   // 0 to 20
};

// InputError for a request out of range (naming the field) and for a scene whose model
// has no speeds to sweep ([speeds] missing). Each analysis' own failure goes into its
// section (ReportSection::failed) and the study goes on.
Report report_study(const Scene& scene, const ReportRequest& request = {});

// Sections that failed, as "title: reason" lines (empty where all ran).
std::vector<std::string> failed_sections(const Report& report);

}  // namespace gyrokit
