#include "app/interrupt.hpp"

#include <atomic>
#include <csignal>

#include <signal.h>

#include <unistd.h>

#include "util/file.hpp"

namespace wp {
namespace {

// Written by the handler (or by request_interrupt, on the preview server's
// thread), read by the render loop: lock-free atomics are the only shared
// state a handler may touch, and they are safe across threads too.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);
std::atomic<bool> g_work_begun{false};
static_assert(std::atomic<bool>::is_always_lock_free);

void on_signal(int sig) {
    int none = 0;
    if (g_work_begun.load() && g_signal.compare_exchange_strong(none, sig)) {
        static const char message[] =
            "\nwavepath: interrupted: finishing the current wave and writing the outputs "
            "(again to quit at once)\n";
        // Best effort: nothing to do in a handler if stderr is gone.
        [[maybe_unused]] const ssize_t written = ::write(2, message, sizeof message - 1);
        return;
    }
    // The second signal, or any before the loop began: no half-written
    // output, then the default action (termination by this signal, which
    // the parent sees as such).
    remove_pending_temp_files();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

} // namespace

void install_interrupt_handlers() {
    struct sigaction action = {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART; // blocking reads and writes carry on after the first one
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

void begin_interruptible_work() {
    g_work_begun.store(true);
}

bool request_interrupt() {
    int none = 0;
    return g_signal.compare_exchange_strong(none, SIGINT);
}

bool interrupt_requested() {
    return g_signal != 0;
}

int interrupt_signal() {
    return g_signal;
}

} // namespace wp
