// The extended Kalman filter that estimates each rotor's thrust and its
// efficiency mu_i against the nominal map from the strain gauges, with the
// motor commands as inputs and motor telemetry and gyro as extra measurements.
// Every measurement is fused at its own time stamp and reported (FusionReport).
#pragma once

#include <cstdint>

#include "estimator/ekf_model.h"
#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/ground_contact.h"
#include "estimator/noise_adaptation.h"
#include "estimator/rotor_fault_monitor.h"
#include "estimator/sample_queue.h"
#include "samples/rotor_count.h"

namespace birotor {

// MOTOR and IMU samples wait in a queue until the next strain sample; the
// filter is then predicted to each one's stamp in time order (the command of
// a MOTOR sample holds from its stamp on), fuses it, and is predicted on to
// the strain sample. A measurement stamped before the filter's time (it
// arrived after a newer strain sample had been processed) cannot be fused at
// its stamp: it is reported kNotFused (its command still takes effect). The
// filter predicts across any strain interval in sub-steps; the pipeline
// re-initialises it after PipelineOptions::reset_gap_s.
class EkfForceEstimator : public ForceEstimator {
 public:
  // Queued samples per input: more than 0.1 s (the default reset gap) of IMU at 1 kHz.
  static constexpr int kQueueCapacity = 128;

  EkfForceEstimator(const BirotorParams& params, const EkfOptions& options);

  const char* Name() const override { return "ekf"; }
  void SetGaugeOffsetPrior(const double offset_std_rad[kBirotorRotors]) override;
  double Gate(FusionSource source) const override;
  // Start the learned slow parameters from these (a state file) at the next
  // (re-)initialisation; only the parameters being learned.
  void SetLearnedParameters(const LearnedVehicleParameters& learned) override;
  // The process model flies this m_p from now on (the state is kept: the
  // thrust scales take the change through the strain innovations).
  void SetTipMassKg(double tip_mass_kg) override { process_.SetTipMassKg(tip_mass_kg); }
  bool flies_tip_mass() const override { return true; }
  // The ground contact's height band (GroundContact::OnPose).
  void AddPose(const PoseSample& sample) override { contact_.OnPose(sample.z_m); }

  bool initialized() const { return initialized_; }
  const EkfState& state() const { return state_; }
  const EkfMatrix& covariance() const { return covariance_; }
  const EkfProcessModel& process_model() const { return process_; }
  const GroundContact& ground_contact() const { return contact_; }
  int64_t utime() const { return last_utime_; }  // time of the state [us]
  // The learned scale on gauge i's variance (NoiseAdaptation) [1].
  double strain_noise_scale(int i) const { return strain_noise_.scale(i); }
  // The learned scale on the accelerometer's variance (NoiseAdaptation) [1].
  double accel_noise_scale() const { return accel_noise_.scale(0); }
  bool learns_strain_noise() const override { return strain_noise_.enabled(); }

