#include "estimator/filter_status.h"

#include <algorithm>

namespace birotor {

void SetFilterFacts(const StrainSample& sample, double converged_force_std_n, bool strain_rejected, bool* converged,
                    ForceEstimate* estimate, FilterStatusFacts* facts) {
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  if (std::max(estimate->force_std_n[0], estimate->force_std_n[1]) < converged_force_std_n) *converged = true;
  *facts = FilterStatusFacts();
  facts->convergence = *converged ? FilterConvergence::kConverged : FilterConvergence::kConverging;
  facts->measurement_rejected = strain_rejected;
}

}  // namespace birotor
