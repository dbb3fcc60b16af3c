// The estimator's input path, shared by the live daemon and the replay tool so
// both give the same numbers: checks every sample's readings (finite, in
// range), admits it by stamp and seq (input_admission.h: order, duplicates,
// time outliers, conflicts), calibrates the strain gauges (scale, and the
// offset from the parameters or a tare on the ground: gauge_tare.h), detects
// stale inputs and long gaps, resets the method after a gap or a backwards
// time jump, owns the input facts of the status (stale, no motor input,
// conflict, reset), composes the published status from its facts, the
// method's and the model-consistency monitor's (force_status.h), and keeps the health counters published on
// ESTIMATOR_STATUS (per input, from the method's fusion reports). No LCM and
// no logging here (nodes/ logs from the counters); no allocation per sample.
#pragma once

#include <cstdint>
#include <memory>

#include "estimator/estimation_method.h"
#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/force_status.h"
#include "estimator/fusion_counters.h"
#include "estimator/gauge_calibration.h"
#include "estimator/gauge_tare.h"
#include "estimator/harmonic_notch.h"
#include "estimator/input_admission.h"
#include "estimator/model_consistency.h"
#include "estimator/motor_speed_tracker.h"
#include "estimator/strain_scale_attribution.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

struct PipelineHealth {
  InputCounters inputs[kNumInputChannels];
  // The IMU's a_z as a measurement of its own (the EKF fuses it in flight):
  // received = accepted IMU samples with a finite a_z, the fusion counters
  // and NIS of its reports, its gate; the other fields stay 0.
  InputCounters accelerometer;
  // Newest accepted sample time over all inputs [us] (time outliers are not
  // accepted; a STRAIN stamp more than time_backwards_reset_s behind it resets it).
  int64_t newest_utime = -1;
  // Re-initialisations; the first strain sample counts as one (kStart).
  int64_t resets = 0;
  ResetReason last_reset_reason = ResetReason::kNone;
  int64_t published = 0;  // force estimates produced
  // The newest FORCE's status, and the facts it was composed from (which
  // say why VALID was withdrawn and why a sigma was widened).
  int32_t last_status = 0;
  ForceStatusFacts last_status_facts;
  ForceEstimate last_estimate;
  // Strain-gauge calibration: the scale in use and the offsets o_i as now
  // known (the calibration the method is given, from the file, a tare or
  // the state file, plus what the method learned in flight, with its sigma;
  // the daemon persists these), and the tare's counters.
  GaugeCalibration gauge;
  // The scale on each gauge's noise variance the method learned
  // (StrainStepInfo::strain_noise_scale; 1 when it learns none) [1]: not an
  // ESTIMATOR_STATUS field (its fingerprint stays); on ESTIMATOR_LEARNED_N
  // as the noise sqrt(scale_i) strain_noise_rad.
  double strain_noise_scale[2] = {1, 1};
  bool strain_noise_learned = false;  // the method learns it (ForceEstimator::learns_strain_noise)
  // The body mass in use (issue 27; ESTIMATOR_STATUS): the file's until the
  // method reports one it learns (body_mass_learned, with its one sigma),
  // and whether learning g_i (gauge.strain_scale) started from the value of
  // the state file (SetGaugeOffsets) rather than the file's 1.
  bool body_mass_learned = false;
  double body_mass_kg = 0;      // [kg]
  double body_mass_std_kg = 0;  // [kg], when learned
  bool strain_scale_from_state_file = false;
  // The tip mass m_p the method flies on both arms (issue 36; model_consistency
  // arm_mode_learn_tip_mass): the file's until the arm-mode test learns it
  // (tip_mass_learned, with its one sigma: the prior's until a reading);
  // kept while learning pauses, as the method keeps flying it. Resumed from
  // the state file (SetGaugeOffsets, learning on): the persisted m_p and
  // sigma from the first sample, tip_mass_from_state_file until the arm-mode
  // test takes its first reading in this run.
  bool tip_mass_learned = false;
  double tip_mass_kg = 0;      // [kg]
  double tip_mass_std_kg = 0;  // [kg], when learned
  bool tip_mass_from_state_file = false;
  TareCounters tare;
  // Model consistency (issue 27): STATUS_MODEL_MISMATCH and its statistic.
  ModelConsistencyState consistency;
};

class EstimatorPipeline {
 public:
  explicit EstimatorPipeline(const EstimatorConfig& config);
  ~EstimatorPipeline();
  EstimatorPipeline(const EstimatorPipeline&) = delete;
  EstimatorPipeline& operator=(const EstimatorPipeline&) = delete;

  // Book-keeping for packets seen by the transport layer.
  void CountReceived(InputChannel channel);
  void CountDecodeError(InputChannel channel);
  void CountOverloadDrop(InputChannel channel);

  void OnMotor(const MotorSample& sample);
  void OnImu(const ImuSample& sample);
  void OnPose(const PoseSample& sample);
  // Returns true and fills *estimate when a FORCE message must be published
  // (one per accepted strain sample; never NaN: invalid estimates carry
  // status without kStatusValid and the last finite values).
  bool OnStrain(const StrainSample& sample, ForceEstimate* estimate);

