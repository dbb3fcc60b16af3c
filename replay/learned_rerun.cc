// The learned values a flight log's inputs support: the estimator re-run.
#include "replay/learned_rerun.h"

namespace birotor {
namespace {

// The re-run's FORCE and ESTIMATOR_STATUS are not needed: only its final state.
class DiscardSink : public MessageSink {
 public:
  void Publish(const std::string&, int64_t, const void*, size_t) override {}
};

// The learned values of the re-run's final state.
LearnedVehicleValues FinalLearnedValues(const EstimatorConfig& config, const PipelineHealth& health) {
  LearnedVehicleValues learned;
  learned.has_strain_scale = config.ekf.learn_strain_scale && health.gauge.has_strain_scale;
  for (int i = 0; i < kBirotorRotors; ++i) {
    learned.strain_scale[i] = health.gauge.strain_scale[i];
    learned.strain_scale_std[i] = health.gauge.strain_scale_std[i];
  }
  learned.has_body_mass = config.ekf.learn_body_mass && health.body_mass_learned;
  learned.body_mass_kg = health.body_mass_kg;
  learned.body_mass_std_kg = health.body_mass_std_kg;
  learned.has_tip_mass = config.model_consistency.arm_mode_learn_tip_mass && health.tip_mass_learned;
  learned.tip_mass_kg = health.tip_mass_kg;
  learned.tip_mass_std_kg = health.tip_mass_std_kg;
  return learned;
}

}  // namespace

bool RelearnFromLog(const std::string& log_path, const EstimatorConfig& config, const std::string& prefix,
                    double min_usable_fraction, LearnedRerun* rerun, std::string* error) {
  if (!config.ekf.learn_strain_scale && !config.ekf.learn_body_mass &&
      !config.model_consistency.arm_mode_learn_tip_mass) {
    *error = log_path + ": the estimator configuration learns nothing (ekf: learn_strain_scale and learn_body_mass, " +
             "model_consistency: arm_mode_learn_tip_mass are off): give the estimator file the flight ran with";
    return false;
  }
  ReplayOptions options;
  options.prefix = prefix;
  options.copy_truth = false;
  DiscardSink discard;
  Replayer replayer(config, options, &discard);
  if (!ReplayLogFile(log_path, &replayer, &rerun->damage, error, min_usable_fraction)) return false;
  rerun->stats = replayer.stats();
  const PipelineHealth& health = replayer.service().health();
  const InputCounters& motor = health.inputs[static_cast<int>(InputChannel::kMotor)];
  if (rerun->stats.forces == 0 || motor.received == motor.rejected_invalid + motor.decode_errors) {
    *error = log_path + ": its inputs cannot support a learned value (" + std::to_string(rerun->stats.forces) +
             " FORCE estimates from " + prefix + "STRAIN, " + std::to_string(motor.received) + " " + prefix +
             "MOTOR samples)";
    return false;
  }
  rerun->learned = FinalLearnedValues(config, health);
  if (!rerun->learned.has_strain_scale && !rerun->learned.has_body_mass && !rerun->learned.has_tip_mass) {
    *error = log_path + ": the estimator re-run over its inputs learned nothing (" +
             std::to_string(rerun->stats.forces) + " FORCE estimates, method " + config.method + ")";
    return false;
  }
  return true;
}

}  // namespace birotor
