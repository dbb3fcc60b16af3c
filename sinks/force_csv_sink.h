// FORCE messages as CSV rows at full precision: the format of the committed
// regression trace (tests/data/ekf_trace.csv) and of birotor-replay --csv.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "birotor/force_estimate_t.hpp"
#include "sinks/message_sink.h"

namespace birotor {

// Writes FORCE messages as CSV rows (full precision, for regression traces),
// forwarding every message to next (may be null).
class ForceCsvSink : public MessageSink {
 public:
  ForceCsvSink(std::FILE* file, const std::string& force_channel, MessageSink* next);
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override;

 private:
  std::FILE* file_;
  std::string force_channel_;
  MessageSink* next_;
  force_estimate_t message_;
};

// Header and one row of the FORCE CSV: utime,seq,force_n_1,force_n_2,
// force_std_n_1,force_std_n_2,thrust_scale_1,thrust_scale_2,status
// (doubles with 17 significant digits, so a trace round-trips exactly).
const char* ForceCsvHeader();
std::string ForceCsvRow(const force_estimate_t& message);

}  // namespace birotor
