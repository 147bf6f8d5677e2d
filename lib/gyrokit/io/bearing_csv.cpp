#include <gyrokit/io/bearing_csv.hpp>

#include <gyrokit/core/input_file.hpp>
#include <gyrokit/core/run_files.hpp>

#include <gyrokit/core/error.hpp>
#include <gyrokit/io/csv.hpp>

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <vector>

namespace gyrokit {

namespace {

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

std::vector<std::string> split(const std::string& line, const std::string& path, size_t line_no) {
    std::vector<std::string> out;
    try {
        out = parse_csv_line(line);
    } catch (const Error& e) {
        throw InputError(fmt::format("{}: line {}: {}; allowed: a quote closed on its line", path, line_no, e.what()));
    }
    for (std::string& f : out) f = trim(f);
    return out;
}

}  // namespace

BearingTable read_bearing_csv(const std::string& path, int dofs, int dof_x, int dof_y) {
    const bool dofs_given = dof_x >= 0 && dof_y >= 0;
    const auto bytes = read_input(path, "bearing table", kMaxDataInputBytes);
    std::istringstream in(*bytes);
    static const std::array<const char*, 11> required = {"speed", "dof_x", "dof_y", "kxx", "kxy", "kyx",
                                                         "kyy",   "cxx",   "cxy",   "cyx", "cyy"};
    std::array<int, 11> column{};
    column.fill(-1);
    BearingTable t;
    t.name = path;
    std::string line;
    size_t line_no = 0, width = 0;
    bool header = false;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string s = trim(line);
        if (s.empty() || s[0] == '#') continue;
        const std::vector<std::string> f = split(s, path, line_no);
        if (!header) {
            for (size_t j = 0; j < f.size(); ++j)
                for (size_t r = 0; r < required.size(); ++r)
                    if (f[j] == required[r]) {
                        // Two columns of one name: which one is meant is not for the reader to guess.
                        if (column[r] >= 0)
                            throw InputError(fmt::format("{}: line {}: the header names '{}' twice (columns {} and "
                                                         "{}); allowed: each column once",
                                                         path, line_no, required[r], column[r] + 1, j + 1));
                        column[r] = static_cast<int>(j);
                    }
            for (size_t r = 0; r < required.size(); ++r)
                if (column[r] < 0 && !(dofs_given && (r == 1 || r == 2)))
                    throw InputError(fmt::format("{}: line {}: the header has no column '{}'; required: speed, "
                                                 "dof_x, dof_y, kxx, kxy, kyx, kyy, cxx, cxy, cyx, cyy",
                                                 path, line_no, required[r]));
            header = true;
            width = f.size();
            continue;
        }
        if (f.size() != width)
            throw InputError(fmt::format("{}: line {}: {} fields; allowed: {} as in the header", path, line_no,
                                         f.size(), width));
        std::array<double, 11> v{};
        for (size_t r = 0; r < required.size(); ++r) {
            if (dofs_given && (r == 1 || r == 2)) continue;
            const std::string& x = f[static_cast<size_t>(column[r])];
            size_t pos = 0;
            bool ok = false;
            try {
                v[r] = std::stod(x, &pos);
                ok = pos == x.size() && std::isfinite(v[r]);
            } catch (const std::exception&) {
            }
            if (!ok)
                throw InputError(fmt::format("{}: line {}: {} = '{}' is not a finite number", path, line_no,
                                             required[r], x));
        }
        const auto as_dof = [&](size_t r) {
            if (v[r] != std::floor(v[r]) || v[r] < 0 || v[r] >= dofs)
                throw InputError(fmt::format("{}: line {}: {} = {} is out of range; allowed: a whole number from 0 "
                                             "to {} (0-based DOF index of the model)",
                                             path, line_no, required[r], v[r], dofs - 1));
            return static_cast<int>(v[r]);
        };
        const int dx = dofs_given ? dof_x : as_dof(1), dy = dofs_given ? dof_y : as_dof(2);
        if (t.speeds.empty()) {
            t.dof_x = dx;
            t.dof_y = dy;
        } else if (dx != t.dof_x || dy != t.dof_y) {
            throw InputError(fmt::format("{}: line {}: dof_x, dof_y = {}, {} differ from {}, {} of the first row; "
                                         "allowed: one DOF pair per table",
                                         path, line_no, dx, dy, t.dof_x, t.dof_y));
        }
        if (!t.speeds.empty() && !(v[0] > t.speeds.back()))
            throw InputError(fmt::format("{}: line {}: speed {} does not exceed the previous {}; allowed: strictly "
                                         "increasing speeds",
                                         path, line_no, v[0], t.speeds.back()));
        BearingCoefficients c;
        c.K << v[3], v[4], v[5], v[6];
        c.C << v[7], v[8], v[9], v[10];
        t.speeds.push_back(v[0]);
        t.rows.push_back(c);
    }
    if (!header) throw InputError(fmt::format("{}: no header line; required: speed, dof_x, dof_y, kxx, ... cyy", path));
    t.validate(dofs);
    return t;
}

}  // namespace gyrokit
