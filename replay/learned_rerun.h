// What a flight log's own inputs support (issue 37 item 4): the estimator
// re-run over the log's STRAIN, MOTOR, IMU and POSE (the replay core, as
// birotor-replay runs it) with the vehicle the values will be deployed into,
// and the learned values of its final state. `birotor-identify --learned LOG`
// deploys these, never a recorded ESTIMATOR_STATUS (unauthenticated: one
// forged message would otherwise set the vehicle's gauge scales and mass).
#pragma once

#include <string>

#include "estimator/estimator_config.h"
#include "params/learned_parameter_update.h"
#include "replay/replayer.h"

namespace birotor {

struct LearnedRerun {
  LearnedVehicleValues learned;  // the re-run's final state
  ReplayStats stats;
  std::string damage;  // a warning line for a usable log with corrupt events or a cut tail
};

// Re-runs config (its vehicle: the one the values are learned relative to;
// its ekf learn_strain_scale / learn_body_mass and model_consistency
// arm_mode_learn_tip_mass: what is learned) over the inputs of the log at
// log_path on prefix's channels. False with a one-line *error naming the
// file, *rerun unusable, when: config learns nothing (every learn switch off), the log is not usable (ReplayLogFile),
// no STRAIN produced a FORCE estimate or no MOTOR sample was accepted (nothing to learn from), or the re-run ended
// without a learned value.
bool RelearnFromLog(const std::string& log_path, const EstimatorConfig& config, const std::string& prefix,
                    double min_usable_fraction, LearnedRerun* rerun, std::string* error);

}  // namespace birotor
