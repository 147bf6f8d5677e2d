// gyrokit-bench-tradeoffs: what its parts share. Settings holds the measuring
// options of a run; every row of the trade-off table is one Trade; the section
// functions each add the rows of one area (eig_rows: "eig", ...) and size_rows
// fills the size and growth tables.
#pragma once

#include "bench_common.hpp"
#include <gyrokit/core/constants.hpp>
#include <gyrokit/io/table.hpp>

#include <exception>
#include <fmt/format.h>
#include <string>
#include <utility>

namespace tradeoffs {

using gyrokit::kPi;


struct Settings {
    bool quick = false;
    double min_time = 0.2;   // s of repeated calls per row (median of the calls)
    int min_repeats = 3;     // calls per row at least

    // Seconds per call of f (bench_common.hpp); a call longer than `single` s is not repeated.
    template <class F>
    double time(F&& f, double single = 5.0) const {
        return gyrokit::bench::median_seconds(std::forward<F>(f), min_time, min_repeats, single);
    }
};

// The columns of the trade-off table; `seconds` and `error` are "-" when the setting failed.
struct Trade {
    std::string area, model, knob, setting;
    gyrokit::Cell seconds, error;
    std::string error_of, reference, note;
};

inline void add(gyrokit::Table& t, const Trade& r) {
    t.add_row({r.area, r.model, r.knob, r.setting, r.seconds, r.error, r.error_of, r.reference, r.note});
}

inline std::string sci(double v) { return fmt::format("{:.1e}", v); }

// The first clause of an error message (the advice after "; " names CLI options).
inline std::string failure(const std::exception& e) {
    const std::string what = e.what();
    return "failed: " + what.substr(0, what.find("; "));
}

// The sections of the trade-off table, in the order of the table.
void eig_rows(gyrokit::Table& t, const Settings& s);        // eigen_rows.cpp
void critical_rows(gyrokit::Table& t, const Settings& s);   // speed_rows.cpp
void campbell_rows(gyrokit::Table& t, const Settings& s);   // speed_rows.cpp
void mesh_rows(gyrokit::Table& t, const Settings& s);       // eigen_rows.cpp
void fluid_rows(gyrokit::Table& t, const Settings& s);      // speed_rows.cpp
void balancer_rows(gyrokit::Table& t, const Settings& s);   // balancer_rows.cpp
void averaged_rows(gyrokit::Table& t, const Settings& s);   // balancer_rows.cpp

// Time per speed point against model size into `t`, the fitted growth exponents into `fit` (eigen_rows.cpp).
void size_rows(gyrokit::Table& t, gyrokit::Table& fit, const Settings& s);

}  // namespace tradeoffs
