// The model-consistency monitor's step on one estimate as the pipeline takes
// it (estimator/estimator_pipeline.cc), for the monitor's tests: the
// estimate's status read as the method's facts, the monitor's facts, and the
// published status and sigmas composed from them (estimator/force_status.h).
#pragma once

#include "estimator/force_status.h"
#include "estimator/model_consistency.h"

namespace birotor {

// VALID in e->status is read as a converged filter and THRUST_DEFICIT as
// the method's deficit. Returns whether the model is confirmed (true for a
// method the monitor does not judge), as ModelConsistencyState::confirmed.
inline bool JudgeAndCompose(ModelConsistencyMonitor* monitor, ForceEstimate* e) {
  ForceStatusFacts facts;
  if (e->status & kStatusValid) facts.filter.convergence = FilterConvergence::kConverged;
  facts.filter.thrust_deficit = (e->status & kStatusThrustDeficit) != 0;
  facts.consistency = monitor->Judge(*e);
  for (int i = 0; i < kBirotorRotors; ++i) e->force_std_n[i] = PublishedForceStd(e->force_std_n[i], facts, i);
  e->status = ComposeForceStatus(facts);
  return !facts.consistency.mismatch && !facts.consistency.model_unconfirmed;
}

}  // namespace birotor
