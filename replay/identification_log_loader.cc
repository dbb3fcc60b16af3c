#include "replay/identification_log_loader.h"

#include "transport/channels.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

template <class Msg, class Sample>
void Append(const LogEvent& event, std::vector<Sample>* out, LogLoadReport* report) {
  Msg message;
  if (DecodeMessage(event.data.data(), event.data.size(), &message) != DecodeError::kNone) {
    ++report->decode_errors;
    return;
  }
  out->push_back(FromMessage(message));
}

}  // namespace

bool LoadSensorLog(const std::string& path, const std::string& prefix, SensorLog* log, LogLoadReport* report,
                   std::string* error, double min_usable_fraction) {
  LogReader reader;
  if (!reader.Open(path, error)) return false;
  const ChannelNames channels = MakeChannelNames(prefix);
  *log = SensorLog();
  *report = LogLoadReport();
  log->source = path;
  LogEvent event;
  while (reader.Next(&event)) {
    ++report->events;
    if (event.channel == channels.strain) {
      Append<strain_t>(event, &log->strain, report);
    } else if (event.channel == channels.motor) {
      Append<motor_t>(event, &log->motor, report);
    } else if (event.channel == channels.imu) {
      Append<imu_t>(event, &log->imu, report);
    } else if (event.channel == channels.pose) {
      Append<pose_t>(event, &log->pose, report);
    } else if (event.channel == channels.loadcell) {
      Append<loadcell_t>(event, &log->loadcell, report);
    } else if (event.channel == channels.truth) {
      Append<truth_t>(event, &log->truth, report);
    }
  }
  report->truncated_tail = reader.TruncatedTail();
  report->tail_offset = reader.tail_offset();
  report->file_size = reader.file_size();
  return CheckLogUsable(reader, path, min_usable_fraction, error, &report->damage);
}

}  // namespace birotor
