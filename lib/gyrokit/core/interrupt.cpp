#include <gyrokit/core/interrupt.hpp>

#include <atomic>
#include <exception>
#include <mutex>

namespace gyrokit {

namespace {

std::atomic<bool> g_interrupt{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the flag is set from a signal handler");

std::mutex g_install;
int g_scopes = 0;
struct sigaction g_previous {};

extern "C" void on_sigint(int) { g_interrupt.store(true, std::memory_order_relaxed); }

}  // namespace

void request_interrupt() noexcept { g_interrupt.store(true, std::memory_order_relaxed); }
void clear_interrupt() noexcept { g_interrupt.store(false, std::memory_order_relaxed); }
bool interrupt_requested() noexcept { return g_interrupt.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
    if (interrupt_requested()) throw Interrupted();
}

InterruptOnSigint::InterruptOnSigint() {
    const std::lock_guard<std::mutex> lock(g_install);
    if (g_scopes++ > 0) return;
    struct sigaction sa {};
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, &g_previous);
}

InterruptOnSigint::~InterruptOnSigint() {
    const std::lock_guard<std::mutex> lock(g_install);
    if (--g_scopes > 0) return;
    sigaction(SIGINT, &g_previous, nullptr);
    const bool pending = interrupt_requested();
    clear_interrupt();
    // A SIGINT after the last safe point: the previous handler gets it now (Python
    // raises KeyboardInterrupt at its next instruction). Not while Interrupted is
    // thrown: that one already reports it.
    if (pending && std::uncaught_exceptions() == 0) raise(SIGINT);
}

}  // namespace gyrokit
