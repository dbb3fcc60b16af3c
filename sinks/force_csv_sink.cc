// FORCE messages as full-precision CSV rows.
#include "sinks/force_csv_sink.h"

#include <cinttypes>

#include "transport/lcm_codec.h"

namespace birotor {

ForceCsvSink::ForceCsvSink(std::FILE* file, const std::string& force_channel, MessageSink* next)
    : file_(file), force_channel_(force_channel), next_(next) {
  std::fprintf(file_, "%s\n", ForceCsvHeader());
}

void ForceCsvSink::Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (channel == force_channel_ && DecodeMessage(data, size, &message_) == DecodeError::kNone) {
    std::fprintf(file_, "%s\n", ForceCsvRow(message_).c_str());
  }
  if (next_ != nullptr) next_->Publish(channel, timestamp_us, data, size);
}

const char* ForceCsvHeader() {
  return "utime,seq,force_n_1,force_n_2,force_std_n_1,force_std_n_2,thrust_scale_1,"
         "thrust_scale_2,status";
}

std::string ForceCsvRow(const force_estimate_t& m) {
  char row[512];
  std::snprintf(row, sizeof(row), "%" PRId64 ",%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d", m.utime, m.seq, m.force_n[0],
                m.force_n[1], m.force_std_n[0], m.force_std_n[1], m.thrust_scale[0], m.thrust_scale[1], m.status);
  return row;
}

}  // namespace birotor
