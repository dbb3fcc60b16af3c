// Where encoded messages go: the MessageSink interface and its plain
// implementations (an LCM instance, an LCM log file). The estimator service,
// the replay, birotor-sim and the tests all publish through it, so the same
// bytes reach the bus, a log or a test vector.
#pragma once

#include <cstddef>
#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "transport/log_io.h"

namespace birotor {

// Where a producer's output goes: LCM when live, a log file in replay, a
// vector in tests. timestamp_us is the event time written to a log (the
// message's utime); LCM ignores it.
class MessageSink {
 public:
  virtual ~MessageSink() = default;
  virtual void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) = 0;
};

// Publishes on an LCM instance.
class LcmSink : public MessageSink {
 public:
  explicit LcmSink(lcm::LCM* lcm) : lcm_(lcm) {}
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override;
  // Publish calls LCM refused (e.g. a full socket buffer).
  int64_t failures() const { return failures_; }

 private:
  lcm::LCM* lcm_;
  int64_t failures_ = 0;
};

// Writes every message to an LCM log (event time = the message's utime).
class LogSink : public MessageSink {
 public:
  explicit LogSink(LogWriter* writer) : writer_(writer) {}
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override;
  bool failed() const { return failed_; }

 private:
  LogWriter* writer_;
  bool failed_ = false;
};

// Publishes every message to first, then to second (either may be null).
class TeeSink : public MessageSink {
 public:
  TeeSink(MessageSink* first, MessageSink* second) : first_(first), second_(second) {}
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override;

 private:
  MessageSink* first_;
  MessageSink* second_;
};

}  // namespace birotor
