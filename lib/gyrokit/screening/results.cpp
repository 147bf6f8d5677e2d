// Result rows as written (CSV cells), tables, the summary and the safe-region figure.
#include <gyrokit/core/error.hpp>
#include <gyrokit/io/csv.hpp>
#include <gyrokit/screening/screening.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>

namespace gyrokit {

namespace {

bool is_number_column(const Sweep& s, std::size_t c) {
    return c >= 1 && c < 1 + s.parameters.size() + quantity_columns(s).size();
}

bool is_label_column(const Sweep& s, std::size_t c) {
    const std::size_t first = 1 + s.parameters.size() + quantity_columns(s).size();
    return c >= first && c < first + label_columns(s).size();
}

}  // namespace

ResultRow format_row(const Sweep& s, const DesignResult& r) {
    ResultRow row;
    row.index = r.index;
    row.cells.push_back(std::to_string(r.index));
    // Shortest round-trip form: the row names the exact design.
    for (double x : r.parameters) row.cells.push_back(fmt::format("{}", x));
    for (const auto& q : r.quantities) row.cells.push_back(q ? fmt::format("{:.12g}", *q) : std::string());
    for (std::size_t k = 0; k < label_columns(s).size(); ++k) row.cells.push_back(k < r.labels.size() ? r.labels[k] : "");
    row.cells.push_back(to_string(r.verdict));
    std::string failed;
    for (const auto& f : r.failed) failed += (failed.empty() ? "" : ";") + f;
    row.cells.push_back(failed);
    row.cells.push_back(r.reason);
    return row;
}

void write_results(std::ostream& os, const Sweep& s, const std::vector<ResultRow>& rows, TableFormat f) {
    const std::vector<std::string> cols = result_columns(s);
    if (f == TableFormat::Csv) {
        os << csv_line(cols);
        for (const auto& r : rows) os << csv_line(r.cells);
        return;
    }
    if (f == TableFormat::Json) {
        nlohmann::ordered_json a = nlohmann::ordered_json::array();
        for (const auto& r : rows) {
            nlohmann::ordered_json o;
            for (std::size_t c = 0; c < cols.size(); ++c) {
                const std::string& v = r.cells[c];
                if (c == 0) o[cols[c]] = r.index;
                else if (is_number_column(s, c) && !v.empty() && std::isfinite(std::stod(v))) o[cols[c]] = std::stod(v);
                else if (is_number_column(s, c)) o[cols[c]] = v.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(v);   // "inf": JSON has no infinity
                else if (is_label_column(s, c) && v.empty()) o[cols[c]] = nullptr;
                else o[cols[c]] = v;
            }
            a.push_back(std::move(o));
        }
        os << a.dump(2) << '\n';
        return;
    }
    Table t(cols);
    for (const auto& r : rows) {
        std::vector<Cell> cells;
        for (std::size_t c = 0; c < cols.size(); ++c) {
            const std::string& v = r.cells[c];
            if (c == 0) cells.emplace_back(static_cast<long long>(r.index));
            else if (is_number_column(s, c) && !v.empty()) cells.emplace_back(std::stod(v));
            else cells.emplace_back(v.empty() ? std::string("-") : v);
        }
        t.add_row(std::move(cells));
    }
    write_table(os, t, f);
}

Table summary_table(const Sweep& s, const std::vector<ResultRow>& rows) {
    const std::size_t nc = result_columns(s).size();
    std::map<std::string, long long> verdicts{{"pass", 0}, {"fail", 0}, {"error", 0}};
    std::map<std::string, long long> failing;
    for (const auto& q : {"separation", "amplification", "stability", "pervasive", "response"}) failing[q] = 0;
    for (const auto& r : rows) {
        ++verdicts[r.cells[nc - 3]];
        std::size_t start = 0;
        const std::string& f = r.cells[nc - 2];
        while (start < f.size()) {
            const std::size_t end = std::min(f.find(';', start), f.size());
            ++failing[f.substr(start, end - start)];
            start = end + 1;
        }
    }
    Table t({"outcome", "designs"});
    t.key = "summary";
    t.title = "summary" + (s.title.empty() ? std::string() : " of " + s.title);
    t.add_row({std::string("designs"), static_cast<long long>(rows.size())});
    for (const auto& v : {"pass", "fail", "error"}) t.add_row({std::string(v), verdicts[v]});
    const Criteria& c = s.criteria;
    const std::vector<std::pair<std::string, bool>> used{{"separation", c.separation.has_value()},
                                                         {"amplification", c.separation && c.separation->max_amplification},
                                                         {"stability", c.stability.has_value()},
                                                         {"pervasive", c.pervasive.has_value()},
                                                         {"response", c.response.has_value()}};
    for (const auto& [name, on] : used)
        if (on) t.add_row({"failing " + name, failing[name]});
    return t;
}

Figure safe_region_figure(const Sweep& s, const std::vector<ResultRow>& rows, const std::string& x,
                          const std::string& y) {
    const std::vector<std::string> cols = result_columns(s);
    const auto col = [&](const std::string& name) -> std::size_t {
        for (std::size_t j = 0; j < s.parameters.size(); ++j)
            if (s.parameters[j].name == name) return 1 + j;
        throw InputError(fmt::format("plot axis '{}' is not a parameter of the sweep {}", name, s.path));
    };
    const std::size_t cx = col(x), cy = col(y), cv = cols.size() - 3;
    Series pass{{}, {}, "pass", "points", "#2ca02c"}, fail{{}, {}, "fail", "points", "#d62728"},
        error{{}, {}, "error", "points", "#7f7f7f"};
    for (const auto& r : rows) {
        Series& se = r.cells[cv] == "pass" ? pass : r.cells[cv] == "fail" ? fail : error;
        se.x.push_back(std::stod(r.cells[cx]));
        se.y.push_back(std::stod(r.cells[cy]));
    }
    Figure fig;
    fig.title = s.title.empty() ? "safe region" : s.title;
    Panel p;
    p.xlabel = x;
    p.ylabel = y;
    p.title = fmt::format("{} designs: {} pass, {} fail, {} error", rows.size(), pass.x.size(), fail.x.size(),
                          error.x.size());
    // Pad the axes so that designs on the range ends are not drawn on the frame.
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const Series* se : {&pass, &fail, &error})
        for (std::size_t k = 0; k < se->x.size(); ++k)
            x0 = std::min(x0, se->x[k]), x1 = std::max(x1, se->x[k]), y0 = std::min(y0, se->y[k]),
            y1 = std::max(y1, se->y[k]);
    if (x0 <= x1) {
        const double dx = x1 > x0 ? 0.05 * (x1 - x0) : 0.05 * std::max(std::abs(x0), 1.0);
        const double dy = y1 > y0 ? 0.05 * (y1 - y0) : 0.05 * std::max(std::abs(y0), 1.0);
        p.xmin = x0 - dx, p.xmax = x1 + dx, p.ymin = y0 - dy, p.ymax = y1 + dy;
    }
    for (Series* se : {&pass, &fail, &error})
        if (!se->x.empty()) p.series.push_back(std::move(*se));
    fig.panels.push_back(std::move(p));
    return fig;
}

}  // namespace gyrokit
