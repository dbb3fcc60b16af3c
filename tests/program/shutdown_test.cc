// Tests of transport/shutdown.h: a real SIGTERM sets the flag instead of
// ending the process.
#include "program/shutdown.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>

namespace birotor {
namespace {

TEST(ShutdownTest, RequestAndClear) {
  ClearShutdownRequest();
  EXPECT_FALSE(ShutdownRequested());
  RequestShutdown();
  EXPECT_TRUE(ShutdownRequested());
  ClearShutdownRequest();
  EXPECT_FALSE(ShutdownRequested());
}

TEST(ShutdownTest, SignalSetsTheFlag) {
  InstallShutdownHandlers();
  ClearShutdownRequest();
  ASSERT_EQ(std::raise(SIGTERM), 0);
  EXPECT_TRUE(ShutdownRequested());
  ClearShutdownRequest();
  ASSERT_EQ(std::raise(SIGINT), 0);
  EXPECT_TRUE(ShutdownRequested());
  ClearShutdownRequest();
}

// A hung loop still ends: a signal more than 1 s after the first.
TEST(ShutdownTest, ALaterSecondSignalEndsTheProcess) {
  EXPECT_EXIT(
      {
        InstallShutdownHandlers();
        ClearShutdownRequest();
        std::raise(SIGTERM);
        usleep(1200000);  // past the 1 s in which a repeat is the same stop
        std::raise(SIGTERM);
      },
      ::testing::KilledBySignal(SIGTERM), "");
}

// `timeout 60 birotor-estimator ...` signals the daemon and then its process
// group: the stop it asked twice is one clean stop (the state file written).
TEST(ShutdownTest, ARepeatWithinASecondIsTheSameStop) {
  EXPECT_EXIT(
      {
        InstallShutdownHandlers();
        ClearShutdownRequest();
        std::raise(SIGTERM);
        std::raise(SIGTERM);
        std::raise(SIGINT);
        std::exit(ShutdownRequested() ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

// Issue 23 item 8: HUP, USR1, USR2 and ALRM are counted and reported once,
// not the end of the process; SIGPIPE is ignored.
TEST(ShutdownTest, HangupUserAndAlarmSignalsAreCountedNotFatal) {
  InstallShutdownHandlers();
  ClearShutdownRequest();
  TakeIgnoredSignalReport();
  ASSERT_EQ(std::raise(SIGHUP), 0);
  ASSERT_EQ(std::raise(SIGHUP), 0);
  ASSERT_EQ(std::raise(SIGUSR1), 0);
  ASSERT_EQ(std::raise(SIGUSR2), 0);
  ASSERT_EQ(std::raise(SIGALRM), 0);
  ASSERT_EQ(std::raise(SIGPIPE), 0);
  EXPECT_FALSE(ShutdownRequested());
  EXPECT_EQ(TakeIgnoredSignalReport(), "SIGHUP x2, SIGUSR1 x1, SIGUSR2 x1, SIGALRM x1 ignored");
  EXPECT_EQ(TakeIgnoredSignalReport(), "");
}

TEST(ShutdownTest, ClosedStandardStreamsAreReopenedOnDevNull) {
  EXPECT_EXIT(
      {
        close(1);
        close(2);
        KeepStandardStreamsOpen();
        const bool open_again = fcntl(1, F_GETFD) != -1 && fcntl(2, F_GETFD) != -1;
        // A descriptor opened now does not take stderr's number.
        const int next = open("/dev/null", O_RDONLY);
        std::_Exit(open_again && next > 2 ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace birotor
