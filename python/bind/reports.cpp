// Tables and figures between the library and Python (reports.hpp).
#include "reports.hpp"

#include "binding_table.hpp"
#include "common.hpp"

#include <gyrokit/core/error.hpp>
#include <gyrokit/core/run_files.hpp>
#include <gyrokit/io/output_file.hpp>

#include <pybind11/stl.h>

#include <sstream>

namespace py = pybind11;
using namespace gyrokit;

namespace gyrokit_python {

void put_diagnostics(py::dict& d, const Diagnostics& diagnostics) {
    py::list notes, warnings;
    for (const Diagnostic& x : diagnostics)
        (x.level == Diagnostic::Level::Warning ? warnings : notes).append(spell_fields(x.text, keyword_words));
    d["notes"] = notes;
    d["warnings"] = warnings;
}

namespace {

py::object cell_object(const Cell& c) {
    if (const auto* d = std::get_if<double>(&c)) return py::float_(*d);
    if (const auto* i = std::get_if<long long>(&c)) return py::int_(*i);
    if (const auto* b = std::get_if<bool>(&c)) return py::bool_(*b);
    return py::str(spell_fields(std::get<std::string>(c), keyword_words));
}

Cell object_cell(const py::handle& o, const std::string& column) {
    // bool before int: Python's True is an int too.
    if (py::isinstance<py::bool_>(o)) return o.cast<bool>();
    if (py::isinstance<py::int_>(o)) return o.cast<long long>();
    if (py::isinstance<py::float_>(o)) return o.cast<double>();
    if (py::isinstance<py::str>(o)) return o.cast<std::string>();
    throw InputError("table column '" + column + "': a cell of type " + std::string(py::str(o.get_type())) +
                     "; allowed: float, int, bool, str");
}

Table table_of(const py::handle& h) {
    const py::dict d = h.cast<py::dict>();
    Table t(d["columns"].cast<std::vector<std::string>>());
    t.key = d["key"].cast<std::string>();
    t.title = d["title"].cast<std::string>();
    for (const py::handle& row : d["rows"].cast<py::list>()) {
        std::vector<Cell> cells;
        for (const py::handle& c : row.cast<py::list>())
            cells.push_back(object_cell(c, cells.size() < t.columns().size() ? t.columns()[cells.size()] : "?"));
        t.add_row(std::move(cells));
    }
    return t;
}

std::vector<Table> tables_of(const py::list& l) {
    std::vector<Table> ts;
    for (const py::handle& h : l) ts.push_back(table_of(h));
    return ts;
}

Series series_of(const py::handle& h) {
    const py::dict d = h.cast<py::dict>();
    Series s;
    s.x = d["x"].cast<std::vector<double>>();
    s.y = d["y"].cast<std::vector<double>>();
    s.label = d["label"].cast<std::string>();
    s.style = d["style"].cast<std::string>();
    s.color = d["color"].cast<std::string>();
    if (d.contains("point_labels")) s.point_labels = d["point_labels"].cast<std::vector<std::string>>();
    return s;
}

std::optional<double> limit(const py::dict& d, const char* key) {
    const py::object o = d[key];
    return o.is_none() ? std::nullopt : std::optional<double>(o.cast<double>());
}

Figure figure_of(const py::dict& d) {
    Figure f;
    f.title = d["title"].cast<std::string>();
    f.width = d["width"].cast<int>();
    f.height_per_panel = d["height_per_panel"].cast<int>();
    for (const py::handle& h : d["panels"].cast<py::list>()) {
        const py::dict pd = h.cast<py::dict>();
        Panel p;
        p.xlabel = pd["xlabel"].cast<std::string>();
        p.ylabel = pd["ylabel"].cast<std::string>();
        p.title = pd["title"].cast<std::string>();
        p.logx = pd["logx"].cast<bool>();
        p.logy = pd["logy"].cast<bool>();
        p.equal_axes = pd["equal_axes"].cast<bool>();
        p.xmin = limit(pd, "xmin"), p.xmax = limit(pd, "xmax"), p.ymin = limit(pd, "ymin"), p.ymax = limit(pd, "ymax");
        for (const py::handle& s : pd["series"].cast<py::list>()) p.series.push_back(series_of(s));
        f.panels.push_back(std::move(p));
    }
    return f;
}

py::object limit_object(const std::optional<double>& v) { return v ? py::object(py::float_(*v)) : py::object(py::none()); }

}  // namespace

py::list tables_list(const std::vector<Table>& tables) {
    py::list out;
    for (const Table& t : tables) {
        py::list rows;
        for (std::size_t i = 0; i < t.rows(); ++i) {
            py::list row;
            for (const Cell& c : t.row(i)) row.append(cell_object(c));
            rows.append(row);
        }
        py::dict d;
        d["key"] = t.key;
        d["title"] = spell_fields(t.title, keyword_words);
        d["columns"] = t.columns();
        d["rows"] = rows;
        out.append(d);
    }
    return out;
}

py::dict figure_dict(const Figure& f) {
    py::list panels;
    for (const Panel& p : f.panels) {
        py::list series;
        for (const Series& s : p.series) {
            py::dict sd;
            sd["x"] = s.x;
            sd["y"] = s.y;
            sd["label"] = s.label;
            sd["style"] = s.style;
            sd["color"] = s.color;
            sd["point_labels"] = s.point_labels;
            series.append(sd);
        }
        py::dict pd;
        pd["xlabel"] = p.xlabel;
        pd["ylabel"] = p.ylabel;
        pd["title"] = p.title;
        pd["logx"] = p.logx;
        pd["logy"] = p.logy;
        pd["equal_axes"] = p.equal_axes;
        pd["xmin"] = limit_object(p.xmin), pd["xmax"] = limit_object(p.xmax);
        pd["ymin"] = limit_object(p.ymin), pd["ymax"] = limit_object(p.ymax);
        pd["series"] = series;
        panels.append(pd);
    }
    py::dict d;
    d["title"] = f.title;
    d["width"] = f.width;
    d["height_per_panel"] = f.height_per_panel;
    d["panels"] = panels;
    return d;
}

}  // namespace gyrokit_python

// _core.write_tables(tables, path, format), _core.format_tables(tables, format),
// _core.render_figure(figure, path).
void bind_reports(py::module_& m) {
    using namespace gyrokit_python;
    m.def("format_tables", [](const py::list& tables, const std::string& format) {
        std::ostringstream out;
        write_tables(out, tables_of(tables), parse_table_format(format));
        return out.str();
    }, py::arg("tables"), py::arg("format"));
    // A result's files go through the library's output layer, with the files its
    // scene was read from as the run's inputs: never saved over one of them.
    m.def("write_tables", [](const py::list& tables, const std::string& path, const std::string& format,
                             const std::vector<std::string>& inputs) {
        std::ostringstream out;
        write_tables(out, tables_of(tables), parse_table_format(format));
        RunFiles files(inputs);
        RunScope run(files);
        replace_file(path, out.str(), "result");
    }, py::arg("tables"), py::arg("path"), py::arg("format"), py::arg("inputs") = std::vector<std::string>{});
    m.def("render_figure", [](const py::dict& figure, const std::string& path, const std::vector<std::string>& inputs) {
        const Figure f = figure_of(figure);
        RunFiles files(inputs);
        files.claim_output(path, "path");   // before gnuplot runs
        py::gil_scoped_release free;
        RunScope run(files);
        render_figure(f, path);
    }, py::arg("figure"), py::arg("path"), py::arg("inputs") = std::vector<std::string>{});
}
