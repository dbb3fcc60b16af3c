// Tests of program/realtime.h: the outcome says what is in force. Each case
// runs in a child process, so the test runner keeps its own scheduler.
#include "program/realtime.h"

#include <gtest/gtest.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

namespace birotor {
namespace {

// Runs body in a child; returns its exit status (0: the child's checks held).
int InChild(const std::function<int()>& body) {
  const pid_t pid = fork();
  if (pid == 0) _exit(body());
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100;
}

TEST(RealtimeTest, ZeroAsksForNothing) {
  const RealtimeOutcome out = ApplyRealtimePriority(0);
  EXPECT_EQ(out.requested_priority, 0);
  EXPECT_FALSE(out.fifo);
  EXPECT_FALSE(out.memory_locked);
  EXPECT_TRUE(out.warning.empty());
  EXPECT_EQ(sched_getscheduler(0), SCHED_OTHER);
}

// Whatever the machine permits, the outcome matches the scheduler the
// process then runs under, and a refusal is one warning naming it.
TEST(RealtimeTest, OutcomeMatchesTheSchedulerInForce) {
  EXPECT_EQ(InChild([] {
              const RealtimeOutcome out = ApplyRealtimePriority(10);
              const bool fifo = sched_getscheduler(0) == SCHED_FIFO;
              if (out.fifo != fifo) return 1;
              if (fifo) {
                sched_param param{};
                sched_getparam(0, &param);
                if (param.sched_priority != 10) return 2;
              }
              if (!out.fifo && out.warning.find("SCHED_FIFO priority 10") == std::string::npos) return 3;
              if (out.fifo && out.memory_locked && !out.warning.empty()) return 4;
              return 0;
            }),
            0);
}

// Without the right to real-time priorities (RLIMIT_RTPRIO 0 and no
// privileges: dropped here as an unprivileged user would have them), the
// program goes on with one warning on the normal scheduler.
TEST(RealtimeTest, RefusedPriorityIsOneWarningAndTheNormalScheduler) {
  EXPECT_EQ(InChild([] {
              if (geteuid() == 0 && setuid(65534) != 0) return 10;  // nobody: no CAP_SYS_NICE
              const rlimit none{0, 0};
              setrlimit(RLIMIT_RTPRIO, &none);
              const RealtimeOutcome out = ApplyRealtimePriority(20);
              if (out.fifo) return 1;
              if (sched_getscheduler(0) != SCHED_OTHER) return 2;
              if (out.warning.find("cannot set SCHED_FIFO priority 20") == std::string::npos) return 3;
              return 0;
            }),
            0);
}

}  // namespace
}  // namespace birotor
