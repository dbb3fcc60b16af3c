// Tests of sources/receive_loop.h with a scripted source (no clock
// assertions): every ready packet is delivered, the periodic work runs after
// each wake-up, a finished source or a shutdown request ends the loop, and a
// source error is returned.
#include "sources/receive_loop.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "program/shutdown.h"
#include "tests/sources/packet_recorder.h"

namespace birotor {
namespace {

// Delivers `count` packets, one per DeliverOne, then finishes (with error).
class ScriptedSource : public MessageSource {
 public:
  ScriptedSource(int count, std::string error) : remaining_(count), final_error_(std::move(error)) {}
  bool Subscribe(const std::vector<std::string>&, PacketHandler* handler, std::string*) override {
    handler_ = handler;
    return true;
  }
  bool Wait(double) override { return !finished_; }
  bool DeliverOne() override {
    if (remaining_ == 0) {
      error_ = final_error_;
      finished_ = true;
      return false;
    }
    --remaining_;
    const uint8_t byte = 1;
    handler_->HandlePacket("X", &byte, 1, -1);
    return true;
  }
  bool finished() const override { return finished_; }
  const std::string& error() const override { return error_; }
  std::string Describe() const override { return "scripted"; }

 private:
  int remaining_;
  std::string final_error_;
  std::string error_;
  bool finished_ = false;
  PacketHandler* handler_ = nullptr;
};

TEST(ReceiveLoopTest, DeliversEveryPacketAndRunsTheWorkUntilTheSourceEnds) {
  ClearShutdownRequest();
  ScriptedSource source(1000, "");
  PacketRecorder recorder;
  std::string error;
  source.Subscribe({}, &recorder, &error);
  int work_calls = 0;
  // A deadline always due: one packet per turn still gets through.
  EXPECT_TRUE(RunReceiveLoop(&source, [&](int64_t now_us) {
    ++work_calls;
    return now_us;
  }));
  EXPECT_EQ(recorder.packets.size(), 1000u);
  EXPECT_GE(work_calls, 1000);
}

TEST(ReceiveLoopTest, ReturnsFalseWhenTheSourceFails) {
  ClearShutdownRequest();
  ScriptedSource source(3, "lcm handle failed: boom");
  PacketRecorder recorder;
  std::string error;
  source.Subscribe({}, &recorder, &error);
  EXPECT_FALSE(RunReceiveLoop(&source, [](int64_t now_us) { return now_us + 1000000; }));
  EXPECT_EQ(recorder.packets.size(), 3u);
}

TEST(ReceiveLoopTest, AShutdownRequestEndsTheLoop) {
  ScriptedSource source(1000000, "");
  PacketRecorder recorder;
  std::string error;
  source.Subscribe({}, &recorder, &error);
  RequestShutdown();
  EXPECT_TRUE(RunReceiveLoop(&source, [](int64_t now_us) { return now_us; }));
  ClearShutdownRequest();
  EXPECT_LE(recorder.packets.size(), 1u);
}

}  // namespace
}  // namespace birotor
