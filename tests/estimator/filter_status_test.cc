// The filter's own status bits (estimator/filter_status.h): VALID latched once
// both force sigmas fell below the threshold, CONVERGING before, REJECTED
// with a gated strain sample, and no input bit (the pipeline owns those).
#include "estimator/filter_status.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

TEST(FilterStatusTest, ValidLatchesOnceBothSigmasAreBelowTheThreshold) {
  StrainSample sample;
  sample.utime = 1234;
  sample.seq = 7;
  ForceEstimate estimate;
  estimate.force_std_n[0] = 0.4;
  estimate.force_std_n[1] = 0.6;  // above 0.5
  bool converged = false;
  SetFilterStatus(sample, 0.5, /*strain_rejected=*/false, &converged, &estimate);
  EXPECT_EQ(estimate.status, kStatusConverging);
  EXPECT_EQ(estimate.utime, 1234);
  EXPECT_EQ(estimate.seq, 7);
  EXPECT_FALSE(converged);
  estimate.force_std_n[1] = 0.49;
  SetFilterStatus(sample, 0.5, false, &converged, &estimate);
  EXPECT_EQ(estimate.status, kStatusValid);
  EXPECT_TRUE(converged);
  // Latched: a sigma back above the threshold keeps VALID until re-initialised.
  estimate.force_std_n[0] = 2.0;
  SetFilterStatus(sample, 0.5, /*strain_rejected=*/true, &converged, &estimate);
  EXPECT_EQ(estimate.status, kStatusValid | kStatusMeasurementRejected);
}

TEST(FilterStatusTest, SetsNoInputBit) {
  StrainSample sample;
  ForceEstimate estimate;
  estimate.status = kStatusNoMotorInput | kStatusInputStale | kStatusInputConflict | kStatusFilterReset;
  estimate.force_std_n[0] = estimate.force_std_n[1] = 10.0;
  bool converged = false;
  SetFilterStatus(sample, 0.5, false, &converged, &estimate);
  EXPECT_EQ(estimate.status, kStatusConverging);  // overwritten: the pipeline adds its bits after the method
}

}  // namespace
}  // namespace birotor
