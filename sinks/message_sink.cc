// The LCM and log-file message sinks.
#include "sinks/message_sink.h"

namespace birotor {

void LcmSink::Publish(const std::string& channel, int64_t /*timestamp_us*/, const void* data, size_t size) {
  if (lcm_->publish(channel, data, static_cast<unsigned int>(size)) != 0) ++failures_;
}

void LogSink::Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (!writer_->Write(channel, timestamp_us, data, size)) failed_ = true;
}

void TeeSink::Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (first_ != nullptr) first_->Publish(channel, timestamp_us, data, size);
  if (second_ != nullptr) second_->Publish(channel, timestamp_us, data, size);
}

}  // namespace birotor
