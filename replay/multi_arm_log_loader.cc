#include "replay/multi_arm_log_loader.h"

#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// The counted samples through transport/counted_messages.h; the IMU's through message_conversion.h.
template <class Msg, class Sample>
void Convert(const Msg& message, Sample* sample) {
  FromMessage(message, sample);
}
void Convert(const imu_t& message, ImuSample* sample) { *sample = FromMessage(message); }

template <class Msg, class Sample>
void Append(const LogEvent& event, std::vector<Sample>* out, LogLoadReport* report) {
  Msg message;
  if (DecodeMessage(event.data.data(), event.data.size(), &message) != DecodeError::kNone) {
    ++report->decode_errors;
    return;
  }
  out->emplace_back();
  Convert(message, &out->back());
}

}  // namespace

bool LoadMultiArmBenchLog(const std::string& path, const std::string& prefix, MultiArmBenchLog* log,
                          LogLoadReport* report, std::string* error, double min_usable_fraction) {
  LogReader reader;
  if (!reader.Open(path, error)) return false;
  const ChannelNames channels = MakeChannelNames(prefix);
  *log = MultiArmBenchLog();
  *report = LogLoadReport();
  log->source = path;
  LogEvent event;
  while (reader.Next(&event)) {
    ++report->events;
    if (event.channel == channels.strain_n) {
      Append<strain_n_t>(event, &log->strain, report);
    } else if (event.channel == channels.motor_n) {
      Append<motor_n_t>(event, &log->motor, report);
    } else if (event.channel == channels.loadcell_n) {
      Append<loadcell_n_t>(event, &log->loadcell, report);
    } else if (event.channel == channels.imu) {
      Append<imu_t>(event, &log->imu, report);
    } else if (event.channel == channels.vehicle && !log->has_vehicle) {
      vehicle_description_t message;
      if (DecodeMessage(event.data.data(), event.data.size(), &message) != DecodeError::kNone) {
        ++report->decode_errors;
        continue;
      }
      std::string why;
      if (!FromMessage(message, &log->vehicle, &why)) {
        *error = path + ": VEHICLE: " + why;
        return false;
      }
      log->has_vehicle = true;
    }
  }
  report->truncated_tail = reader.TruncatedTail();
  report->tail_offset = reader.tail_offset();
  report->file_size = reader.file_size();
  return CheckLogUsable(reader, path, min_usable_fraction, error, &report->damage);
}

}  // namespace birotor
