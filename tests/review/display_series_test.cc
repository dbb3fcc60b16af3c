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
  const DisplayChart chart = MakeChart("c", "t", "y", {{&table, 0, -1, 0, 0, "value", "", false, -1}}, 10.0);
  EXPECT_EQ(chart.samples, 10000);
  EXPECT_EQ(chart.rows, 2 * kMaxDisplayBuckets);  // 1500 buckets of 6.7 ms, two rows each
  EXPECT_NE(chart.rows_json.find(",5]"), std::string::npos) << "the 5.0 spike is a bucket maximum";
  ASSERT_EQ(chart.labels.size(), 2u);
}

TEST(DisplaySeriesTest, BandIsMeanPlusMinusSigma) {
  const Table table = SpikeTable();
  const DisplayChart chart = MakeChart("c", "t", "y", {{&table, 0, 1, 0, 0, "value", "", false, -1}}, 10.0);
  EXPECT_TRUE(chart.bands);
  // A quiet bucket: [1 - 0.1, 1, 1 + 0.1].
  EXPECT_NE(chart.rows_json.find("[0.9,1,1.1]"), std::string::npos);
}

TEST(DisplaySeriesTest, LaneShowsABitSetInOneSample) {
  const Table table = SpikeTable();
  const DisplayChart chart = MakeChart("c", "t", "", {{&table, 2, -1, 4, 3.0, "bit 4", "", false, -1}}, 10.0);
  EXPECT_TRUE(chart.lanes);
  // Lane 3: 3 when clear, 3.8 in the bucket holding the one sample with the bit.
  EXPECT_NE(chart.rows_json.find(",3.8]"), std::string::npos);
  int64_t rises = 0;
  const std::vector<double> at = BitRises(table, 2, 4, 5, &rises);
  EXPECT_EQ(rises, 1);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_NEAR(at[0], 7.0, 1e-9);
}

// Issue 37: one FORCE with a NaN or infinite sigma (or value) must not reach
// the page's JSON as nan/inf (which stops its script and blanks every chart).
TEST(DisplaySeriesTest, NanAndInfinityAreGapsNotJson) {
  Table table({"value", "sigma"});
  for (int i = 0; i < 100; ++i) {
    const double sigma = i == 10 ? INFINITY : i == 11 ? NAN : 0.1;
    table.Add(0.01 * i + 0.005, {i == 50 ? NAN : i == 51 ? -INFINITY : 1.0, sigma});
  }
  const DisplayChart chart = MakeChart("c", "t", "y", {{&table, 0, 1, 0, 0, "value", "", false, -1}}, 1.0);
  EXPECT_EQ(chart.rows, 200);  // 100 buckets (one sample each), two rows
  EXPECT_EQ(chart.rows_json.find("inf"), std::string::npos) << chart.rows_json.substr(0, 400);
  EXPECT_EQ(chart.rows_json.find("nan"), std::string::npos);
  // Rows 10 and 11: the value without its band; rows 50 and 51: a gap.
  EXPECT_NE(chart.rows_json.find("[0.1,[1,1,1]]"), std::string::npos);
  EXPECT_NE(chart.rows_json.find("[0.5,\"NaN\"]"), std::string::npos);
  EXPECT_NE(chart.rows_json.find("[0.51,\"NaN\"]"), std::string::npos);
}

// The y range: the start-up CONVERGING rows (value 70 N, sigma 30 N) do not set
// it; the 0.5 and 99.5 % nearest-rank percentiles of the other 990 rows' band
// edges (value 20 + k / 1000 N, k = 10..999, sigma 0), padded by 10 %.
TEST(DisplaySeriesTest, RobustRangeLeavesOutConvergingRowsAndOutliers) {
  Table table({"value", "sigma", "status"});
  for (int k = 0; k < 1000; ++k) {
    const bool converging = k < 10;
    table.Add(1e-3 * k, {converging ? 70.0 : 20.0 + 1e-3 * k, converging ? 30.0 : 0.0, converging ? 2.0 : 1.0});
  }
  SeriesSpec spec{&table, 0, 1, 0, 0.0, "force", "", false, 2};
  DisplayChart chart = MakeChart("c", "t", "y", {spec}, 1.0);
  SetRobustYRange({spec}, &chart);
  ASSERT_TRUE(chart.has_y_range);
  // 2970 values (value, value - 0, value + 0); index ceil(0.005 * 2970) - 1 = 14
  // -> k = 10 + 14 / 3 = 14; index ceil(0.995 * 2970) - 1 = 2955 -> k = 10 + 985 = 995.
  const double low = 20.014, high = 20.995, pad = 0.1 * (high - low);
  EXPECT_NEAR(chart.y_low, low - pad, 1e-9);
  EXPECT_NEAR(chart.y_high, high + pad, 1e-9);
  EXPECT_EQ(chart.outside_y_range, 0);
  // Without the status column the 70 N +- 30 N start sets the top.
  spec.converging_column = -1;
  SetRobustYRange({spec}, &chart);
  EXPECT_GT(chart.y_high, 21.0);
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