  const PipelineHealth& health() const { return health_; }
  // Replaces the gauge offsets in use (e.g. from the persisted state file);
  // the scale stays the parameter file's. A later tare replaces them again.
  // A learned strain scale or tip mass in calibration is where this run's
  // learning starts (and what the method flies from the first sample) when
  // this run learns it; with its learning off it is ignored (the file's).
  void SetGaugeOffsets(const GaugeCalibration& calibration);
  // Clears the per-period fields (rates, NIS) after a status message.
  void TakePeriod();
  const char* method_name() const { return EstimationMethodName(method_kind_); }
  EstimationMethod method() const { return method_kind_; }
  const EstimatorConfig& config() const { return config_; }

 private:
  // Admits a sample with valid readings (counted in health_); true if accepted.
  bool Admit(InputChannel channel, int64_t utime, int32_t seq, Admission* admission);
  // Re-initialises the method and re-feeds the newest motor command (without
  // its telemetry) if it is still current at utime.
  void ResetMethod(ResetReason reason, int64_t utime);
  // Gives the method a new calibration offset (file, tare, state file, or
  // what it learned before a reset) and reports it.
  void UseGaugeOffsets(const double offset_rad[kBirotorRotors], const double offset_std_rad[kBirotorRotors],
                       GaugeOffsetSource source);
  // The offset-departure test starts from a tare: its offsets, their sigma
  // widened by the tip mass's prior share of the rest reading.
  void AnchorOffsetsAtTare();
  // health_.gauge = calibration_ + what the method learned (scaled to the raw reading).
  void UpdateReportedGaugeOffsets(const StrainStepInfo& info);
  // Resets before the method sees the strain sample (start, backwards jump,
  // gap); true when the strain interval makes the input stale.
  bool CheckStrainTiming(const StrainSample& sample, int64_t previous_utime, bool backwards_jump);
  // The strain sample as the method gets it: calibrated, notch-filtered.
  StrainSample Condition(const StrainSample& sample, int64_t previous_utime, bool backwards_jump);
  // A finite estimate in place of a non-finite one (the method is reset;
  // InputStatusFacts::non_finite_replaced says so).
  void ReplaceNonFinite(const StrainSample& sample, ForceEstimate* estimate);
  // The input facts: no motor input, stale, conflict, reset.
  void FillInputFacts(const StrainSample& sample, bool stale, InputStatusFacts* facts);
  // The published estimate: its sigmas (PublishedForceStd) and status
  // (ComposeForceStatus) from the facts; the health counters.
  void Publish(const ForceStatusFacts& facts, ForceEstimate* estimate);
  // The tip mass the arm-mode test learned, to the method when it moved.
  void HandOverTipMass();
  // With learned strain scales: which change the scales and the arm mode
  // point at (estimator/strain_scale_attribution.h).
  ScaleAttribution AttributeLearnedScales() const;
  // The attribution's share that leaves the tip mass the file's, and its
  // MODEL_MISMATCH (ModelConsistencyMonitor::AddScaleAttribution).
  void JudgeLearnedScales(int64_t utime);
  // An earlier run's tip mass and sigma (the state file) into the arm-mode
  // test's learning and the method, when this run learns the tip mass.
  void ResumeTipMass(double tip_mass_kg, double std_kg);
  // Counts the reports of the method call just made (reports_).
  void CountReports();
  void Count(const FusionReport& report);

  EstimatorConfig config_;
  BirotorParams model_;  // the birotor model's parameters of config_.vehicle (BirotorModelOf)
  EstimationMethod method_kind_ = EstimationMethod::kEkf;
  std::unique_ptr<ForceEstimator> method_;
  InputAdmission admission_;
  GaugeCalibration calibration_;  // applied to every strain reading: b = (b_meas - o) / s
  PipelineHealth health_;
  GaugeTare tare_;
  MotorSpeedTracker rotor_speed_;  // for the harmonic notches
  HarmonicNotch notch_;
  FusionReports reports_;  // of the newest method call
  // The model's arm mode over m_p (empty: the tip mass is not learned).
  ArmModeTipMassMap tip_mass_map_;
  // learn_strain_scale with the tip mass learned: the mode tells the
  // learned scales' stiffness from a gauge's scale or a payload.
  bool attributes_scales_ = false;
  ScaleAttributionOptions scale_attribution_options_;  // its priors and limits (ScaleAttributionOptionsOf)
  double tip_mass_file_share_ = 0.0;                   // weight of a stiffness or a common scale [1]
  int64_t scales_judged_utime_ = -1;                   // JudgeLearnedScales' newest judgement [us]; -1 none
  static constexpr int64_t kScaleJudgementIntervalUs = 20000;
  ModelConsistencyMonitor consistency_;  // judges every fusion report (docs/mismatch.md)

  bool started_ = false;             // a strain sample has been accepted
  bool reset_flag_pending_ = false;  // InputStatusFacts::filter_reset on the next estimate
  bool has_motor_ = false;           // a MOTOR sample has been accepted
  MotorSample last_motor_;
  int64_t first_motor_utime_ = -1;    // stamp of the first accepted MOTOR sample [us]
  double tip_mass_in_method_kg_ = 0;  // the m_p last handed to the method (0: the file's) [kg]
  bool has_finite_estimate_ = false;
  ForceEstimate last_finite_estimate_;
};

// The NIS gate of each input's measurements for config.method (its
// method's Gate); NaN where the method has none (the baselines, POSE).
double GateOf(const EstimatorConfig& config, InputChannel channel);

}  // namespace birotor
