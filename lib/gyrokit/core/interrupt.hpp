// Stopping a long computation from outside: a signal handler or another thread
// requests it, the computation notices at its next safe point (between speeds,
// designs, ODE right-hand sides) and throws Interrupted. Python's KeyboardInterrupt
// and a service manager's SIGINT reach the library this way.
#pragma once

#include <gyrokit/core/error.hpp>

#include <csignal>

namespace gyrokit {

class Interrupted : public Error {
public:
    Interrupted() : Error("interrupted") {}
};

// Async-signal-safe: one atomic store.
void request_interrupt() noexcept;
void clear_interrupt() noexcept;
bool interrupt_requested() noexcept;
// Throws Interrupted if a stop was requested. Computations call it at safe points.
void throw_if_interrupted();

// For its lifetime, SIGINT requests an interrupt instead of running the previous
// handler (Python's, which would only act after the call returns). Nested and
// concurrent scopes share one installation; the last one out restores the old
// handler, clears the request and, if a SIGINT came that no Interrupted reported
// (it arrived after the last safe point), raises it again for the old handler.
class InterruptOnSigint {
public:
    InterruptOnSigint();
    ~InterruptOnSigint();
    InterruptOnSigint(const InterruptOnSigint&) = delete;
    InterruptOnSigint& operator=(const InterruptOnSigint&) = delete;
    static bool interrupted() noexcept { return interrupt_requested(); }
};

}  // namespace gyrokit
