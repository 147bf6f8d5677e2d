// A requested interrupt stops the long computations at their next safe point with
// gyrokit::Interrupted (Python raises it as KeyboardInterrupt), in threads and in
// worker processes alike, and leaves nothing behind: the next call runs normally.
#include <gyrokit/numerics/scalar_search.hpp>
#include <gyrokit/solve/spectrum_solver.hpp>
#include <gyrokit/balancing/simulation.hpp>
#include <gyrokit/core/interrupt.hpp>
#include <gyrokit/models/gyrostat.hpp>

#include "test_helpers.hpp"

#include <catch2/catch.hpp>
#include <cerrno>
#include <csignal>
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

TEST_CASE("an exception in a root search's or a minimum search's function reaches the caller, the GSL solver freed",
          "[interrupt]") {
    // Found by fuzz_solvers: the exception unwound through GSL's C frames and leaked the
    // solver (LeakSanitizer); now it is kept, GSL gets a NaN, and the search rethrows it.
    int calls = 0;
    const std::function<double(double)> root = [&calls](double x) {
        if (++calls > 3) throw SolverError("the function failed");
        return x - 0.3;
    };
    CHECK_THROWS_WITH(find_root(root, 0.0, 1.0, 1e-12), "the function failed");
    calls = 0;
    const std::function<double(double)> bowl = [&calls](double x) {
        if (++calls > 4) throw Interrupted();
        return (x - 0.3) * (x - 0.3);
    };
    CHECK_THROWS_AS(find_smooth_minimum(bowl, 0.0, 0.4, 1.0, 1e-10), Interrupted);
    CHECK(find_root([](double x) { return x - 0.3; }, 0.0, 1.0, 1e-12) == Approx(0.3).epsilon(1e-11));
}

namespace {
volatile std::sig_atomic_t g_previous_handler_calls = 0;
extern "C" void count_sigint(int) { g_previous_handler_calls = g_previous_handler_calls + 1; }
}  // namespace

TEST_CASE("a SIGINT that no safe point reported goes to the previous handler when the scope ends", "[interrupt]") {
    struct sigaction mine {}, before {};
    mine.sa_handler = count_sigint;
    sigemptyset(&mine.sa_mask);
    sigaction(SIGINT, &mine, &before);
    g_previous_handler_calls = 0;
    {
        const InterruptOnSigint scope;
        raise(SIGINT);   // caught by the scope: a request, not the previous handler
        CHECK(interrupt_requested());
        CHECK(g_previous_handler_calls == 0);
    }
    CHECK(g_previous_handler_calls == 1);   // handed back, once
    CHECK_FALSE(interrupt_requested());
    {
        const InterruptOnSigint scope;   // no SIGINT: nothing handed back
    }
    CHECK(g_previous_handler_calls == 1);
    sigaction(SIGINT, &before, nullptr);
}
