// The library's tables and figures of a result, as Python sees them: the tables a
// command prints (dicts of key, title, columns and rows) and the figure it draws
// (panels of series), so that a result is saved in the CLI's formats and plotted
// with the CLI's picture.
#pragma once

#include <gyrokit/core/diagnostics.hpp>
#include <gyrokit/io/plot.hpp>
#include <gyrokit/io/table.hpp>

#include <pybind11/pybind11.h>

#include <vector>

namespace gyrokit_python {

pybind11::list tables_list(const std::vector<gyrokit::Table>& tables);
pybind11::dict figure_dict(const gyrokit::Figure& figure);
// A study's notes and warnings as the result's lists (d["notes"], d["warnings"]),
// option fields in Python's keywords.
void put_diagnostics(pybind11::dict& d, const gyrokit::Diagnostics& diagnostics);

}  // namespace gyrokit_python
