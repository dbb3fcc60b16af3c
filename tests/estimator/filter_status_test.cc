// The filter's own status facts (estimator/filter_status.h): converged
// latched once both force sigmas fell below the threshold, converging
// before, rejected with a gated strain sample, and no input fact (the
// pipeline owns those); composed, VALID / CONVERGING / REJECTED.
#include "estimator/filter_status.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

int32_t Bits(const FilterStatusFacts& filter) {
  ForceStatusFacts facts;
  facts.filter = filter;
  return ComposeForceStatus(facts);
}

TEST(FilterStatusTest, ValidLatchesOnceBothSigmasAreBelowTheThreshold) {
  StrainSample sample;
  sample.utime = 1234;
  sample.seq = 7;
  ForceEstimate estimate;
  estimate.force_std_n[0] = 0.4;
  estimate.force_std_n[1] = 0.6;  // above 0.5
  bool converged = false;
  FilterStatusFacts facts;
  SetFilterFacts(sample, 0.5, /*strain_rejected=*/false, &converged, &estimate, &facts);
  EXPECT_EQ(Bits(facts), kStatusConverging);
  EXPECT_EQ(estimate.utime, 1234);
  EXPECT_EQ(estimate.seq, 7);
  EXPECT_FALSE(converged);
  estimate.force_std_n[1] = 0.49;
  SetFilterFacts(sample, 0.5, false, &converged, &estimate, &facts);
  EXPECT_EQ(Bits(facts), kStatusValid);
  EXPECT_TRUE(converged);
  // Latched: a sigma back above the threshold keeps VALID until re-initialised.
  estimate.force_std_n[0] = 2.0;
  SetFilterFacts(sample, 0.5, /*strain_rejected=*/true, &converged, &estimate, &facts);
  EXPECT_EQ(Bits(facts), kStatusValid | kStatusMeasurementRejected);
}

TEST(FilterStatusTest, SetsNoOtherFact) {
  StrainSample sample;
  ForceEstimate estimate;
  estimate.force_std_n[0] = estimate.force_std_n[1] = 10.0;
  bool converged = false;
  FilterStatusFacts facts;
  facts.rotor_fault[0] = facts.rotor_fault[1] = facts.thrust_deficit = true;
  SetFilterFacts(sample, 0.5, false, &converged, &estimate, &facts);
  EXPECT_EQ(Bits(facts), kStatusConverging);  // overwritten: the method adds its faults after
}

}  // namespace
}  // namespace birotor
