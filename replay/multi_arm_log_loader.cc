#include "replay/multi_arm_log_loader.h"

#include <algorithm>

#include "transport/channels.h"
#include "transport/counted_messages.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// Entries [0, min(count, kMaxSampleArms)) of a counted array.
template <class Array>
void CopyEntries(const std::vector<double>& from, int count, Array* to) {
  const size_t n = std::min<size_t>(static_cast<size_t>(std::max(count, 0)), std::min(from.size(), to->size()));
  std::copy_n(from.begin(), n, to->begin());
}

MultiArmStrainSample FromCounted(const strain_n_t& m) {
  MultiArmStrainSample s;
  s.utime = m.utime;
  s.seq = m.seq;
  s.n_arms = m.n_arms;
  CopyEntries(m.deflection_rad, m.n_arms, &s.deflection_rad);
  return s;
}

MultiArmMotorSample FromCounted(const motor_n_t& m) {
  MultiArmMotorSample s;
  s.utime = m.utime;
  s.seq = m.seq;
  s.n_rotors = m.n_rotors;
  CopyEntries(m.omega_cmd_rad_s, m.n_rotors, &s.omega_cmd_rad_s);
  CopyEntries(m.omega_meas_rad_s, m.n_rotors, &s.omega_meas_rad_s);
  return s;
}

MultiArmLoadCellSample FromCounted(const loadcell_n_t& m) {
  MultiArmLoadCellSample s;
  s.utime = m.utime;
  s.seq = m.seq;
  s.n_rotors = m.n_rotors;
  CopyEntries(m.force_n, m.n_rotors, &s.force_n);
  return s;
}

ImuSample FromCounted(const imu_t& m) { return FromMessage(m); }

template <class Msg, class Sample>
void Append(const LogEvent& event, std::vector<Sample>* out, LogLoadReport* report) {
  Msg message;
  if (DecodeMessage(event.data.data(), event.data.size(), &message) != DecodeError::kNone) {
    ++report->decode_errors;
    return;
  }
  out->push_back(FromCounted(message));
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
