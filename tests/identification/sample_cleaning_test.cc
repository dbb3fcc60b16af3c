// Tests of identification/sample_cleaning.h: each kind of bad sample is
// dropped and counted once, and a lone stamp from the future does not make
// the samples after it "out of order".
#include "identification/sample_cleaning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace birotor {
namespace {

constexpr int64_t kJumpUs = 100000;  // IdentificationOptions::max_time_jump_s default

std::vector<StrainSample> Strain(const std::vector<int64_t>& utimes) {
  std::vector<StrainSample> samples;
  for (int64_t t : utimes) {
    StrainSample s;
    s.utime = t;
    samples.push_back(s);
  }
  return samples;
}

std::vector<int64_t> Utimes(const std::vector<StrainSample>& samples) {
  std::vector<int64_t> utimes;
  for (const StrainSample& s : samples) utimes.push_back(s.utime);
  return utimes;
}

TEST(SampleCleaningTest, EachBadSampleIsDroppedAndCountedOnce) {
  SensorLog log;
  log.strain = Strain({1000, 2000, 2000, std::numeric_limits<int64_t>::min(), 3000, 2500, int64_t{1} << 53, 4000});
  log.strain[4].deflection_rad[1] = std::nan("");  // 3000 is non-finite
  const SampleCleaningReport report = CleanLog(&log, kJumpUs);
  EXPECT_EQ(Utimes(log.strain), (std::vector<int64_t>{1000, 2000, 2500, 4000}));
  EXPECT_EQ(report.strain.duplicate, 1);
  EXPECT_EQ(report.strain.bad_stamp, 2);
  EXPECT_EQ(report.strain.non_finite, 1);
  EXPECT_EQ(report.strain.out_of_order, 0);
  EXPECT_EQ(report.total(), 4);
}

TEST(SampleCleaningTest, LoneFutureStampIsDroppedAndTheStreamGoesOn) {
  SensorLog log;
  log.strain = Strain({1000, 2000, 402000, 3000, 4000, 5000});
  const SampleCleaningReport report = CleanLog(&log, kJumpUs);
  EXPECT_EQ(Utimes(log.strain), (std::vector<int64_t>{1000, 2000, 3000, 4000, 5000}));
  EXPECT_EQ(report.strain.bad_stamp, 1);
  EXPECT_EQ(report.strain.out_of_order, 0);
}

TEST(SampleCleaningTest, ConfirmedPauseIsKept) {
  SensorLog log;
  log.strain = Strain({1000, 2000, 902000, 903000, 904000});  // the recording paused 0.9 s
  const SampleCleaningReport report = CleanLog(&log, kJumpUs);
  EXPECT_EQ(log.strain.size(), 5u);
  EXPECT_EQ(report.total(), 0);
}

TEST(SampleCleaningTest, FirstSampleFromTheFutureDoesNotHideTheLog) {
  SensorLog log;
  log.strain = Strain({9000000000, 1000, 2000, 3000});
  const SampleCleaningReport report = CleanLog(&log, kJumpUs);
  EXPECT_EQ(Utimes(log.strain), (std::vector<int64_t>{1000, 2000, 3000}));
  EXPECT_EQ(report.strain.bad_stamp, 1);
}

TEST(SampleCleaningTest, DuplicatedFirstSampleIsADuplicateNotABadStamp) {
  SensorLog log;
  log.strain = Strain({1000, 1000, 2000, 2000, 3000});
  const SampleCleaningReport report = CleanLog(&log, kJumpUs);
  EXPECT_EQ(Utimes(log.strain), (std::vector<int64_t>{1000, 2000, 3000}));
  EXPECT_EQ(report.strain.duplicate, 2);
  EXPECT_EQ(report.strain.bad_stamp, 0);
}

TEST(SampleCleaningTest, MissingTelemetryIsNotBadButInfiniteIs) {
  SensorLog log;
  log.motor.resize(3);
  log.motor[0].utime = 1000;
  log.motor[1].utime = 3000;
  log.motor[2].utime = 5000;
  log.motor[0].omega_meas_rad_s[0] = std::nan("");  // no ESC reading: kept
  log.motor[1].omega_meas_rad_s[1] = std::numeric_limits<double>::infinity();
  const SampleCleaningReport report = CleanLog(&log, kJumpUs);
  EXPECT_EQ(log.motor.size(), 2u);
  EXPECT_EQ(report.motor.non_finite, 1);
}

}  // namespace
}  // namespace birotor
