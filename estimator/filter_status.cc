#include "estimator/filter_status.h"

#include <algorithm>

namespace birotor {

void SetFilterStatus(const StrainSample& sample, double converged_force_std_n, bool strain_rejected, bool* converged,
                     ForceEstimate* estimate) {
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  if (std::max(estimate->force_std_n[0], estimate->force_std_n[1]) < converged_force_std_n) *converged = true;
  int32_t status = *converged ? kStatusValid : kStatusConverging;
  if (strain_rejected) status |= kStatusMeasurementRejected;
  estimate->status = status;
}

}  // namespace birotor
