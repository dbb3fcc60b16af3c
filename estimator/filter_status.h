// The status of a force estimate as every filter (the EKF and the linear
// methods) sets it from its own covariance, so that VALID, CONVERGING,
// MEASUREMENT_REJECTED and NO_MOTOR_INPUT mean the same for each of them.
#pragma once

#include "samples/samples.h"

namespace birotor {

// Stamps *estimate with the strain sample's utime and seq and sets its status
// from force_std_n (already filled): kStatusValid once both stds have been
// below converged_force_std_n since the last initialisation (latched in
// *converged), else kStatusConverging; kStatusMeasurementRejected when the
// strain sample was rejected by its gate; kStatusNoMotorInput before the
// first MOTOR sample. The method adds its own bits (faults) afterwards.
void SetFilterStatus(const StrainSample& sample, double converged_force_std_n, bool strain_rejected, bool has_motor,
                     bool* converged, ForceEstimate* estimate);

}  // namespace birotor
