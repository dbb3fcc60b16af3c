// Common interface of the rotor-force estimation methods (EKF, thesis
// open-loop inversion, nominal motor map), so the daemon, the replay tool and
// the evaluation run any of them through the same code path.
#pragma once

#include "estimator/samples.h"

namespace birotor {

// Outcome of a strain update, for health reporting.
struct StrainUpdateInfo {
  bool fused = false;  // the sample changed the estimate
  bool gated = false;  // rejected by the chi-square innovation gate
  double nis = 0;      // normalised innovation squared (2 dof); NaN if none
  bool reset = false;  // the method re-initialised itself on this sample
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
  // rotor faults are set by the method; the pipeline adds stale/reset bits.
  virtual void AddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainUpdateInfo* info) = 0;
};

}  // namespace birotor
