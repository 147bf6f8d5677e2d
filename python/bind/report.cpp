// The HTML report of a scene (report_study, html_report): the page and what it holds,
// written through the library's output layer (never over one of the scene's files).
#include "common.hpp"
#include "binding_table.hpp"

#include <gyrokit/core/run_files.hpp>
#include <gyrokit/io/output_file.hpp>
#include <gyrokit/reports/html_report.hpp>
#include <gyrokit/scene/scene.hpp>
#include <gyrokit/study/report_study.hpp>

#include <pybind11/stl.h>

namespace py = pybind11;
using namespace gyrokit;
using namespace gyrokit_python;

void bind_report(py::module_& m) {
    m.def(
        "report",
        [](const Scene& scene, std::optional<std::string> unit, int mode_shapes) {
            ReportRequest r;
            r.unit = unit;
            r.mode_shapes = mode_shapes;
            Report rep;
            std::string page;
            {
                Released free;
                rep = report_study(scene, r);
                page = html_report(rep);
            }
            py::dict d;
            d["html"] = page;
            d["title"] = rep.title;
            d["unit"] = rep.unit;
            d["version"] = rep.version;
            d["generated"] = rep.generated;
            py::list sections;
            for (const ReportSection& s : rep.sections) {
                py::dict x;
                x["key"] = s.key;
                x["title"] = s.title;
                x["failed"] = spell_fields(s.failed, keyword_words);
                std::vector<std::string> keys;
                for (const Table& t : s.tables) keys.push_back(t.key);
                x["tables"] = keys;
                x["figures"] = static_cast<int>(s.figures.size());
                sections.append(x);
            }
            d["sections"] = sections;
            py::list inputs;
            for (const ReportInput& i : rep.inputs) inputs.append(py::make_tuple(i.path, i.fingerprint));
            d["inputs"] = inputs;
            return d;
        },
        py::arg("scene"), py::arg("unit") = py::none(), py::arg("mode_shapes") = kReportModeShapes);
    // The page written through the output layer, the scene's files as the run's inputs.
    m.def(
        "write_report",
        [](const std::string& page, const std::string& path, const std::vector<std::string>& inputs) {
            RunFiles files(inputs);
            RunScope run(files);
            replace_file(path, page, "report");
        },
        py::arg("page"), py::arg("path"), py::arg("inputs") = std::vector<std::string>{});
}
