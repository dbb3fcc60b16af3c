// The slow vehicle parameters of the EKF (issue 27 item 2, docs/mismatch.md):
// when they learn (free flight only), their freeze on the ground, and what
// the filter reports and takes back of them. Members of EkfForceEstimator.
#include <algorithm>
#include <cmath>

#include "estimator/ekf_force_estimator.h"

namespace birotor {
namespace {

constexpr double kMicrosecond = 1e-6;

}  // namespace

void EkfForceEstimator::UpdateLearning() {
  // Learn only in free flight with the rotors carrying the vehicle: at rest
  // the contact is judged from the thrust estimate, so the first samples
  // count as airborne until the support force is seen; and before any MOTOR
  // sample the thrust is the assumed hover thrust (frozen, undecided).
  if (!has_motor_) {
    FreezeSlowParameters(true);
    return;
  }
  const double total_force_n = process_.Force(state_, 0) + process_.Force(state_, 1);
  const bool flying = !(options_.body_held || contact_.supported()) && total_force_n >= params_.HoverForceN();
  if (!flying) {
    flying_since_utime_ = kNotFlying;
  } else if (flying_since_utime_ == kNotFlying) {
    flying_since_utime_ = last_utime_;  // lift-off: the delay starts
  }
  const bool lifting_off =
      flying_since_utime_ >= 0 && (last_utime_ - flying_since_utime_) * kMicrosecond < options_.slow_learning_delay_s;
  FreezeSlowParameters(!flying || lifting_off);
}

void EkfForceEstimator::FreezeSlowParameters(bool frozen) {
  if (frozen == slow_frozen_) return;
  slow_frozen_ = frozen;
  for (const int p : {kStrainScale1, kStrainScale2, kBodyMassScale}) {
    if (variance_floor_[p] == 0.0) continue;  // not learned
    if (frozen) {
      // Frozen at its value, uncorrelated: no gain.
      learned_.std[p] = std::sqrt(std::max(covariance_(p, p), 0.0));
      covariance_.row(p).setZero();
      covariance_.col(p).setZero();
    } else {
      covariance_(p, p) = learned_.std[p] * learned_.std[p];
    }
  }
}

void EkfForceEstimator::FillLearnedParameters(StrainStepInfo* info) {
  info->has_learned_strain_scale = options_.learn_strain_scale;
  info->has_learned_body_mass = options_.learn_body_mass;
  for (const int p : {kStrainScale1, kStrainScale2, kBodyMassScale}) {
    learned_.value[p] = state_(p);
    if (!slow_frozen_) learned_.std[p] = std::sqrt(std::max(covariance_(p, p), 0.0));
  }
  for (int i = 0; i < 2; ++i) {
    info->learned_strain_scale[i] = learned_.value[kStrainScaleIndex[i]];
    info->learned_strain_scale_std[i] = learned_.std[kStrainScaleIndex[i]];
  }
  info->learned_body_mass_kg = learned_.value[kBodyMassScale] * params_.body_mass_kg;
  info->learned_body_mass_std_kg = learned_.std[kBodyMassScale] * params_.body_mass_kg;
}

void EkfForceEstimator::SetLearnedParameters(const LearnedVehicleParameters& learned) {
  for (int i = 0; i < 2 && options_.learn_strain_scale && learned.has_strain_scale; ++i) {
    learned_.value[kStrainScaleIndex[i]] = learned.strain_scale[i];
    learned_.std[kStrainScaleIndex[i]] = learned.strain_scale_std[i];
  }
  if (options_.learn_body_mass && learned.has_body_mass) {
    learned_.value[kBodyMassScale] = learned.body_mass_kg / params_.body_mass_kg;
    learned_.std[kBodyMassScale] = learned.body_mass_std_kg / params_.body_mass_kg;
  }
}

}  // namespace birotor
