// Learned values from a gauge state file or a flight log.
#include "nodes/learned_values_file.h"

#include <limits>

#include "nodes/gauge_state_file.h"
#include "nodes/status_message.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

bool FromStateFile(const std::string& path, const std::string& vehicle_checksum, LearnedVehicleValues* learned,
                   std::string* error) {
  // The offsets are not deployed (a tare measures them): no bound on them here.
  GaugeCalibration state;
  if (!ReadGaugeState(path, vehicle_checksum, std::numeric_limits<double>::infinity(), &state, error)) return false;
  *learned = LearnedVehicleValues();
  learned->has_strain_scale = state.has_strain_scale;
  for (int i = 0; i < 2; ++i) {
    learned->strain_scale[i] = state.strain_scale[i];
    learned->strain_scale_std[i] = state.strain_scale_std[i];
  }
  return true;
}

bool FromLog(const std::string& path, const std::string& prefix, const std::string& vehicle_checksum,
             LearnedVehicleValues* learned, std::string* error) {
  const std::string channel = MakeChannelNames(prefix).estimator_status;
  estimator_status_t status;
  if (!ReadLastLearnedStatus(path, channel, &status, error)) return false;
  if (status.vehicle_checksum != vehicle_checksum) {
    *error = path + ": its newest " + channel + " with a learned value was flown with another vehicle or parameter " +
             "file (vehicle checksum '" + status.vehicle_checksum + "', expected " + vehicle_checksum + ")";
    return false;
  }
  *learned = LearnedVehicleValues();
  learned->has_strain_scale = status.strain_scale_source != kLearnedSourceParams;
  for (int i = 0; i < 2; ++i) {
    learned->strain_scale[i] = status.strain_scale[i];
    learned->strain_scale_std[i] = status.strain_scale_std[i];
  }
  learned->has_body_mass = status.body_mass_source != kLearnedSourceParams;
  learned->body_mass_kg = status.body_mass_kg;
  learned->body_mass_std_kg = status.body_mass_std_kg;
  return true;
}

}  // namespace

bool ReadLearnedValues(const std::string& path, const std::string& prefix, const std::string& vehicle_checksum,
                       LearnedVehicleValues* learned, std::string* error) {
  LogReader probe;
  std::string not_a_log;
  if (probe.Open(path, &not_a_log)) return FromLog(path, prefix, vehicle_checksum, learned, error);
  if (FromStateFile(path, vehicle_checksum, learned, error)) return true;
  if (error->find("not a gauge state file") != std::string::npos) *error += ", nor an LCM log";
  return false;
}

}  // namespace birotor
