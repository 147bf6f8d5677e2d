// What the binding files of the compiled core share: option fields in Python's
// keywords (also the exception translator's), the library's parallelism rule on
// threads, and the GIL released for a long call that Ctrl-C can stop.
#pragma once

#include <gyrokit/solve/workers.hpp>
#include <gyrokit/core/interrupt.hpp>

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace gyrokit_python {

// Python's keyword arguments for the library's option fields.
std::string keyword_words(const std::string& field);

// The library's parallelism rule; its note (jobs capped to the cores) as a Python warning.
// Speeds solved in parallel on threads: a Python host must not fork.
gyrokit::Workers threads(int jobs);

// Whether this is Python's main thread, the one its SIGINT handler serves.
bool on_main_thread();

// The GIL released for a long call that Ctrl-C can stop: on the main thread,
// SIGINT requests an interrupt, the library notices it at its next safe point
// (between speeds, designs, ODE steps) and throws Interrupted, raised here as
// KeyboardInterrupt; one that came after the last safe point goes back to
// Python's handler when the call returns. A call from another thread leaves
// SIGINT to Python (the main thread's KeyboardInterrupt).
struct MaybeSigint {
    std::optional<gyrokit::InterruptOnSigint> scope;
    explicit MaybeSigint(bool on) {
        if (on) scope.emplace();
    }
};
struct Released {
    MaybeSigint sigint{on_main_thread()};   // first: it asks Python, with the GIL held
    pybind11::gil_scoped_release free;
};

}  // namespace gyrokit_python
