// Signal handlers restricted to async-signal-safe operations: a lock-free
// atomic store, signal() and raise().
#include "transport/shutdown.h"

#include <signal.h>

#include <atomic>
#include <csignal>

namespace birotor {
namespace {

std::atomic<bool> shutdown_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void HandleShutdownSignal(int signal_number) {
  if (shutdown_requested.exchange(true)) {
    // Second signal: the loop did not stop; fall back to the default action.
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
  }
}

void Install(int signal_number) {
  struct sigaction action {};
  action.sa_handler = HandleShutdownSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking call returns EINTR and the loop checks the flag
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

void InstallShutdownHandlers() {
  Install(SIGINT);
  Install(SIGTERM);
}

bool ShutdownRequested() { return shutdown_requested.load(); }

void RequestShutdown() { shutdown_requested.store(true); }

void ClearShutdownRequest() { shutdown_requested.store(false); }

}  // namespace birotor
