// Design screening from Python: the whole study (screen), or one design at a time for a
// caller's executor (screen_design, screen_plan, screen_error_row).
#include "binding_table.hpp"

#include <gyrokit/solve/solver_choice.hpp>
#include <gyrokit/gyrokit.hpp>

#include "common.hpp"

#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <gyrokit/core/run_files.hpp>

#include <filesystem>

#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

namespace {

// The sweep file's study, on its own designs or on `designs` (values in the order
// of `names`; a name of the sweep keeps its tied paths).
// `scene`: a Scene's (text, name) in place of the sweep's base scene, or None.
Sweep sweep_with(const std::string& path, const py::object& scene, const py::object& names, const py::object& designs,
                 bool check_parameters = true) {
    const auto [text, name] = scene.is_none() ? std::pair<std::string, std::string>()
                                              : scene.cast<std::pair<std::string, std::string>>();
    Sweep s = read_sweep(path, text, name);
    if (designs.is_none()) return s;
    // The sweep's criteria and operating range on the given designs.
    const std::vector<SweepParameter> declared = s.parameters;
    s.parameters.clear();
    s.plot_axes.clear();
    s.sampling = Sampling::List;
    s.designs = designs.cast<std::vector<std::vector<double>>>();
    for (const auto& n : names.cast<std::vector<std::string>>()) {
        SweepParameter p;
        p.name = n;
        for (const auto& d : declared)
            if (d.name == n) p.paths = d.paths;
        s.parameters.push_back(p);
    }
    for (std::size_t j = 0; j < s.parameters.size(); ++j)
        for (const auto& d : s.designs)
            if (j < d.size()) s.parameters[j].values.push_back(d[j]);
    finalize_sweep(s, check_parameters);
    for (auto& p : s.parameters) p.values.clear();
    return s;
}

// gk.screen: the whole study on threads, its rows as text cells.
py::dict py_screen(const std::string& path, const py::object& scene, const py::object& names,
                   const py::object& designs, int jobs, const py::object& progress) {
    RunFiles files;   // one run: the sweep, the base scene and its files read once
    RunScope run(files);
    const Sweep s = sweep_with(path, scene, names, designs);
    RunOptions o;
    o.jobs = threads(jobs).count;
    if (!progress.is_none())
        o.progress = [progress](std::size_t done, std::size_t total) {
            py::gil_scoped_acquire hold;
            progress(done, total);
        };
    RunResult r;
    {
        Released free;
        r = run_screening(s, o);
    }
    std::vector<std::vector<std::string>> rows;
    for (const auto& row : r.rows) rows.push_back(row.cells);
    py::dict d;
    d["columns"] = r.columns;
    d["rows"] = rows;
    d["parameters"] = [&] {
        std::vector<std::string> p;
        for (const auto& x : s.parameters) p.push_back(x.name);
        return p;
    }();
    d["quantities"] = quantity_columns(s);
    d["labels"] = label_columns(s);
    d["unit"] = s.unit.name;
    std::vector<std::string> inputs;
    for (const auto& in : files.inputs()) inputs.push_back(std::filesystem::absolute(in.path).string());
    d["inputs"] = inputs;   // what the result may not be saved over
    return d;
}

// One design of the study, for a caller's executor (a process pool, a Dask
// cluster): the row run_screening would write for it.
// `number`: the design's number in the caller's study (designs given one by one
// are design 0 of a one-design list).
std::vector<std::string> py_screen_design(const std::string& path, const py::object& scene, const py::object& names,
                                          const py::object& designs, std::size_t index, std::size_t number) {
    const Sweep s = sweep_with(path, scene, names, designs, false);
    if (index >= s.design_count())
        throw InputError("design " + std::to_string(index) + ": allowed: 0 to " +
                         std::to_string(s.design_count() == 0 ? 0 : s.design_count() - 1));
    DesignResult r;
    {
        Released free;
        r = evaluate_design(s, index);
    }
    r.index = number;
    return format_row(s, r).cells;
}

// What a study is before it runs: its columns, parameters, quantities, unit and design count.
py::dict py_screen_plan(const std::string& path, const py::object& scene, const py::object& names,
                        const py::object& designs) {
    const Sweep s = sweep_with(path, scene, names, designs);
    py::dict d;
    d["columns"] = result_columns(s);
    std::vector<std::string> p;
    for (const auto& x : s.parameters) p.push_back(x.name);
    d["parameters"] = p;
    d["quantities"] = quantity_columns(s);
    d["labels"] = label_columns(s);
    d["unit"] = s.unit.name;
    d["designs"] = s.design_count();
    return d;
}

// The row of a design that could not be evaluated where it ran (a worker lost):
// verdict error with `reason`, so that no design is silently missing.
std::vector<std::string> py_screen_error_row(const std::string& path, const py::object& scene,
                                             const py::object& names, const py::object& designs, std::size_t index,
                                             std::size_t number, const std::string& reason) {
    const Sweep s = sweep_with(path, scene, names, designs, false);
    DesignResult r;
    r.index = number;
    r.parameters = s.design(index);
    r.quantities.assign(quantity_columns(s).size(), std::nullopt);
    r.labels.assign(label_columns(s).size(), std::string());
    r.verdict = Verdict::Error;
    r.reason = reason;
    return format_row(s, r).cells;
}

}  // namespace

void bind_screening(py::module_& m) {
    m.def("screen", &py_screen, py::arg("sweep"), py::arg("scene"), py::arg("names"), py::arg("designs"),
          py::arg("jobs"), py::arg("progress"));

    m.def("screen_design", &py_screen_design, py::arg("sweep"), py::arg("scene"), py::arg("names"),
          py::arg("designs"), py::arg("index"), py::arg("number"));

    m.def("screen_plan", &py_screen_plan, py::arg("sweep"), py::arg("scene"), py::arg("names"), py::arg("designs"));

    m.def("screen_error_row", &py_screen_error_row, py::arg("sweep"), py::arg("scene"), py::arg("names"),
          py::arg("designs"), py::arg("index"), py::arg("number"), py::arg("reason"));
}
