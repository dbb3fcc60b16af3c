// The status of a force estimate as every filter (the EKF and the linear
// methods) sets it from its own covariance, so that VALID, CONVERGING and
// MEASUREMENT_REJECTED mean the same for each of them. The input bits
// (stale, no motor input, conflict) are the pipeline's.
#pragma once

#include "samples/samples.h"

namespace birotor {

// Stamps *estimate with the strain sample's utime and seq and sets its status
// from force_std_n (already filled): kStatusValid once both stds have been
// below converged_force_std_n since the last initialisation (latched in
// *converged), else kStatusConverging; kStatusMeasurementRejected when the
// strain sample was rejected by its gate. The method adds its own bits
// (faults) afterwards.
void SetFilterStatus(const StrainSample& sample, double converged_force_std_n, bool strain_rejected, bool* converged,
                     ForceEstimate* estimate);

}  // namespace birotor
