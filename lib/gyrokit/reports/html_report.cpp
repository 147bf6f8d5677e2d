#include <gyrokit/reports/html_report.hpp>

#include <gyrokit/io/svg_figure.hpp>
#include <gyrokit/io/table.hpp>

#include <fmt/format.h>

namespace gyrokit {

namespace {

// Escaped HTML text, option fields in the front end's words (io/table.hpp).
std::string html(const std::string& marked) { return markup_escape(spelled_text(marked)); }

const char* const kStyle = R"(body{font-family:sans-serif;font-size:14px;margin:2em auto;max-width:1000px;color:#111}
h1{font-size:24px}h2{font-size:19px;border-bottom:1px solid #999;margin-top:2em}
table.data{border-collapse:collapse;margin:1em 0;font-size:12px}
table.data caption{text-align:left;font-weight:bold;padding:4px 0}
table.data th,table.data td{border:1px solid #bbb;padding:2px 6px;text-align:left;vertical-align:top}
table.data td.num{text-align:right;font-variant-numeric:tabular-nums}
figure{margin:1em 0}figure svg{max-width:100%;height:auto}
.failed{color:#a00;font-weight:bold}.notes{font-size:12px;color:#444}
.warning{color:#a60}
div.long{max-height:32em;overflow:auto;display:inline-block;border:1px solid #ddd}
@media print{nav{display:none}section:first-of-type{page-break-before:auto}div.long{max-height:none;overflow:visible;border:none}section{page-break-before:always}figure,table{page-break-inside:avoid}
body{margin:0;max-width:none}})";

std::string cell(const Cell& c) {
    if (const double* d = std::get_if<double>(&c)) return fmt::format("<td class=\"num\">{:.6g}</td>", *d);
    if (const long long* i = std::get_if<long long>(&c)) return fmt::format("<td class=\"num\">{}</td>", *i);
    if (const bool* b = std::get_if<bool>(&c)) return *b ? "<td>true</td>" : "<td>false</td>";
    return "<td>" + html(std::get<std::string>(c)) + "</td>";
}

// A long table scrolls in a box of its own on screen (printed whole).
constexpr std::size_t kFoldedRows = 60;

// Ids: a table's key ("table-" and its section where it has none); sections are "section-" and their key.
std::string table(const Table& t, const std::string& section_key) {
    const bool fold = t.rows() > kFoldedRows;
    std::string out = fold ? "<div class=\"long\">\n" : "";
    out += fmt::format("<table class=\"data\" id=\"{}\">", html(t.key.empty() ? "table-" + section_key : t.key));
    if (!t.title.empty()) out += "<caption>" + html(t.title) + "</caption>";
    out += "<thead><tr>";
    for (const std::string& c : t.columns()) out += "<th>" + html(c) + "</th>";
    out += "</tr></thead><tbody>\n";
    for (std::size_t r = 0; r < t.rows(); ++r) {
        out += "<tr>";
        for (const Cell& c : t.row(r)) out += cell(c);
        out += "</tr>\n";
    }
    return out + "</tbody></table>\n" + (fold ? "</div>\n" : "");
}

std::string notes(const Diagnostics& d) {
    if (d.empty()) return "";
    std::string out = "<ul class=\"notes\">\n";
    for (const Diagnostic& x : d)
        out += fmt::format("<li{}>{}: {}</li>\n", x.level == Diagnostic::Level::Warning ? " class=\"warning\"" : "",
                           x.level == Diagnostic::Level::Warning ? "warning" : "note", html(x.text));
    return out + "</ul>\n";
}

std::string section(const ReportSection& s, std::size_t number) {
    std::string out =
        fmt::format("<section id=\"section-{}\">\n<h2>{}. {}</h2>\n", html(s.key), number, html(s.title));
    if (!s.failed.empty()) out += "<p class=\"failed\">Not computed: " + html(s.failed) + "</p>\n";
    for (const std::string& p : s.text) out += "<p>" + html(p) + "</p>\n";
    out += notes(s.diagnostics);
    for (std::size_t i = 0; i < s.figures.size(); ++i)
        out += "<figure>\n" + svg_figure(s.figures[i], fmt::format("{}-{}", s.key, i)) + "</figure>\n";
    for (const Table& t : s.tables) out += table(t, s.key);
    return out + "</section>\n";
}

std::string run_section(const Report& r, std::size_t number) {
    std::string out = fmt::format("<section id=\"section-run\">\n<h2>{}. The run</h2>\n", number);
    out += fmt::format("<p>gyrokit {} ({}); generated {}.</p>\n<p>Speeds in {}: {}.</p>\n", html(r.version),
                       html(r.build), html(r.generated), html(r.unit), html(r.settings));
    Table inputs({"input", "fingerprint_fnv1a64"});
    inputs.key = "inputs";
    inputs.title = "Inputs (FNV-1a fingerprints of the bytes read)";
    for (const ReportInput& i : r.inputs) inputs.add_row({i.path, i.fingerprint});
    out += table(inputs, "run");
    return out + "</section>\n";
}

}  // namespace

std::string html_report(const Report& r) {
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    out += "<title>" + html(r.title) + " — gyrokit report</title>\n<style>\n" + kStyle + "\n</style>\n</head>\n<body>\n";
    out += "<header>\n<h1>" + html(r.title) + "</h1>\n";
    out += fmt::format("<p>Rotordynamic analysis by gyrokit {}. Speeds in {}.</p>\n", html(r.version), html(r.unit));
    out += "<nav><ol>\n";
    for (const ReportSection& s : r.sections)
        out += fmt::format("<li><a href=\"#section-{}\">{}</a>{}</li>\n", html(s.key), html(s.title),
                           s.failed.empty() ? "" : " (not computed)");
    out += "<li><a href=\"#section-run\">The run</a></li>\n</ol></nav>\n</header>\n";
    for (std::size_t i = 0; i < r.sections.size(); ++i) out += section(r.sections[i], i + 1);
    out += run_section(r, r.sections.size() + 1);
    return out + "</body>\n</html>\n";
}

}  // namespace gyrokit
