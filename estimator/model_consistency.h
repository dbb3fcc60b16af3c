// Model-consistency monitor (issue 27): windowed statistics of the filter's
// fusion reports that separate "noise as modelled" from "the vehicle does not
// match its parameter file", a sequential (CUSUM) test on the accelerometer
// for overwhelming evidence within milliseconds, with a decision
// (STATUS_MODEL_MISMATCH) and the parameter most likely wrong. Pure library: no LCM, no logging, no
// allocation per report (docs/mismatch.md).
#pragma once

#include <array>
#include <cstdint>

#include "estimator/arm_mode_monitor.h"
#include "estimator/estimator_config.h"
#include "estimator/force_status.h"
#include "estimator/fusion_report.h"
#include "estimator/offset_departure.h"
#include "estimator/strain_scale_attribution.h"
#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

// The vehicle parameter a mismatch points at (named in ESTIMATOR_STATUS).
enum class MismatchParameter : int {
  kNone = 0,
  // k_i or s_i: the strain-derived forces disagree with the accelerometer's
  // total force AND with the thrust map (the thrust scales mu_i moved away from 1).
  kStiffnessOrGaugeScale = 1,
  // Body mass: the strain-derived forces agree with the thrust map (mu_i near
  // 1) but not with the accelerometer's total force, which divides by the mass.
  kMass = 2,
  // tau_m: the telemetry does not follow the commands as modelled.
  kMotorLag = 3,
  // m_p: the arms' symmetric mode rings at another frequency than the
  // file's (the arm-mode test; the rigid body cannot see a tip-mass error).
  kTipMass = 4,
};
// The thrust map c_T is not named: a c_T error is learned by the thrust
// scales mu_i (accurate forces; THRUST_DEFICIT when the rotors are weaker
// than the map), it is not a mismatch (docs/mismatch.md).
// "", "stiffness_or_gauge_scale", "mass", "motor_lag", "tip_mass".
const char* MismatchParameterName(MismatchParameter parameter);

static_assert(sizeof(ModelConsistencyOptions::nis_ratio_limit) / sizeof(double) == kNumFusionSources,
              "one limit per FusionSource");

// mu_i = 1 on every rotor: the file's thrust map, before any estimate.
inline ArmValues UnitThrustScales() {
  ArmValues unit;
  unit.fill(1.0);
  return unit;
}

// Statistics of one source over one window; per component j of the
// measurement (the birotor's strain b1, b2; an N-arm vehicle's b_1 .. b_N).
struct SourceWindowStats {
  int64_t reports = 0;                    // reports with an innovation (fused or rejected)
  int64_t rejected = 0;                   // of which rejected by the gate
  int64_t count = 0;                      // fused reports with a NIS
  double nis_ratio = 0;                   // mean NIS / m, m the measured components [1]
  double bias[kMaxMeasurementSize] = {};  // mean of y_j / sqrt(S_jj) per component [1]
  double lag1[kMaxMeasurementSize] = {};  // lag-1 autocorrelation of y_j / sqrt(S_jj) (whiteness) [1]
};

struct ModelConsistencyState {
  bool mismatch = false;  // raised (STATUS_MODEL_MISMATCH)
  MismatchParameter parameter = MismatchParameter::kNone;
  // The model is confirmed: confirm_windows consistent windows in a row
  // since start, and no mismatch (THRUST_DEFICIT needs it; VALID with
  // valid_needs_confirmation).
  bool confirmed = false;
  // The decision statistic of the newest window: the largest of
  // nis_ratio / nis_ratio_limit, |bias| / bias_limit and rejected share /
  // rejected_share_limit over the sources (> 1: inconsistent) [1].
  double statistic = 0;
  FusionSource worst_source = FusionSource::kStrain;
  // The fast test (options fast_cusum_*): the larger of the
  // accelerometer's C+ and C- over fast_cusum_limit, now (> 1: raised); and
  // the largest C+ or C- since start-up (the margins of docs/mismatch.md) [1].
  double fast_statistic = 0;
  double fast_cusum_peak = 0;
  // What ESTIMATOR_STATUS and the daemon's warning report: the larger of the
  // window's and the fast test's statistic (> 1: that test says
  // inconsistent) [1]. Right after a fast raise the first window has not
  // closed yet and statistic alone still reads 0.
  // The arm-mode and offset-departure tests' statistics count too (each > 1: beyond its limit).
  double ReportedStatistic() const {
    double s = statistic > fast_statistic ? statistic : fast_statistic;
    s = s > arm_mode.statistic ? s : arm_mode.statistic;
    return s > offsets.statistic ? s : offsets.statistic;
  }
  bool raised_fast = false;                          // the current (or last) mismatch was raised by the fast test
  int64_t raised_utime = -1;                         // when the current (or last) mismatch was raised [us]; -1 never
  int64_t raised_count = 0;                          // mismatches raised since start-up
  int64_t windows = 0;                               // windows completed
  SourceWindowStats last[kNumFusionSources];         // the newest completed window
  ArmValues thrust_scale_mean = UnitThrustScales();  // window mean of mu_i of the estimates [1]
  ArmModeState arm_mode;                             // the arm-mode test (options arm_mode_*)
  OffsetDepartureState offsets;                      // the offset-departure test (options offset_departure_*)
  // With learned strain scales (AddScaleAttribution): they point at a
  // payload, or at no single change; held until they stand for the forces [bool].
  bool scales_unexplained = false;
};

