// The rotor-force EKF for any described vehicle (N = 2 .. kMaxArms elastic
// arms): each rotor's thrust and its efficiency mu_i against the nominal map
// from the strain gauges, with the motor commands as inputs and motor
// telemetry, gyro and accelerometer as extra measurements. The filter is a
// template on N (fixed-size state, no heap in the per-sample path) behind one
// runtime interface; MakeMultiArmEkf picks N from the description.
// docs/estimator.md, "The EKF for N arms".
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>

#include "estimator/estimator_config.h"
#include "estimator/force_status.h"
#include "estimator/fusion_counters.h"
#include "estimator/fusion_report.h"
#include "estimator/multi_arm_ekf_fusion.h"
#include "estimator/multi_arm_ekf_model.h"
#include "estimator/multi_arm_fault_monitor.h"
#include "estimator/multi_arm_ground.h"
#include "estimator/noise_adaptation.h"
#include "estimator/sample_queue.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"
#include "samples/samples.h"

namespace birotor {

// The runtime interface: the N-arm samples in, MultiArmForceEstimate out.
class MultiArmForceEstimator {
 public:
  virtual ~MultiArmForceEstimator() = default;
  virtual int arm_count() const = 0;
  // Forget everything; the next strain sample initialises.
  virtual void Reset() = 0;
  // Queued until the next strain sample (the birotor EKF's time handling).
  virtual void AddMotor(const MultiArmMotorSample& sample) = 0;
  virtual void AddImu(const ImuSample& sample) = 0;
  // The body's height from POSE, on arrival (not queued): where the ground
  // may still touch it (the EKF's MultiArmGroundContact); ignored by a
  // method without a ground phase.
  virtual void AddPose(const PoseSample& /*sample*/) {}
  // Applies the queued samples stamped up to this one, predicts to its
  // stamp, fuses it and fills *estimate (n_rotors, forces, sigmas, mu_i,
  // status and rotor_fault_bits). Never throws; a non-finite state
  // re-initialises from the sample.
  virtual void AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) = 0;
  // The force sigma of rotor i [N] and its fault flag, after the last strain sample.
  virtual double force_std_n(int rotor) const = 0;
  // The facts the newest estimate's status was composed from (the pipeline
  // composes the published status from them and its own input facts).
  virtual const MultiArmFilterFacts& facts() const = 0;
  // What the newest AddStrain fused, in the order it happened (the queued
  // telemetry, gyro and accelerometer, then the strain; FusionReport), for
  // the pipeline's model-consistency monitor; null for a method without
  // innovations (not judged).
  virtual const FusionReports* reports() const { return nullptr; }
  // The NIS gate of a measurement (ESTIMATOR_STATUS shows it per input);
  // NaN for a method without one.
  virtual double Gate(FusionSource /*source*/) const { return std::numeric_limits<double>::quiet_NaN(); }
  // The learned scale on gauge i's noise variance (NoiseAdaptation) [1];
  // 1 for a method that does not learn it.
  virtual double strain_noise_scale(int /*gauge*/) const { return 1.0; }
  // Whether it learns that scale (false: 1 for good).
  virtual bool learns_strain_noise() const { return false; }
  // The ground holds the body now (its contact model; false for a method
  // without a ground phase): the arms' modes are not the free vehicle's.
  virtual bool body_supported() const { return false; }
  // In the air within the may-touch band of the ground (GroundContact::near_ground).
  virtual bool body_near_ground() const { return false; }
  // Every arm's tip mass from now on r times the description's (learned
  // from the arm mode, estimator/tip_mass_learning.h): an online
  // re-parameterisation of the model, no state reset, no allocation.
  // Methods whose model has no m_p ignore it (flies_tip_mass false).
  virtual void SetTipMassScale(double /*ratio*/) {}
  virtual bool flies_tip_mass() const { return false; }
  // Each gauge offset is known to one sigma offset_std_rad[i] (in
  // deflection: the raw sigma over s_i; one per arm) from the next
  // (re-)initialisation on, in place of the description's
  // gauge_offset_std_rad (the offsets of the gauge state file). Methods
  // without offset states ignore it.
  virtual void SetGaugeOffsetPrior(const double* /*offset_std_rad*/) {}
  // The offset e_i the method has learned on top of the calibration it
  // reads gauge i with, and its one sigma [rad, in deflection]; false when
  // it has none (no offset states, not initialised, an arm without a gauge).
  virtual bool LearnedGaugeOffset(int /*arm*/, double* /*offset_rad*/, double* /*std_rad*/) const { return false; }
};

