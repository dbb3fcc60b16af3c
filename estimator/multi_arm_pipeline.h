// The input path of the N-arm estimator (the method of estimator.method for N
// arms behind MultiArmForceEstimator, estimator/multi_arm_ekf.h), shared
// by birotor-estimator --vehicle, birotor-replay --vehicle and the N-rotor
// lock-step loop so all give the same numbers: checks every sample's
// readings (finite, in range, the vehicle's count), admits it by stamp and
// seq (input_admission.h: order, duplicates, time outliers, conflicts, as
// for the birotor), resets the filter at the start, after a strain gap of
// reset_gap_s and after a backwards time jump, replaces a non-finite
// estimate by the last finite one, owns the input facts of the status (no
// motor input, stale, conflict, reset), has the status composed in
// force_status.cc from them, the filter's and the model-consistency
// monitor's (the birotor's ModelConsistencyMonitor on the filter's fusion
// reports, for N rotors: STATUS_MODEL_MISMATCH withdraws VALID,
// docs/mismatch.md), and keeps the per-input health counters of
// ESTIMATOR_STATUS, and notches each gauge's rotor harmonics (HarmonicNotch
// tuned from MultiArmSpeedTracker's speeds at the strain stamp,
// harmonic_notch.multi_arm_enabled). The per-input fusion counters (fused,
// gated, not fused, NIS, gate; the accelerometer's of its own) are counted
// from the filter's fusion reports as the birotor's (fusion_counters.h).
// The arm-mode test (ArmModeMonitor on the description's most readable arm
// mode) flags a tip-mass error as the birotor's does, and until it confirms
// the file's tip mass each published sigma carries the tip mass's prior.
// The learned tip mass and the gauge offsets persist across a restart as
// the birotor's do (GaugeState at a stop, ResumeGaugeState at the start:
// the gauge state file of nodes/vehicle_state_file.h). What the birotor's
// EstimatorPipeline has and this one has not yet: the ground tare
// (docs/estimator.md, "The EKF for N arms").
// No LCM, no logging, no allocation per sample.
#pragma once

#include <cstdint>
#include <memory>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/force_status.h"
#include "estimator/fusion_counters.h"
#include "estimator/harmonic_notch.h"
#include "estimator/input_admission.h"
#include "estimator/model_consistency.h"
#include "estimator/multi_arm_ekf.h"
#include "estimator/multi_arm_gauge_state.h"
#include "estimator/multi_arm_linear_speed.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"
#include "samples/samples.h"

namespace birotor {

struct MultiArmPipelineHealth {
  InputCounters inputs[kNumInputChannels];  // STRAIN (STRAIN_N), MOTOR (MOTOR_N), IMU, POSE
  // The IMU's a_z as a measurement of its own, as the birotor's
  // PipelineHealth::accelerometer: accepted IMU samples with a finite a_z,
  // the fusion counters and NIS of its reports, its gate.
  InputCounters accelerometer;
  int64_t newest_utime = -1;  // newest accepted sample over all inputs [us]
  int64_t resets = 0;         // re-initialisations; the first strain sample counts (kStart)
  ResetReason last_reset_reason = ResetReason::kNone;
  int64_t published = 0;  // estimates produced
  // The newest estimate's status and the facts it was composed from (the
  // service composes ESTIMATOR_STATUS's status from them with its own).
  int32_t last_status = 0;
  int32_t last_rotor_fault_bits = 0;
  MultiArmFilterFacts last_filter_facts;
  InputStatusFacts last_input_facts;
  ConsistencyStatusFacts last_consistency_facts;
  MultiArmForceEstimate last_estimate;
  // Model consistency (STATUS_MODEL_MISMATCH and its statistic, docs/mismatch.md).
  ModelConsistencyState consistency;
  // The method's learned scale on each gauge's noise variance
  // (MultiArmForceEstimator::strain_noise_scale; 1 when it learns none) [1].
  ArmValues strain_noise_scale = UnitThrustScales();
  bool strain_noise_learned = false;  // the method learns it (MultiArmForceEstimator::learns_strain_noise)
  // Where the gauge offsets the strain is read with come from: the
  // description's, or the state file's (ResumeGaugeState).
  GaugeOffsetSource gauge_offset_source = GaugeOffsetSource::kParameters;
  // The tip masses the method flies, r times each arm's m_p,i of the
  // description (model_consistency arm_mode_learn_tip_mass): r = 1 until
  // the arm-mode test learns it (tip_mass_learned, with its one sigma: the
  // prior's until a reading); kept while learning pauses. Resumed from the
  // state file (learning on): the persisted r and sigma from the first
  // sample, tip_mass_from_state_file until the arm-mode test takes its
  // first reading in this run (as the birotor's PipelineHealth).
  bool tip_mass_learned = false;
  double tip_mass_ratio = 1.0;      // r [1]
  double tip_mass_ratio_std = 0.0;  // its one sigma, when learned [1]
  bool tip_mass_from_state_file = false;
};

class MultiArmPipeline {
 public:
  // config.vehicle is the description (2 .. kMaxArms arms); config.method
  // selects the method (MakeMultiArmForceEstimator, estimation_method.h:
  // ekf, linear_kf, luenberger, inversion) with its sections, and pipeline:
  // is used. Throws std::invalid_argument for a method or description the
  // registry cannot serve.
  explicit MultiArmPipeline(const EstimatorConfig& config);