// For the birotor (EstimatorPipeline) and any N-rotor vehicle
// (MultiArmPipeline: rotors N, the arm-mode test on its most readable arm mode,
// Judge on the thrust scales of its estimate). A report's component of variance 0 (not measured) is
// left out of its statistics.
class ModelConsistencyMonitor {
 public:
  // arm_mode: the file's symmetric arm mode (ExpectedArmMode), file_hz 0:
  // no arm-mode test; strain_noise_rad: the gauges' noise per arm; rotors:
  // the thrust scales each estimate has (2 .. kMaxSampleArms); tip_mass: the
  // model's mode over m_p (ArmModeTipMassMap::Of the file; empty: the tip
  // mass is not learned).
  explicit ModelConsistencyMonitor(const ModelConsistencyOptions& options = ModelConsistencyOptions(),
                                   const ArmModeExpectation& arm_mode = ArmModeExpectation(),
                                   double strain_noise_rad = 2e-5, int rotors = kBirotorRotors,
                                   const ArmModeTipMassMap& tip_mass = ArmModeTipMassMap());
  // Every fusion report of the method (no allocation).
  void Add(const FusionReport& report);
  // Every strain sample the method got, for the arm-mode test (see
  // ArmModeMonitor::Add). A method without innovations is not judged.
  void AddStrain(int64_t utime, const double* deflection_rad, bool airborne, bool outlier);
  // The strain scales g_i the method learns and their sigmas: the arm-mode
  // test then allows what they may be (WithLearnedStrainScales).
  void SetLearnedStrainScales(const double g[2], const double g_std[2]) {
    arm_mode_.SetExpected(WithLearnedStrainScales(arm_mode_file_, g, g_std));
  }
  // The method's learned scales on the gauges' noise variances
  // (StrainStepInfo::strain_noise_scale): the arm-mode test weighs the
  // mode's excitation against that noise.
  void SetStrainNoiseScales(const double* scale) { arm_mode_.SetStrainNoiseScales(scale); }
  // The tip mass an earlier run learned, and its sigma (the gauge state
  // file): the arm-mode test's learning starts from it
  // (ArmModeMonitor::ResumeTipMass). False when the tip mass is not learned.
  bool ResumeTipMass(double tip_mass_kg, double std_kg) {
    const bool resumed = arm_mode_.ResumeTipMass(tip_mass_kg, std_kg);
    state_.arm_mode = arm_mode_.state();
    return resumed;
  }
  // The offset-departure test (estimator/offset_departure.h) on gauges whose
  // raw readings move as direction[i] when the vehicle weighs more and whose
  // offsets drift by drift_psd_rad2_s[i]; not run until this is called.
  // force_per_direction_n[i]: the force on rotor i of a payload that moves
  // the readings by one direction [N] (offset_force_std_n of Judge's facts).
  void SetOffsetGauges(const double* direction, const double* drift_psd_rad2_s, const double* force_per_direction_n);
  // A new calibration of the offsets (the file's, a tare, a state file) with
  // one sigma each [rad of the raw reading]: the test starts from it.
  void AnchorOffsets(const double* offset_rad, const double* offset_std_rad);
  // The offsets in use at utime (calibration plus what the method learned);
  // judged in free flight, each gauge's own departure also near_ground
  // (OffsetDepartureTest::Add). Raises MODEL_MISMATCH when they depart:
  // "mass" along the common force, "stiffness_or_gauge_scale" for one gauge.
  void AddOffsets(int64_t utime, const double* offset_rad, bool free_flight, bool near_ground = false);
  // With learned strain scales (estimator/strain_scale_attribution.h), after
  // every strain sample. Their common part most likely a payload (or both
  // gauges alike: the forces are that share off), or no single change
  // explaining them, held for offset_departure_hold_s, raises MODEL_MISMATCH
  // (`mass` / `stiffness_or_gauge_scale`), held until a stiffness, a gauge's
  // scale or a tip mass explains them with scale_attribution_stand_weight;
  // the windows' clearing waits for it. While every change but a payload
  // holds that weight, the forces stand: an offsets' departure (the offsets
  // took the common force before the scales were split from them) neither
  // holds MODEL_MISMATCH nor widens the sigmas.
  void AddScaleAttribution(int64_t utime, const ScaleAttribution& attribution);
  // Every force estimate (its utime, and its thrust scales for the
  // attribution); returns the monitor's facts on it (all false for a method
  // it does not judge): the mismatch raised, the model not yet confirmed
  // (with valid_needs_confirmation: VALID withheld), and the tip mass not
  // yet confirmed by the arm mode with the sigma of its prior that the
  // published force sigma carries meanwhile (with
  // arm_mode_valid_needs_reading: VALID withheld). ComposeForceStatus and
  // PublishedForceStd apply them; the estimate is not changed here.
  ConsistencyStatusFacts Judge(const ForceEstimate& estimate) { return Judge(estimate.utime, estimate.thrust_scale); }
  // The same for an estimate at utime [us] with the monitor's rotors' thrust scales mu_i [1].
  ConsistencyStatusFacts Judge(int64_t utime, const double* thrust_scale);
  // Forgets the window in progress and the fast test's CUSUM (filter
  // re-initialised); the confirmation and a raised mismatch stay (cleared
  // after clear_windows consistent windows).
  void Restart();
  const ModelConsistencyState& state() const { return state_; }
  const ModelConsistencyOptions& options() const { return options_; }

