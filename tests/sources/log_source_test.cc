// Tests of sources/log_source.h: every event of a subscribed channel in log
// order, with the logger's recorded time as the receive time; an empty
// subscription takes every channel.
#include "sources/log_source.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "tests/sources/packet_recorder.h"

namespace birotor {
namespace {

std::string WriteLog() {
  const std::string path = "/tmp/birotor_log_source_test_" + std::to_string(getpid()) + ".lcm";
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  const uint8_t payload[] = {1, 2, 3};
  EXPECT_TRUE(writer.Write("A", 100, payload, 3));
  EXPECT_TRUE(writer.Write("B", 200, payload, 2));
  EXPECT_TRUE(writer.Write("A", 300, payload, 1));
  EXPECT_TRUE(writer.Close());
  return path;
}

TEST(LogSourceTest, DeliversTheSubscribedEventsWithTheirRecordedTime) {
  const std::string path = WriteLog();
  LogSource source;
  std::string error;
  ASSERT_TRUE(source.Open(path, &error)) << error;
  PacketRecorder recorder;
  ASSERT_TRUE(source.Subscribe({"A"}, &recorder, &error));
  int taken = 0;
  while (source.Wait(0.0) && source.DeliverOne()) ++taken;
  EXPECT_EQ(taken, 3);
  EXPECT_TRUE(source.finished());
  EXPECT_TRUE(source.error().empty());
  ASSERT_EQ(recorder.packets.size(), 2u);
  EXPECT_EQ(recorder.packets[0].receive_wall_utime, 100);
  EXPECT_EQ(recorder.packets[1].receive_wall_utime, 300);
  EXPECT_EQ(recorder.packets[1].bytes, (std::vector<uint8_t>{1}));
  EXPECT_EQ(source.reader().events_read(), 3);
  unlink(path.c_str());
}

TEST(LogSourceTest, AnEmptySubscriptionTakesEveryChannel) {
  const std::string path = WriteLog();
  LogSource source;
  std::string error;
  ASSERT_TRUE(source.Open(path, &error)) << error;
  PacketRecorder recorder;
  ASSERT_TRUE(source.Subscribe({}, &recorder, &error));
  while (source.DeliverOne()) {
  }
  ASSERT_EQ(recorder.packets.size(), 3u);
  EXPECT_EQ(recorder.packets[1].channel, "B");
  unlink(path.c_str());
}

}  // namespace
}  // namespace birotor
