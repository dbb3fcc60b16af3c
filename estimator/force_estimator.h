// Common interface of the rotor-force estimation methods (EKF, thesis
// open-loop inversion, nominal motor map), so the daemon, the replay tool and
// the evaluation run any of them through the same code path.
#pragma once

#include "estimator/fusion_report.h"
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

// What a strain step did besides its fusion reports.
struct StrainStepInfo {
  // kNumerical when the method re-initialised itself on this sample (the
  // pipeline owns every other reason); kNone otherwise.
  ResetReason reset = ResetReason::kNone;
};

// One estimation method. Samples arrive already validated and in time order
// per channel (EstimatorPipeline does that). No method allocates, throws or
// logs in these calls.
class ForceEstimator {
 public:
  virtual ~ForceEstimator() = default;
  // Short name: one of EstimationMethodNames() (estimator_config.h).
  virtual const char* Name() const = 0;
  // Forget everything (start, long gap, time jump backwards).
  virtual void Reset() = 0;
  virtual void AddMotor(const MotorSample& sample) = 0;
  virtual void AddImu(const ImuSample& /*sample*/) {}
  // Processes one strain sample and writes the estimate for its utime.
  // status bits kStatusValid / kStatusConverging / kStatusMeasurementRejected /
  // rotor faults / thrust deficit are set by the method; the pipeline adds
  // the stale, conflict and reset bits (and withholds VALID with them).
  virtual void AddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) = 0;

  // The gauges' calibration changed (a tare, the persisted state): the
  // deflections given from now on have a zero offset known to one sigma of
  // offset_std_rad [rad, in deflection]. Methods without offset states ignore it.
  virtual void SetGaugeOffsetPrior(const double /*offset_std_rad*/[2]) {}
  // The offset e_i the method has learned on top of the calibration and its
  // one sigma [rad, in deflection]; false when it has no offset states or
  // no estimate yet.
  virtual bool LearnedGaugeOffset(double /*offset_rad*/[2], double /*offset_std_rad*/[2]) const { return false; }
  // Every measurement given to the method ends in exactly one FusionReport
  // (fused, rejected by its gate, or not fused), sent here as it happens
  // (possibly later than the Add call that delivered it). nullptr: none sent.
  void set_fusion_sink(FusionReportSink* sink) { fusion_sink_ = sink; }

 protected:
  void Report(const FusionReport& report) const {
    if (fusion_sink_ != nullptr) fusion_sink_->OnFusion(report);
  }

 private:
  FusionReportSink* fusion_sink_ = nullptr;
};

}  // namespace birotor