// The filter for N arms. MOTOR and IMU samples wait in a queue until the next
// strain sample; the filter is predicted to each one's stamp in time order
// (the command of a MOTOR sample holds from its stamp on), fuses it, and is
// predicted on to the strain sample, in sub-steps of at most
// max_prediction_step_s. A sample stamped before the filter's time is not
// fused (its command still takes effect). On the ground (the birotor's
// GroundContact, judged from each IMU sample on arrival: MultiArmGroundContact)
// the held body's model predicts and the accelerometer is not fused, as in
// the birotor's EkfForceEstimator. The strain noise is learned online as
// there (NoiseAdaptation on the strain reports, estimator.ekf
// adapt_strain_noise): R_i = scale_i strain_noise_rad^2 from the next strain
// sample on; so is the accelerometer's, a_z and a_x each
// (adapt_accel_noise). Differences from it: no learned slow parameters, a fixed-size
// state of 1 + 5N.
template <int N>
class MultiArmEkf : public MultiArmForceEstimator {
 public:
  using Layout = MultiArmEkfLayout<N>;
  using Model = MultiArmEkfModel<N>;
  using State = typename Model::State;
  using Covariance = typename Model::Covariance;
  using Input = typename Model::Input;
  static constexpr int kQueueCapacity = 128;

  // vehicle.arm_count must be N (MakeMultiArmEkf checks).
  MultiArmEkf(const VehicleDescription& vehicle, const EkfOptions& options);

