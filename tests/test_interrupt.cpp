// A requested interrupt stops the long computations at their next safe point with
// gyrokit::Interrupted (Python raises it as KeyboardInterrupt), in threads and in
// worker processes alike, and leaves nothing behind: the next call runs normally.
#include <gyrokit/analysis/spectrum_solver.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/models/gyrostat.hpp>

#include "test_helpers.hpp"

#include <catch2/catch.hpp>
#include <cerrno>
#include <sys/wait.h>
#include <vector>

using namespace gyrokit;

namespace {

// Clears the request whatever a test does.
struct Cleared {
    Cleared() { clear_interrupt(); }
    ~Cleared() { clear_interrupt(); }
};

std::vector<double> speeds(int n) {
    std::vector<double> w;
    for (int i = 0; i < n; ++i) w.push_back(10.0 * i);
    return w;
}

}  // namespace

TEST_CASE("an interrupt stops the speeds, on threads and in worker processes", "[interrupt]") {
    const Cleared cleared;
    const GyroscopicSystem sys = make_system(test::centrifuge());
    const SolverFactory make = dense_solver(sys);
    for (const WorkerKind kind : {WorkerKind::Threads, WorkerKind::Processes}) {
        request_interrupt();
        CHECK_THROWS_AS(solve_speeds(make, speeds(20), Workers(2, kind)), Interrupted);
        errno = 0;
        CHECK(waitpid(-1, nullptr, WNOHANG) == -1);   // every worker reaped
        CHECK(errno == ECHILD);
        clear_interrupt();
        CHECK(solve_speeds(make, speeds(20), Workers(2, kind)).size() == 20);
    }
}

TEST_CASE("an interrupt stops an ODE run within 1024 right-hand sides", "[interrupt]") {
    const Cleared cleared;
    unsigned long calls = 0;
    const OdeRhs f = [&calls](double, const double* y, double* dy, const char**) {
        ++calls;
        dy[0] = y[1];
        dy[1] = -y[0];
        return true;
    };
    OdeOptions o;
    o.method = OdeMethod::Rk4;
    std::vector<double> y{1.0, 0.0};
    request_interrupt();
    CHECK_THROWS_AS(integrate_ode(f, y, 0.0, {1e6}, o, [](double, const double*) {}), Interrupted);
    CHECK(calls <= 1024);
    clear_interrupt();
    y = {1.0, 0.0};
    integrate_ode(f, y, 0.0, {6.283185307179586}, o, [](double, const double*) {});
    CHECK(y[0] == Approx(1.0).margin(1e-6));   // one period of cos
}