 private:
  void DoReset() override;
  void DoAddMotor(const MotorSample& sample) override;
  void DoAddImu(const ImuSample& sample) override;
  void DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) override;
  bool TelemetryUsable(const MotorSample& sample) const;
  void Initialize(const StrainSample& sample);
  // Predicts from the state's time to utime in equal RK4 sub-steps of at
  // most max_prediction_step_s with the held command; nothing if not later.
  void PredictTo(int64_t utime);
  void Predict(double dt_s, const EkfInput& input);
  // Applies the queued MOTOR and IMU samples stamped up to utime, oldest
  // first (MOTOR first on equal stamps).
  void ApplyQueuedUpTo(int64_t utime);
  void ApplyMotor(const MotorSample& sample);
  void ApplyImu(const ImuSample& sample);
  bool AccelerometerUsable(const ImuSample& sample) const;
  // Strain update with its gate and the inflation after persistent rejection,
  // with the learned strain noise; then the noise learns from its report
  // (LearnStrainNoise, estimator/ekf_parameter_learning.cc).
  FusionReport FuseStrain(const StrainSample& sample);
  void LearnStrainNoise(const FusionReport& strain);
  // Which gate policy a fusion runs under (GateWithInflation): none (gated
  // only), the strain's or the gyro's.
  enum class GateInflation { kNone, kStrain, kGyro, kAccelerometer };
  // Every fusion of the filter goes through here (estimator/ekf_fusion.cc,
  // with the fusion of each measurement): FuseMeasurement, or with
  // `inflation` the gate's policy against a persistent change (the strain's:
  // thrust scales opened; the gyro's: the pitch rate's variance widened),
  // in place on the blocks
  // of x and P of the LiveStates (the rest of P is zero: no fusion moves
  // it), with the live states that H does not read updated through their
  // cross covariance (UpdateTrailingStates): the same x and P as the update
  // on all the states, at the cost of what is learned and read (with slow
  // parameters live, JosephForm::kCombined: the same product to round-off).
  template <int M>
  FusionReport Fuse(const MeasurementLinearization<M, kEkfStateSize>& at, const Eigen::Matrix<double, M, M>& noise,
                    const Eigen::Matrix<double, M, 1>& z, const FusionRequest& request,
                    GateInflation inflation = GateInflation::kNone);
  // On the N live states: FuseLive finds the leading K that H reads (the
  // first block boundary, the dynamic states, the offsets, the strain
  // scales or all, past H's last non-zero column; at most N), FuseRead fuses.
  template <int N, int M>
  FusionReport FuseLive(const MeasurementLinearization<M, kEkfStateSize>& at, const Eigen::Matrix<double, M, M>& noise,
                        const Eigen::Matrix<double, M, 1>& z, const FusionRequest& request, GateInflation inflation);
  template <int K, int N, int M>
  FusionReport FuseRead(const MeasurementLinearization<M, kEkfStateSize>& at, const Eigen::Matrix<double, M, M>& noise,
                        const Eigen::Matrix<double, M, 1>& z, const FusionRequest& request, GateInflation inflation);
  template <int N, int M, typename State, typename Cov>
  FusionReport FuseOn(const MeasurementLinearization<M, N>& at, const Eigen::Matrix<double, M, M>& noise,
                      const Eigen::Matrix<double, M, 1>& z, const FusionRequest& request, GateInflation inflation,
                      State* x, Cov* cov);
  // A slow parameter is learned and not frozen: its rows and columns of P
  // may be non-zero. Otherwise they are exactly zero (not learned: zero
  // prior and process noise; frozen: FreezeSlowParameters zeroed them and
  // Predict adds no noise to them).
  bool StrainScalesLive() const { return options_.learn_strain_scale && !scales_frozen_; }
  bool BodyMassLive() const { return options_.learn_body_mass && !mass_frozen_; }
  // The states a fusion on the N live states must not move now (a bit per
  // state; 0 mostly): see EkfOptions::step_hold_s.
  uint32_t HeldStates(int live_states) const;
  // The offsets, held while the body is in the air near the ground
  // (GroundContact::near_ground, the may-touch band): the touches'
  // transients must not move the offsets the held body anchored (they
  // moved them and MODEL_MISMATCH was raised), nor may what the widened
  // a_z lets pass (a payload would go into them).
  uint32_t OffsetsHeldNearGround() const;
  int64_t StepHoldEndUtime() const;  // the state's time plus step_hold_s [us]
  // The strain gate is rejecting a step, or let one in less than step_hold_s ago.
  bool InThrustStep() const;
  // The gyro may take back a lost pitch rate (gyro_liftoff_recovery_s).
  bool GyroMayInflate(int64_t utime) const;
  // The accelerometer's gate may open the strain scales (GateInflation::
  // kAccelerometer): they learn, and no thrust step or rotor fault explains
  // the rejections.
  bool AccelerometerMayInflate() const { return StrainScalesLive() && !InThrustStep() && !faults_.AnyRotorFault(); }
  // Whether slow state p (kStrainScale1, kStrainScale2, kBodyMassScale) is frozen.
  bool SlowStateFrozen(int p) const { return p == kBodyMassScale ? mass_frozen_ : scales_frozen_; }
  // The leading states whose rows and columns of P may be non-zero: up to
  // the offsets (kStrainScale1) while no slow parameter is live, up to the
  // strain scales (kBodyMassScale) while only they learn, else all (the
  // strain scales' rows stay zero while they are frozen and the mass is live).
  int LiveStates() const {
    if (BodyMassLive()) return kEkfStateSize;
    return StrainScalesLive() ? kBodyMassScale : kStrainScale1;
  }
  // P = Phi P Phi^T + Qc dt on the N live states; gamma: the transition's
  // body-mass column (N = 14 in free flight with the mass learned), else
  // null (estimator/ekf_prediction.cc, with Predict).
  template <int N>
  void PropagateCovariance(const DynamicMatrix& phi, const DynamicVector* gamma, double dt_s);
  void ReportNotFused(FusionSource source, int64_t utime) const;
  // The gyro and accelerometer readings of an IMU sample the filter would have used.
  void ReportImuNotFused(const ImuSample& sample) const;
  // Empties both queues, reporting each waiting measurement as not fused.
  void DiscardQueued();
  // Symmetrises P and applies the variance floors and ceilings; false if the
  // state or covariance is not finite (or a variance is negative). On the N
  // live states (the rest of P is zero).
  bool ConditionCovariance();
  template <int N>
  bool ConditionCovariance();
  // The forces, their sigmas and thrust scales (averaged over the body-mass
  // hypotheses, parameter_hypotheses.h), and the filter facts.
  void FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate, FilterStatusFacts* facts);
  // e_i and its sigma into the step result (the pipeline reports them).
  void FillLearnedOffsets(StrainStepInfo* info) const;
  // g_i and m into the step result, and kept for the next (re-)initialisation.
  void FillLearnedParameters(StrainStepInfo* info);
  // The sigma of g_i that is published: the filter's, widened by the part of
  // the reading its offset holds (see the .cc).
  double PublishedStrainScaleStd(int arm) const;
  // The slow parameters are learned in free flight only (airborne, and
  // f1 + f2 above half the weight; the strain scales after a lift-off only
  // once that held for slow_learning_delay_s): on the ground (or a test
  // stand) the accelerometer reads the support, and the rest deflection that
  // the tare was computed from would be learned as a scale. Frozen: their
  // rows and columns of P are zeroed (no gain; the value is kept), no
  // process noise, and their sigma kept; learning again: the sigma comes
  // back, uncorrelated.
  void FreezeSlowParameters(bool scales_frozen, bool mass_frozen);
  void FreezeSlowParameter(int p, bool frozen);
  // P(H1 | data): the body mass is not the file's (parameter_hypotheses.h); 0 when not learned.
  double PayloadProbability() const;
  // Decides whether the slow parameters learn now (see FreezeSlowParameters).
  void UpdateLearning();
  // Remembers the offsets and the strain scales' sigma at a start or a lift-off.
  void StartSettling();
  bool SettlingOffsetsMoved() const;
  // At the end of the settling: the offsets and the strain scales from
  // there, uncorrelated (see the .cc).
  void SplitScaleAndOffsetAgain();

  BirotorParams params_;
  EkfOptions options_;
  EkfProcessModel process_;
  StrainMeasurementModel strain_model_;
  MotorSpeedMeasurementModel motor_model_;
  GyroMeasurementModel gyro_model_;
  AccelerometerMeasurementModel accel_model_;
  AccelerometerLinearization accel_linearization_;  // from the newest prediction step
  GroundContact contact_;                           // from the IMU: selects the supported-body model
  int64_t contact_released_utime_ = -1;             // the newest lift-off (contact let go) [us]; -1 none
  EkfState process_noise_psd_;                      // diagonal of Qc; Q = Qc dt
  double offset_prior_std_rad_[kBirotorRotors];     // sigma of e_i at (re-)initialisation [rad]
  EkfInput hover_input_;                            // command assumed before any MOTOR sample
  double variance_floor_[kEkfStateSize];            // kVarianceFloor, 0 for slow states not learned
  // The slow parameters (g_i, r_m) at the newest sample, or their start
  // values: where a (re-)initialisation starts them (indexed by state).
  struct {
    double value[kEkfStateSize] = {};
    double std[kEkfStateSize] = {};
    double published_strain_scale_std[2] = {};  // PublishedStrainScaleStd while learning
  } learned_;
  bool scales_frozen_ = false;                 // the strain scales are frozen (not flying, or lifting off)
  bool mass_frozen_ = false;                   // the body mass is frozen (not flying)
  int64_t step_hold_until_utime_ = 0;          // held after a thrust step up to here (HeldStates) [us]
  int64_t liftoff_hold_until_utime_ = 0;       // held after a lift-off up to here [us]
  double slow_noise_psd_[kEkfStateSize] = {};  // Qc of the slow states while learned (0 while frozen)
  // Start of the current free flight [us], or one of these.
  static constexpr int64_t kNotFlying = -1, kFlyingSinceStart = -2;
  int64_t flying_since_utime_ = kFlyingSinceStart;
  // The rotors have carried the vehicle since it last touched (UpdateLearning):
  // a thrust deficit in the air (a rotor loss) is then no landing.
  bool carried_in_flight_ = false;
  // The settling of the fast states after a start or a lift-off, at whose
  // end the strain scales and offsets are split again (SplitScaleAndOffsetAgain).
  struct {
    bool pending = false;
    int64_t until_utime = 0;
    double offset_rad[kBirotorRotors] = {0, 0};            // e_i at the start of the settling
    double offset_variance_rad2[kBirotorRotors] = {0, 0};  // and its variance
    // settling_offset_limit_sigma x its sigma then: VALID waits beyond it [rad]
    double offset_limit_rad[kBirotorRotors] = {0, 0};
    double scale_variance[kBirotorRotors] = {0, 0};  // var(g_i) to learn from after it
  } settling_;

  bool initialized_ = false;
  bool converged_ = false;
  int64_t last_utime_ = 0;  // time of state_ [us]
  EkfState state_;
  EkfMatrix covariance_;
  GateWithInflation strain_gate_;      // strain gate and its inflation policy
  GateWithInflation gyro_gate_;        // gyro gate; a lost pitch rate is inflated by its initial variance
  GateWithInflation accel_gate_;       // accelerometer gate while strain scales learn; the scales open up
  NoiseAdaptation strain_noise_;       // the learned scale on each gauge's variance
  NoiseAdaptation accel_noise_;        // the learned scale on the accelerometer's variance
  Eigen::Matrix2d strain_noise_rad2_;  // R of the strain: diag(scale_i strain_noise_rad^2) [rad^2]

  bool has_motor_ = false;
  EkfInput command_;  // held from the newest applied MOTOR sample's stamp
  SampleQueue<MotorSample, kQueueCapacity> motor_queue_;
  SampleQueue<ImuSample, kQueueCapacity> imu_queue_;

  RotorFaultMonitor faults_;  // rotor faults and the shared thrust deficit, from mu and P
};

}  // namespace birotor
