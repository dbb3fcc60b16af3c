// The LCM and log-file message sinks.
#include "sinks/message_sink.h"

namespace birotor {

void LcmSink::Publish(const std::string& channel, int64_t /*timestamp_us*/, const void* data, size_t size) {
  lcm_->publish(channel, data, static_cast<unsigned int>(size));
}

void LogSink::Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (!writer_->Write(channel, timestamp_us, data, size)) failed_ = true;
}

}  // namespace birotor
