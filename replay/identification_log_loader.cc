#include "replay/identification_log_loader.h"

#include "replay/log_events.h"
#include "transport/channels.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

template <class Msg, class Sample>
void Append(const LogEvent& event, std::vector<Sample>* out, LogLoadReport* report) {
  Msg message;
  if (DecodeCounted(event, &message, report)) out->push_back(FromMessage(message));
}

}  // namespace

bool LoadSensorLog(const std::string& path, const std::string& prefix, SensorLog* log, LogLoadReport* report,
                   std::string* error, double min_usable_fraction) {
  const ChannelNames channels = MakeChannelNames(prefix);
  *log = SensorLog();
  log->source = path;
  return ReadLogEvents(path, min_usable_fraction, report, error, [&](const LogEvent& event) {
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
    return true;
  });
}

}  // namespace birotor
