// The filter facts of a force estimate as every filter (the EKF and the
// linear methods) sets them from its own covariance, so that VALID,
// CONVERGING and MEASUREMENT_REJECTED mean the same for each of them
// (estimator/force_status.h composes the bits; the input facts are the
// pipeline's).
#pragma once

#include "estimator/force_status.h"
#include "samples/samples.h"

namespace birotor {

// Stamps *estimate with the strain sample's utime and seq and sets the
// filter facts from force_std_n (already filled): converged once both stds
// have been below converged_force_std_n since the last initialisation
// (latched in *converged), else converging; measurement_rejected when the
// strain sample was rejected by its gate. The method adds its own facts
// (faults) afterwards.
void SetFilterFacts(const StrainSample& sample, double converged_force_std_n, bool strain_rejected, bool* converged,
                    ForceEstimate* estimate, FilterStatusFacts* facts);

}  // namespace birotor