  int arm_count() const override { return N; }
  void Reset() override;
  void AddMotor(const MultiArmMotorSample& sample) override;
  void AddImu(const ImuSample& sample) override;
  void AddPose(const PoseSample& sample) override { contact_.OnPose(sample.z_m); }
  void AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) override;
  double force_std_n(int rotor) const override { return force_std_n_[static_cast<size_t>(rotor)]; }
  const MultiArmFilterFacts& facts() const override { return facts_; }
  const FusionReports* reports() const override { return &reports_; }
  double Gate(FusionSource source) const override { return EkfGateNis(options_, source); }
  double strain_noise_scale(int gauge) const override { return strain_noise_.scale(gauge); }
  // The learned scales on the accelerometer's variance (NoiseAdaptation):
  // component 0 a_z, 1 a_x [1].
  double accel_noise_scale(int component) const { return accel_noise_.scale(component); }
  bool learns_strain_noise() const override { return strain_noise_.enabled(); }
  bool body_supported() const override { return contact_.supported(); }
  bool body_near_ground() const override { return contact_.near_ground(); }
  void SetTipMassScale(double ratio) override { model_.SetTipMassScale(ratio); }
  bool flies_tip_mass() const override { return true; }
  void SetGaugeOffsetPrior(const double* offset_std_rad) override;
  bool LearnedGaugeOffset(int arm, double* offset_rad, double* std_rad) const override;

  bool initialized() const { return initialized_; }
  const State& state() const { return state_; }
  const Covariance& covariance() const { return covariance_; }
  const Model& model() const { return model_; }
  int64_t utime() const { return last_utime_; }
  bool supported() const { return contact_.supported(); }  // the ground holds the body

 private:
  using Measured = std::array<bool, N>;

  void Initialize(const MultiArmStrainSample& sample);
  // The calibrated strain readings z_i = (raw_i - o_i) / s_i and which are
  // measured (a gauge, a finite reading, the sample's arm count is N).
  void CalibratedStrain(const MultiArmStrainSample& sample, Eigen::Matrix<double, N, 1>* z, Measured* measured) const;
  void PredictTo(int64_t utime);
  void Predict(double dt_s, const Input& input);
  void ApplyQueuedUpTo(int64_t utime);
  void ApplyMotor(const MultiArmMotorSample& sample);
  void ApplyImu(const ImuSample& sample);
  // A masked entry's variance to 0 (FusionReport: consumers leave it out).
  static void LeaveOutUnmeasured(const Measured& measured, FusionReport* report);
  // The strain update with its gate and inflation, at the learned noise R_i;
  // returns its report (a masked arm's variance 0).
  FusionReport FuseStrain(const MultiArmStrainSample& sample);
  // The adaptation learns from the strain report; R_i follows its scales.
  void LearnStrainNoise(const FusionReport& strain);
  // Whether any rotor's fault is flagged now.
  bool AnyRotorFault() const;
  // The masked R of the strain at the learned variances [rad^2].
  Eigen::Matrix<double, N, N> StrainNoise(const Measured& measured) const;
  // Applies the birotor's variance floors and ceilings to P (exactly symmetric:
  // every step writes each pair once);
  // false if the state or covariance is not finite.
  bool ConditionCovariance();
  void UpdateFaults(int64_t utime);
  void FillEstimate(const MultiArmStrainSample& sample, bool gated, MultiArmForceEstimate* estimate);

  VehicleDescription vehicle_;
  EkfOptions options_;
  Model model_;
  State process_noise_psd_;                 // diagonal of Qc; Q = Qc dt
  std::array<double, N> offset_prior_std_;  // sigma of e_i at (re-)initialisation [rad]
  Input hover_input_;                       // command assumed before any MOTOR sample
  State floor_, ceiling_;                   // variance floor and ceiling per state, the birotor's [unit^2]
  MultiArmAccelLinearization<N> accel_linearization_;
  bool accel_linearization_valid_ = false;

  bool initialized_ = false;
  bool converged_ = false;
  int64_t last_utime_ = 0;
  State state_;
  Covariance covariance_;
  GateWithInflation strain_gate_;
  bool has_motor_ = false;
  Input command_;
  SampleQueue<MultiArmMotorSample, kQueueCapacity> motor_queue_;
  SampleQueue<ImuSample, kQueueCapacity> imu_queue_;
  MultiArmFaultMonitor faults_;
  MultiArmGroundContact contact_;  // from the IMU on arrival: selects the held body's model
  // The Schmidt hold on the offsets a redundant vehicle cannot see in flight
  // (estimator/multi_arm_offset_hold.h; inactive for N <= 3 or when off).
  LeadingGainHold<N> offset_hold_;
  // The hold for this fusion: in flight, null on the ground (the held body
  // pins b_i there, every offset is learned).
  const LeadingGainHold<N>* FlightOffsetHold() const {
    return offset_hold_.active && !contact_.supported() ? &offset_hold_ : nullptr;
  }
  // Every offset held (keep = 0; inactive when the offsets are not
  // estimated) for the accelerometer near the ground.
  LeadingGainHold<N> every_offset_hold_;
  // The accelerometer's hold. Near the ground (GroundContact::near_ground,
  // the may-touch band) a_z may carry a support N >= 0 that the widened
  // variance covers but does not centre: a_z reads no offset, and its
  // innovations moved them only through P's correlations, the support
  // taken for an offset pattern (the trirotor hovering at the ground's
  // height: 2-sigma share 0.83-0.96 on rotor 1, seeds 1-10). Elsewhere
  // FlightOffsetHold.
  const LeadingGainHold<N>* AccelerometerOffsetHold() const {
    return every_offset_hold_.active && contact_.near_ground() ? &every_offset_hold_ : FlightOffsetHold();
  }
  // The thrust scales mu_i of the rotors without a gauge, held from every
  // update (keep 0) while the ground may carry part of the weight
  // (GroundContact::may_carry): only the free body's motion shows those
  // rotors, and the support's force and torque then move the IMU and the
  // arms as a thrust change would. Held only where learned when the
  // episode began (sigma below ground_carry_learned_thrust_scale_std): an
  // unlearned one is free to learn, its prior's sigma in its force. Without
  // the hold a 25 % loss on rotor 2 of the trirotor without arm 2's gauge,
  // learned in the 30 ms before the body settled back on the ground, was
  // undone in 0.1 s and the rotor published VALID 3.4 N off.
  TrailingGainHold<N> ground_thrust_scale_hold_;
  bool has_arm_without_gauge_ = false;  // else never a hold: every rotor is read by its gauge
  bool ground_carry_ = false;           // may_carry at the hold's last update
  const TrailingGainHold<N>* GroundThrustScaleHold() {
    if (!has_arm_without_gauge_) return nullptr;
    const bool carry = contact_.may_carry();
    if (carry && !ground_carry_) {  // an episode begins: hold each learned mu_i of a rotor without a gauge
      const double learned_std = options_.ground_carry_learned_thrust_scale_std;
      for (int i = 0; i < N; ++i) {
        const int mu = Layout::ThrustScale(i);
        const bool held =
            !vehicle_.arms[static_cast<size_t>(i)].has_gauge && covariance_(mu, mu) < learned_std * learned_std;
        ground_thrust_scale_hold_.keep(i) = held ? 0.0 : 1.0;
      }
      ground_thrust_scale_hold_.active = ground_thrust_scale_hold_.keep.minCoeff() == 0.0;
    }
    ground_carry_ = carry;
    return carry && ground_thrust_scale_hold_.active ? &ground_thrust_scale_hold_ : nullptr;
  }
  std::array<double, N> force_std_n_{};
  MultiArmFilterFacts facts_;                   // of the newest estimate
  NoiseAdaptation strain_noise_;                // the learned scale on each gauge's variance
  NoiseAdaptation accel_noise_;                 // the learned scales on a_z's and a_x's variances
  std::array<double, N> strain_variance_rad2_;  // R_i = scale_i strain_noise_rad^2 [rad^2]
  FusionReports reports_;                       // of the newest AddStrain
};

// The filter for the description's arm count (2 .. kMaxArms); null outside.
std::unique_ptr<MultiArmForceEstimator> MakeMultiArmEkf(const VehicleDescription& vehicle, const EkfOptions& options);

extern template class MultiArmEkf<2>;
extern template class MultiArmEkf<3>;
extern template class MultiArmEkf<4>;
extern template class MultiArmEkf<5>;
extern template class MultiArmEkf<6>;

}  // namespace birotor
