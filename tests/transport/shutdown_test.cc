// Tests of transport/shutdown.h: a real SIGTERM sets the flag instead of
// ending the process.
#include "transport/shutdown.h"

#include <gtest/gtest.h>

#include <csignal>

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

TEST(ShutdownTest, SecondSignalEndsTheProcess) {
  EXPECT_EXIT(
      {
        InstallShutdownHandlers();
        ClearShutdownRequest();
        std::raise(SIGTERM);
        std::raise(SIGTERM);
      },
      ::testing::KilledBySignal(SIGTERM), "");
}

}  // namespace
}  // namespace birotor