  void CountReceived(InputChannel channel) { ++health_.inputs[static_cast<int>(channel)].received; }
  void CountDecodeError(InputChannel channel) { ++health_.inputs[static_cast<int>(channel)].decode_errors; }
  void CountOverloadDrop(InputChannel channel) { ++health_.inputs[static_cast<int>(channel)].dropped_overload; }

  void OnMotor(const MultiArmMotorSample& sample);
  void OnImu(const ImuSample& sample);
  void OnPose(const PoseSample& sample);  // counted; the EKF takes its height (ground may touch)
  // True and *estimate filled when an estimate must be published (one per
  // accepted strain sample; never NaN).
  bool OnStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate);

  const MultiArmPipelineHealth& health() const { return health_; }
  const VehicleDescription& vehicle() const { return config_.vehicle; }
  const EstimatorConfig& config() const { return config_; }
  void TakePeriod();  // clears the per-period fields after a status message

  // Starts from an earlier run's state (the gauge state file; before the
  // first sample): each gauge is read with the persisted offset o_i, the
  // method's offset prior is its sigma, and with tip-mass learning on the
  // persisted r flies from the first sample with its sigma, learning
  // resuming from it (a value the readings reject is learned afresh,
  // ArmModeMonitor). An arm count other than the description's is ignored.
  void ResumeGaugeState(const MultiArmGaugeState& state);
  // What a stop persists: each offset as known now (the one in use plus
  // what the method learned on top, s_i e_i, with its sigma s_i std(e_i)),
  // and the learned r with its sigma when the tip mass is learned.
  MultiArmGaugeState GaugeState() const;

 private:
  bool Admit(InputChannel channel, int64_t utime, int32_t seq, Admission* admission);
  bool ValidStrain(const MultiArmStrainSample& sample) const;
  bool ValidMotor(const MultiArmMotorSample& sample) const;
  // Resets before the filter sees the strain sample; true when the strain
  // interval makes the input stale.
  bool CheckStrainTiming(int64_t utime, int64_t previous_utime, bool backwards_jump);
  void ResetFilter(ResetReason reason, int64_t utime);
  // The deflections as the filter gets them: rotor harmonics notched (when on).
  MultiArmStrainSample Condition(const MultiArmStrainSample& sample, int64_t previous_utime, bool backwards_jump);
  void ReplaceNonFinite(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate);
  // Until the arm mode confirms the file's tip mass, or while it is
  // learned, each published sigma carries what the tip mass's sigma puts
  // into that rotor's force: hypot(sigma_i, s rotor_tip_weight_n_i), s the
  // monitor's relative sigma (arm_mode_unconfirmed_tip_mass_std, or the
  // learned one), as the birotor's PublishedForceStd.
  void WidenForUnconfirmedTipMass(MultiArmForceEstimate* estimate) const;
  // The offsets' departure as a payload's force (offset_force_std_n of the
  // facts) in each rotor's sigma, in quadrature (offset_departure_in_sigma_above).
  static void WidenForOffsetDeparture(const ConsistencyStatusFacts& consistency, MultiArmForceEstimate* estimate);
  // The filter flies the m_p the arm-mode test learned (every arm's r times
  // the description's), from the next strain sample on.
  void HandOverTipMass();
  // An earlier run's r and sigma into the arm-mode test's learning and the
  // method, when this run learns the tip mass.
  void ResumeTipMass(double ratio, double ratio_std);
  void FillInputFacts(int64_t utime, bool stale, InputStatusFacts* facts);
  // The method's fusion reports of this strain sample into the monitor and
  // the per-input counters, the sample as the filter got it into the
  // arm-mode test; the monitor's facts on the estimate.
  // Each gauge's offset in use and its sigma: the calibration plus what the
  // method learned on top (s_i e_i); false when the method learns none.
  bool OffsetsInUse(ArmValues* offset_rad, ArmValues* offset_std_rad) const;
  ConsistencyStatusFacts JudgeConsistency(const MultiArmStrainSample& deflection,
                                          const MultiArmForceEstimate& estimate);

  EstimatorConfig config_;
  std::unique_ptr<MultiArmForceEstimator> filter_;
  ArmModeExpectation arm_mode_;          // the file's arm mode (ExpectedArmMode of the description)
  ModelConsistencyMonitor consistency_;  // judges every fusion report (docs/mismatch.md)
  InputAdmission admission_;
  bool notch_on_;                     // harmonic_notch.enabled and multi_arm_enabled
  MultiArmSpeedTracker rotor_speed_;  // for the harmonic notches
  HarmonicNotch notch_;
  MultiArmPipelineHealth health_;
  bool started_ = false;
  bool reset_flag_pending_ = false;
  bool has_motor_ = false;
  MultiArmMotorSample last_motor_;
  int64_t first_motor_utime_ = -1;
  bool has_finite_estimate_ = false;
  MultiArmForceEstimate last_finite_estimate_;
  double tip_mass_ratio_in_filter_ = 1.0;  // the r last handed to the filter [1]
  // The offsets each gauge is read with: the description's, or the state
  // file's (ResumeGaugeState), with their sigma and source.
  MultiArmGaugeState calibration_;
  bool offsets_resumed_ = false;  // the raw readings are moved onto the description's offsets
};

}  // namespace birotor