 private:
  struct Accumulator {
    int64_t reports = 0;
    int64_t rejected = 0;
    int64_t count = 0;
    double nis_ratio_sum = 0;
    double z_sum[kMaxMeasurementSize] = {};
    double z2_sum[kMaxMeasurementSize] = {};
    double zz_lag_sum[kMaxMeasurementSize] = {};
    double z_previous[kMaxMeasurementSize] = {};
    int64_t z_count[kMaxMeasurementSize] = {};  // fused reports that measured component j
  };
  // Starts the first window or closes the current one at utime.
  void Advance(int64_t utime);
  void CloseWindow(int64_t utime);
  // An accelerometer report into the fast test's CUSUM; raises at its limit.
  void AddToCusum(const FusionReport& report);
  void Raise(int64_t utime, const double* thrust_scale);
  // The tip mass's sigma in the forces' (not yet confirmed by the arm
  // mode, or learned from it), and VALID.
  void AwaitArmMode(ConsistencyStatusFacts* facts) const;
  // offset_force_std_n from the offsets' departure (offset_departure_in_sigma_above).
  void CarryOffsetDeparture(ConsistencyStatusFacts* facts) const;
  // The parameter named for the worst source, given the thrust scales mu_i.
  MismatchParameter Attribute(const double* thrust_scale) const;

  ModelConsistencyOptions options_;
  int rotors_;
  ArmModeExpectation arm_mode_file_;  // the file's, before any learned scale
  ArmModeMonitor arm_mode_;
  OffsetDepartureTest offsets_;                                 // off (limit 0) until SetOffsetGauges
  std::array<double, kMaxSampleArms> force_per_direction_n_{};  // SetOffsetGauges [N]
  int64_t window_us_ = 0;
  int64_t window_start_utime_ = -1;
  bool judging_ = false;  // a report with an innovation has arrived
  Accumulator acc_[kNumFusionSources];
  double cusum_high_ = 0;                               // C+ of the fast test [1]
  double cusum_low_ = 0;                                // C- [1]
  ArmValues newest_thrust_scale_ = UnitThrustScales();  // of the newest estimate [1]
  ArmValues thrust_scale_sum_{};
  int64_t estimates_ = 0;
  int64_t scales_suspect_since_ = -1;  // AddScaleAttribution's payload or unexplained began [us]; -1 none
  bool scales_stand_ = false;          // AddScaleAttribution: the forces stand (releases an offsets' departure)
  // The offsets' departure holds MODEL_MISMATCH (no learned scales stand for the forces).
  bool DepartureHolds() const { return offsets_.state().departed && !scales_stand_; }
  int inconsistent_run_ = 0;
  int consistent_run_ = 0;
  ModelConsistencyState state_;
};

}  // namespace birotor
