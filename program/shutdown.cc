// Signal handlers restricted to async-signal-safe operations: lock-free
// atomics, clock_gettime(), signal() and raise().
#include "program/shutdown.h"

#include <fcntl.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>

namespace birotor {
namespace {

std::atomic<bool> shutdown_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
// CLOCK_MONOTONIC at the first shutdown signal [ns].
std::atomic<int64_t> first_signal_ns{0};
static_assert(std::atomic<int64_t>::is_always_lock_free, "the signal handler needs a lock-free time");
// A repeat this soon after the first signal is the same stop asked twice:
// GNU timeout signals the program and then its whole process group, a
// shell may pass one Ctrl-C to a pipeline's every member [ns].
constexpr int64_t kRepeatGraceNs = 1000000000;

int64_t MonotonicNs() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<int64_t>(now.tv_sec) * 1000000000 + now.tv_nsec;
}

struct IgnoredSignal {
  int number;
  const char* name;
};
constexpr IgnoredSignal kIgnoredSignals[] = {
    {SIGHUP, "SIGHUP"}, {SIGUSR1, "SIGUSR1"}, {SIGUSR2, "SIGUSR2"}, {SIGALRM, "SIGALRM"}};
constexpr int kNumIgnoredSignals = sizeof(kIgnoredSignals) / sizeof(kIgnoredSignals[0]);
std::atomic<int> ignored_counts[kNumIgnoredSignals];
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free counter");

extern "C" void HandleShutdownSignal(int signal_number) {
  const int64_t now_ns = MonotonicNs();
  if (!shutdown_requested.exchange(true)) {
    first_signal_ns.store(now_ns);
    return;
  }
  if (now_ns - first_signal_ns.load() < kRepeatGraceNs) return;  // the same stop asked twice
  // A later signal: the loop did not stop; fall back to the default action.
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

extern "C" void CountIgnoredSignal(int signal_number) {
  for (int i = 0; i < kNumIgnoredSignals; ++i) {
    if (kIgnoredSignals[i].number == signal_number) ignored_counts[i].fetch_add(1);
  }
}

void Install(int signal_number, void (*handler)(int), int flags) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = flags;
  sigaction(signal_number, &action, nullptr);
}

}  // namespace

void InstallShutdownHandlers() {
  // No SA_RESTART: a blocking call returns EINTR and the loop checks the flag.
  Install(SIGINT, HandleShutdownSignal, 0);
  Install(SIGTERM, HandleShutdownSignal, 0);
  for (const IgnoredSignal& ignored : kIgnoredSignals) Install(ignored.number, CountIgnoredSignal, SA_RESTART);
  Install(SIGPIPE, SIG_IGN, 0);
}

bool ShutdownRequested() { return shutdown_requested.load(); }

void RequestShutdown() { shutdown_requested.store(true); }

void ClearShutdownRequest() { shutdown_requested.store(false); }

std::string TakeIgnoredSignalReport() {
  std::string report;
  for (int i = 0; i < kNumIgnoredSignals; ++i) {
    const int count = ignored_counts[i].exchange(0);
    if (count == 0) continue;
    if (!report.empty()) report += ", ";
    report += std::string(kIgnoredSignals[i].name) + " x" + std::to_string(count);
  }
  return report.empty() ? report : report + " ignored";
}

void KeepStandardStreamsOpen() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // open() returns the lowest free descriptor: this one.
    const int opened = open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
    if (opened >= 0 && opened != fd) {
      dup2(opened, fd);
      close(opened);
    }
  }
}

}  // namespace birotor
