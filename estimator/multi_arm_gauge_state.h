// What the N-arm estimator keeps across a restart (the gauge state file of a
// vehicle with N arms, nodes/vehicle_state_file.h): each gauge's offset o_i
// as known at the stop, with its sigma, and the tip-mass ratio r the
// arm-mode test learned (every arm's m_p,i = r times the description's),
// with its sigma. MultiArmPipeline::GaugeState gives it at a stop and
// MultiArmPipeline::ResumeGaugeState starts from it.
#pragma once

#include "estimator/gauge_calibration.h"
#include "samples/multi_arm_samples.h"

namespace birotor {

struct MultiArmGaugeState {
  int arm_count = 0;                                          // entries [0, arm_count) are used
  ArmValues offset_rad{};                                     // o_i: gauge i's raw reading at zero deflection [rad]
  ArmValues offset_std_rad{};                                 // one sigma of o_i [rad]
  GaugeOffsetSource source = GaugeOffsetSource::kParameters;  // where the offsets came from
  // The tip mass the arm-mode test learned (model_consistency
  // arm_mode_learn_tip_mass): r and its one sigma; has_tip_mass false when
  // it is not learned (the description's m_p,i).
  bool has_tip_mass = false;
  double tip_mass_ratio = 1.0;      // r [1]
  double tip_mass_ratio_std = 0.0;  // [1]
};

}  // namespace birotor
