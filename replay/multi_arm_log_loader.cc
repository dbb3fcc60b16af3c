#include "replay/multi_arm_log_loader.h"

#include "replay/log_events.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"
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
  if (!DecodeCounted(event, &message, report)) return;
  out->emplace_back();
  Convert(message, &out->back());
}

}  // namespace

bool LoadMultiArmBenchLog(const std::string& path, const std::string& prefix, MultiArmBenchLog* log,
                          LogLoadReport* report, std::string* error, double min_usable_fraction) {
  const ChannelNames channels = MakeChannelNames(prefix);
  *log = MultiArmBenchLog();
  log->source = path;
  return ReadLogEvents(path, min_usable_fraction, report, error, [&](const LogEvent& event) {
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
      if (!DecodeCounted(event, &message, report)) return true;
      std::string why;
      if (!FromMessage(message, &log->vehicle, &why)) {
        *error = path + ": VEHICLE: " + why;
        return false;
      }
      log->has_vehicle = true;
    }
    return true;
  });
}

}  // namespace birotor
