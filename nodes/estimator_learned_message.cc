// Building ESTIMATOR_LEARNED_N from the birotor's and the N-arm pipeline.
#include "nodes/estimator_learned_message.h"

#include <cmath>
#include <cstddef>
#include <limits>

#include "model/vehicle_description_checksum.h"
#include "nodes/status_message.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* LearnedOrParams(bool learned) { return learned ? kLearnedSourceLearned : kLearnedSourceParams; }

// params (the file's m_p), state_file (an earlier run's, no reading yet in
// this one) or learned (refined by this run's readings).
const char* TipMassSource(bool learned, bool from_state_file) {
  if (!learned) return kLearnedSourceParams;
  return from_state_file ? kLearnedSourceStateFile : kLearnedSourceLearned;
}

// Gauge i's noise as the method weighs it, sqrt(R_i) = sqrt(scale_i)
// strain_noise_rad [rad]; NaN for an arm without a gauge (no R_i).
double StrainNoiseRad(const VehicleDescription& vehicle, const EkfOptions& ekf, int arm, double variance_scale) {
  if (!vehicle.arms[static_cast<size_t>(arm)].has_gauge) return kNaN;
  return std::sqrt(variance_scale) * ekf.strain_noise_rad;
}

}  // namespace

void PrepareEstimatorLearned(const VehicleDescription& vehicle, estimator_learned_n_t* message) {
  const size_t n = static_cast<size_t>(vehicle.arm_count);
  message->vehicle_checksum = DescriptionChecksum(vehicle);
  message->n_arms = static_cast<int8_t>(vehicle.arm_count);
  message->strain_scale.assign(n, 1.0);
  message->strain_scale_std.assign(n, kNaN);
  message->tip_mass_kg.assign(n, kNaN);
  message->tip_mass_std_kg.assign(n, kNaN);
  message->strain_noise_rad.assign(n, kNaN);
  // Room for the longest source ("state_file") in each string.
  for (std::string* source : {&message->strain_scale_source, &message->tip_mass_source, &message->strain_noise_source,
                              &message->body_mass_source}) {
    source->reserve(16);
    *source = kLearnedSourceParams;
  }
}

void FillEstimatorLearned(const PipelineHealth& health, const EstimatorConfig& config, const estimator_status_t& status,
                          estimator_learned_n_t* message) {
  message->utime = status.utime;
  message->seq = status.seq;
  const bool scale_learned = health.gauge.has_strain_scale;
  for (int arm = 0; arm < message->n_arms; ++arm) {
    const size_t i = static_cast<size_t>(arm);
    message->strain_scale[i] = scale_learned ? health.gauge.strain_scale[arm] : 1.0;
    message->strain_scale_std[i] = scale_learned ? health.gauge.strain_scale_std[arm] : kNaN;
    message->tip_mass_kg[i] = health.tip_mass_kg;
    message->tip_mass_std_kg[i] = health.tip_mass_learned ? health.tip_mass_std_kg : kNaN;
    message->strain_noise_rad[i] = StrainNoiseRad(config.vehicle, config.ekf, arm, health.strain_noise_scale[arm]);
  }
  message->strain_scale_source = StrainScaleSource(health);
  message->tip_mass_source = TipMassSource(health.tip_mass_learned, health.tip_mass_from_state_file);
  message->strain_noise_source = LearnedOrParams(health.strain_noise_learned);
  message->body_mass_kg = health.body_mass_kg;
  message->body_mass_std_kg = health.body_mass_learned ? health.body_mass_std_kg : kNaN;
  message->body_mass_source = LearnedOrParams(health.body_mass_learned);
}

void FillEstimatorLearned(const MultiArmPipelineHealth& health, const EstimatorConfig& config,
                          const estimator_status_t& status, estimator_learned_n_t* message) {
  message->utime = status.utime;
  message->seq = status.seq;
  const VehicleDescription& vehicle = config.vehicle;
  // The arm-mode test learns one r for every arm: m_p,i = r m_p,i of the file.
  const bool learned = health.tip_mass_learned;
  for (int arm = 0; arm < message->n_arms; ++arm) {
    const size_t i = static_cast<size_t>(arm);
    message->strain_scale[i] = vehicle.arms[i].has_gauge ? 1.0 : kNaN;
    message->strain_scale_std[i] = kNaN;
    message->tip_mass_kg[i] = (learned ? health.tip_mass_ratio : 1.0) * vehicle.arms[i].tip_mass_kg;
    message->tip_mass_std_kg[i] = learned ? health.tip_mass_ratio_std * vehicle.arms[i].tip_mass_kg : kNaN;
    message->strain_noise_rad[i] = StrainNoiseRad(vehicle, config.ekf, arm, health.strain_noise_scale[i]);
  }
  message->strain_scale_source = kLearnedSourceParams;
  message->tip_mass_source = TipMassSource(learned, health.tip_mass_from_state_file);
  message->strain_noise_source = LearnedOrParams(health.strain_noise_learned);
  message->body_mass_kg = vehicle.body_mass_kg;
  message->body_mass_std_kg = kNaN;
  message->body_mass_source = kLearnedSourceParams;
}

}  // namespace birotor
