// Common interface of the rotor-force estimation methods (EKF, thesis
// open-loop inversion, nominal motor map), so the daemon, the replay tool and
// the evaluation run any of them through the same code path.
#pragma once

#include <limits>

#include "estimator/force_status.h"
#include "estimator/fusion_report.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"

namespace birotor {

// Why a method was re-initialised (ESTIMATOR_STATUS last_reset_reason).
enum class ResetReason : int {
  kNone = 0,
  kStart,          // the first strain sample
  kGap,            // strain interval longer than PipelineOptions::reset_gap_s
  kTimeBackwards,  // strain stamp jumped back more than time_backwards_reset_s
  kNumerical,      // the method's state or covariance stopped being finite or positive
};
// "", "start", "gap", "time_backwards", "numerical" (string literals).
const char* ResetReasonName(ResetReason reason);

// What a strain step did besides its fusion reports and the estimate.
struct StrainStepInfo {
  // kNumerical when the method re-initialised itself on this sample (the
  // pipeline owns every other reason); kNone otherwise.
  ResetReason reset = ResetReason::kNone;
  // The method's ground contact: the body is held or supported (its arm
  // modes are then the contact's). Methods without one report false.
  bool body_supported = false;
  // The offset e_i the method has learned on top of the calibration it was
  // given, and its one sigma [rad, in deflection]; valid only when
  // has_learned_gauge_offset (methods with offset states, once initialised).
  bool has_learned_gauge_offset = false;
  double learned_gauge_offset_rad[2] = {0, 0};
  double learned_gauge_offset_std_rad[2] = {0, 0};
  // The slow vehicle parameters the method learns (issue 27): the strain
  // scale g_i per arm (the calibrated gauge reads g_i b_i + e_i) [1] and the
  // body mass [kg], with their one sigma; valid only when has_learned_*.
  bool has_learned_strain_scale = false;
  double learned_strain_scale[2] = {1, 1};
  double learned_strain_scale_std[2] = {0, 0};
  bool has_learned_body_mass = false;
  double learned_body_mass_kg = 0;
  double learned_body_mass_std_kg = 0;
  // The scale on each gauge's noise variance the method has learned (EKF
  // adapt_strain_noise, estimator/noise_adaptation.h): its strain R_i
  // is scale_i strain_noise_rad^2 [1]; 1 for methods that learn none.
  double strain_noise_scale[2] = {1, 1};
  // The method's status facts (converged, measurement rejected, rotor
  // faults, thrust deficit); ComposeForceStatus makes the bits.
  // (Last: the struct then resets field by field, without a zeroed copy.)
  FilterStatusFacts filter;
};

// Slow vehicle parameters to start learning from (a state file of an earlier run).
struct LearnedVehicleParameters {
  bool has_strain_scale = false;  // the fields below hold values to start from
  bool has_body_mass = false;
  double strain_scale[kBirotorRotors] = {1, 1};      // g_i [1]
  double strain_scale_std[kBirotorRotors] = {0, 0};  // [1]
  double body_mass_kg = 0;                           // [kg]
  double body_mass_std_kg = 0;                       // [kg]
};

// One estimation method. Samples arrive already validated and in time order
// per channel (EstimatorPipeline does that). No method allocates, throws or
// logs in these calls. Every measurement given to a method ends in exactly
// one FusionReport (fused, rejected by its gate, or not fused), appended to
// the `reports` of the call in which it happened (possibly a later call than
// the one that delivered it: the EKF fuses a MOTOR sample at the next strain
// sample). reports may be nullptr: none kept.
class ForceEstimator {
 public:
  virtual ~ForceEstimator() = default;
  // Short name: one of EstimationMethodNames() (estimation_method.h).
  virtual const char* Name() const = 0;

  // Forget everything (start, long gap, time jump backwards).
  void Reset(FusionReports* reports) {
    Call(reports, [&] { DoReset(); });
  }
  void AddMotor(const MotorSample& sample, FusionReports* reports) {
    Call(reports, [&] { DoAddMotor(sample); });
  }
  void AddImu(const ImuSample& sample, FusionReports* reports) {
    Call(reports, [&] { DoAddImu(sample); });
  }
  // Processes one strain sample and writes the estimate for its utime and
  // what else the step did (*info).
  // One owner per status fact: the method fills the filter's facts
  // (info->filter: converged, measurement rejected, rotor faults, thrust
  // deficit) and nothing else; the pipeline fills the input facts and the
  // model-consistency facts, the service the transport facts, and
  // ComposeForceStatus (force_status.h) makes the bits of all of them.
  // estimate->status holds the method's facts alone composed (for a method
  // used without the pipeline); the pipeline composes it again with its own.
  void AddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info, FusionReports* reports) {
    Call(reports, [&] { DoAddStrain(sample, estimate, info); });
    estimate->status = ComposeFilterStatus(info->filter);
  }

  // One accepted POSE sample, on arrival (a method that judges the ground's
  // contact takes its height: GroundContact::OnPose); the others ignore it.
  // No report: the pose is not fused.
  virtual void AddPose(const PoseSample& /*sample*/) {}

  // The NIS gate the method applies to a measurement source; NaN where it
  // has none (it does not use the source, or uses it without a gate).
  virtual double Gate(FusionSource /*source*/) const { return std::numeric_limits<double>::quiet_NaN(); }
  // The gauges' calibration changed (a tare, the persisted state): the
  // deflections given from now on have a zero offset known to one sigma of
  // offset_std_rad [rad, in deflection]. Methods without offset states ignore
  // it; the others say what they learn on top of it in StrainStepInfo.
  virtual void SetGaugeOffsetPrior(const double /*offset_std_rad*/[2]) {}
  // Methods that learn slow vehicle parameters start from these at their
  // next (re-)initialisation; the others ignore them.
  virtual void SetLearnedParameters(const LearnedVehicleParameters& /*learned*/) {}
  // The tip mass m_p [kg] of every arm from now on (learned from the arm
  // mode, estimator/tip_mass_learning.h): an online re-parameterisation of
  // the method's model, no state is reset. Methods whose model has no
  // m_p ignore it. No allocation.
  virtual void SetTipMassKg(double /*tip_mass_kg*/) {}
  // Whether SetTipMassKg moves the method's forces (its model has m_p): a
  // learned tip mass is only learned for a method that flies it; the others
  // keep the file's m_p and its prior in their sigma (docs/mismatch.md).
  virtual bool flies_tip_mass() const { return false; }
  // Whether the method learns its gauges' noise (StrainStepInfo::
  // strain_noise_scale; EKF adapt_strain_noise); false: it weighs them with
  // the file's strain_noise_rad, or weighs no noise at all.
  virtual bool learns_strain_noise() const { return false; }

 protected:
  // A report of the call in progress.
  void Report(const FusionReport& report) const {
    if (reports_ != nullptr) reports_->Add(report);
  }

 private:
  virtual void DoReset() = 0;
  virtual void DoAddMotor(const MotorSample& sample) = 0;
  virtual void DoAddImu(const ImuSample& /*sample*/) {}
  virtual void DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) = 0;
  template <typename F>
  void Call(FusionReports* reports, F&& body) {
    reports_ = reports;
    body();
    reports_ = nullptr;
  }

  FusionReports* reports_ = nullptr;  // of the call in progress only
};

}  // namespace birotor
