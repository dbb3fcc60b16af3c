// Learned values from a gauge state file or a flight log.
#include "nodes/learned_values_file.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "nodes/gauge_state_file.h"
#include "nodes/status_message.h"
#include "transport/channels.h"
#include "transport/log_io.h"

namespace birotor {

bool IsLcmLog(const std::string& path) {
  LogReader probe;
  std::string not_a_log;
  return probe.Open(path, &not_a_log);
}

bool ReadLearnedState(const std::string& path, const std::string& vehicle_checksum,
                      const MessageAuthenticator& authenticator, LearnedVehicleValues* learned, std::string* error) {
  // The offsets are not deployed (a tare measures them): no bound on them here.
  const double any_offset = std::numeric_limits<double>::infinity();
  GaugeCalibration state;
  if (!ReadGaugeState(path, vehicle_checksum, any_offset, authenticator, &state, error)) {
    // A file without a mac line may be no state file at all: say so.
    std::string kind_error;
    GaugeCalibration unused;
    if (!ReadGaugeState(path, vehicle_checksum, any_offset, &unused, &kind_error) &&
        kind_error.find("not a gauge state file") != std::string::npos) {
      *error = kind_error + ", nor an LCM log";
    }
    return false;
  }
  *learned = LearnedVehicleValues();
  learned->has_strain_scale = state.has_strain_scale;
  for (int i = 0; i < kBirotorRotors; ++i) {
    learned->strain_scale[i] = state.strain_scale[i];
    learned->strain_scale_std[i] = state.strain_scale_std[i];
  }
  learned->has_tip_mass = state.has_tip_mass;
  learned->tip_mass_kg = state.tip_mass_kg;
  learned->tip_mass_std_kg = state.tip_mass_std_kg;
  return true;
}

bool ReadRecordedLearnedValues(const std::string& path, const std::string& prefix, LearnedVehicleValues* recorded,
                               std::string* vehicle_checksum, std::string* error) {
  estimator_status_t status;
  if (!ReadLastLearnedStatus(path, MakeChannelNames(prefix).estimator_status, &status, error)) return false;
  *vehicle_checksum = status.vehicle_checksum;
  *recorded = LearnedVehicleValues();
  recorded->has_strain_scale = status.strain_scale_source != kLearnedSourceParams;
  for (int i = 0; i < kBirotorRotors; ++i) {
    recorded->strain_scale[i] = status.strain_scale[i];
    recorded->strain_scale_std[i] = status.strain_scale_std[i];
  }
  recorded->has_body_mass = status.body_mass_source != kLearnedSourceParams;
  recorded->body_mass_kg = status.body_mass_kg;
  recorded->body_mass_std_kg = status.body_mass_std_kg;
  return true;
}

namespace {

// One field of the comparison; appended to *out when it disagrees.
void CompareField(const std::string& field, bool recorded_has, double recorded, double recorded_std, bool rerun_has,
                  double rerun, double rerun_std, double max_sigmas, std::vector<LearnedDisagreement>* out) {
  if (!recorded_has) return;
  LearnedDisagreement d{field, recorded, recorded_std, rerun_has, rerun, rerun_std, 0.0};
  if (rerun_has) {
    const double combined = std::hypot(recorded_std, rerun_std);
    const double difference = std::abs(recorded - rerun);
    // A non-finite value or sigma is a disagreement whatever its size.
    d.sigmas = combined > 0 ? difference / combined : (difference > 0 ? INFINITY : 0.0);
    if (std::isfinite(d.sigmas) && d.sigmas <= max_sigmas) return;
  }
  out->push_back(d);
}

}  // namespace

std::vector<LearnedDisagreement> CompareLearnedValues(const LearnedVehicleValues& recorded,
                                                      const LearnedVehicleValues& rerun, double max_sigmas) {
  std::vector<LearnedDisagreement> out;
  for (int i = 0; i < kBirotorRotors; ++i) {
    CompareField("strain_scale[" + std::to_string(i) + "]", recorded.has_strain_scale, recorded.strain_scale[i],
                 recorded.strain_scale_std[i], rerun.has_strain_scale, rerun.strain_scale[i], rerun.strain_scale_std[i],
                 max_sigmas, &out);
  }
  CompareField("body_mass_kg", recorded.has_body_mass, recorded.body_mass_kg, recorded.body_mass_std_kg,
               rerun.has_body_mass, rerun.body_mass_kg, rerun.body_mass_std_kg, max_sigmas, &out);
  CompareField("tip_mass_kg", recorded.has_tip_mass, recorded.tip_mass_kg, recorded.tip_mass_std_kg, rerun.has_tip_mass,
               rerun.tip_mass_kg, rerun.tip_mass_std_kg, max_sigmas, &out);
  return out;
}

std::string DisagreementText(const LearnedDisagreement& d) {
  char text[320];
  if (d.rerun_learned) {
    std::snprintf(text, sizeof(text),
                  "%s: the log's ESTIMATOR_STATUS says %.6g +- %.3g, its inputs re-run give %.6g +- %.3g (%.1f "
                  "combined sigmas apart): the recorded status was not used",
                  d.field.c_str(), d.recorded, d.recorded_std, d.rerun, d.rerun_std, d.sigmas);
  } else {
    std::snprintf(text, sizeof(text),
                  "%s: the log's ESTIMATOR_STATUS says %.6g +- %.3g, but the re-run of its inputs did not learn it: "
                  "the recorded status was not used",
                  d.field.c_str(), d.recorded, d.recorded_std);
  }
  return text;
}

}  // namespace birotor
