// The review's display grid: min and max of each bucket survive (a one-sample
// spike is drawn), bands cover mean +- sigma, lanes show a bit set anywhere in
// a bucket, and the counts come from every sample.
#include "review/display_series.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

// 10 000 samples at 1 kHz (10 s) of 1.0 with one spike of 5.0 at t = 4.321 s.
Table SpikeTable() {
  Table table({"value", "sigma", "bits"});
  for (int i = 0; i < 10000; ++i) {
    const double t = 1e-3 * i;
    table.Add(t, {i == 4321 ? 5.0 : 1.0, 0.1, i == 7000 ? 4.0 : 1.0});
  }
  return table;
}

TEST(DisplaySeriesTest, BucketsKeepTheSpikeAndTheCount) {
  const Table table = SpikeTable();
  const DisplayChart chart = MakeChart("c", "t", "y", {{&table, 0, -1, 0, 0, "value"}}, 10.0);
  EXPECT_EQ(chart.samples, 10000);
  EXPECT_EQ(chart.rows, 2 * kMaxDisplayBuckets);  // 1500 buckets of 6.7 ms, two rows each
  EXPECT_NE(chart.rows_json.find(",5]"), std::string::npos) << "the 5.0 spike is a bucket maximum";
  ASSERT_EQ(chart.labels.size(), 2u);
}

TEST(DisplaySeriesTest, BandIsMeanPlusMinusSigma) {
  const Table table = SpikeTable();
  const DisplayChart chart = MakeChart("c", "t", "y", {{&table, 0, 1, 0, 0, "value"}}, 10.0);
  EXPECT_TRUE(chart.bands);
  // A quiet bucket: [1 - 0.1, 1, 1 + 0.1].
  EXPECT_NE(chart.rows_json.find("[0.9,1,1.1]"), std::string::npos);
}

TEST(DisplaySeriesTest, LaneShowsABitSetInOneSample) {
  const Table table = SpikeTable();
  const DisplayChart chart = MakeChart("c", "t", "", {{&table, 2, -1, 4, 3.0, "bit 4"}}, 10.0);
  EXPECT_TRUE(chart.lanes);
  // Lane 3: 3 when clear, 3.8 in the bucket holding the one sample with the bit.
  EXPECT_NE(chart.rows_json.find(",3.8]"), std::string::npos);
  int64_t rises = 0;
  const std::vector<double> at = BitRises(table, 2, 4, 5, &rises);
  EXPECT_EQ(rises, 1);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_NEAR(at[0], 7.0, 1e-9);
}

TEST(DisplaySeriesTest, RatesAndGapsFromEverySample) {
  FlightData data;
  data.duration_s = 10.0;
  for (int i = 0; i < 10000; ++i) {
    if (i < 5000 || i >= 5200) data.input_t_s[0].push_back(1e-3 * i);  // a 201 ms gap at 5 s
  }
  const Table rates = InputRatesAndGaps(data, 10);
  ASSERT_EQ(rates.rows(), 10u);
  EXPECT_NEAR(rates.columns[0][0], 1000.0, 1.0);  // 1 kHz
  EXPECT_NEAR(rates.columns[0][5], 800.0, 1.0);   // 800 samples in [5, 6) s
  EXPECT_NEAR(rates.columns[kReviewRateInputs][5], 201.0, 1e-6);
  EXPECT_TRUE(std::isnan(rates.columns[1][0]));  // no MOTOR in this log
}

}  // namespace
}  // namespace birotor
