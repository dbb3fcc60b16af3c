// The review page's chart data: columns of a FlightData put on one bucket
// grid per chart for display (min and max of each bucket, so no spike is
// lost, two rows per bucket), and the input rates and gaps per bucket.
// Display only: every count and time the page prints comes from all samples.
#pragma once

#include <string>
#include <vector>

#include "review/flight_data.h"

namespace birotor {

// Most buckets on a chart's time axis: 2 rows each, enough for a full-width
// chart on a 4K screen; a zoom shows the same rows closer.
inline constexpr int kMaxDisplayBuckets = 1500;

// One drawn series: a column of a table; a band adds a one-sigma column
// (drawn as mean +- sigma); a lane draws bit `bit` of the column as a step
// between lane and lane + 0.8 (status bits over time).
struct SeriesSpec {
  const Table* table = nullptr;
  int column = 0;
  int sigma_column = -1;  // >= 0: a band
  int bit = 0;            // != 0: a lane of this bit, at height lane
  double lane = 0.0;
  std::string label;
  std::string color;    // CSS colour; "" leaves it to dygraphs
  bool dashed = false;  // drawn dashed (a truth or a reference beside an estimate)
  // >= 0: a column of the same table with FORCE status bits; rows with
  // CONVERGING set are left out of the chart's y range (not of the drawing).
  int converging_column = -1;
};

struct DisplayChart {
  std::string id;
  std::string title;
  std::string y_label;
  std::vector<std::string> labels;  // "t [s]" then one per series
  bool bands = false;               // dygraph customBars: every value a [low, mid, high] triple
  bool lanes = false;
  std::vector<std::string> colors;  // one per series, or empty
  std::vector<std::string> dashed;  // labels of the dashed series
  // The y axis from RobustYRange; without one, dygraphs fits every value.
  bool has_y_range = false;
  double y_low = 0.0, y_high = 0.0;
  int64_t outside_y_range = 0;  // log samples (after convergence) beyond it
  int64_t samples = 0;          // log samples behind the chart (all series)
  int rows = 0;                 // display rows
  std::string rows_json;        // [[t, v, ...], ...]
};

// The chart of series over [0, duration_s]: buckets = the largest series'
// sample count, at most kMaxDisplayBuckets. Empty series are left out; a
// chart with none has no rows.
DisplayChart MakeChart(const std::string& id, const std::string& title, const std::string& y_label,
                       const std::vector<SeriesSpec>& series, double duration_s);

// The y range that holds the middle kRobustRangeShare of the values (band
// edges value +- sigma included) of series, without the rows a series marks
// CONVERGING: the nearest-rank percentiles (1 - share) / 2 and (1 + share) / 2
// (numerics/percentile.h), widened by kRobustRangePad of the span on each
// side (a flat series: +-kRobustRangeFlatPad of its value, at least that in
// its unit). A start-up sigma of 30 N or a single spike so no longer sets the
// axis; the samples beyond it are counted in chart->outside_y_range. Lanes
// keep their fixed axis. No finite value: no range.
inline constexpr double kRobustRangeShare = 0.99;
inline constexpr double kRobustRangePad = 0.1;
inline constexpr double kRobustRangeFlatPad = 0.05;
void SetRobustYRange(const std::vector<SeriesSpec>& series, DisplayChart* chart);

// Per input of FlightData::input_t_s: messages per second and the longest
// interval between two messages [ms] ending in each of `buckets` buckets.
// Columns: rate of each input, then gap of each input.
Table InputRatesAndGaps(const FlightData& data, int buckets);

// Times of the rises (0 -> 1, or set on the first sample) of `bit` in
// column `column` of table, at most max_rises of them; *total counts all.
std::vector<double> BitRises(const Table& table, int column, int bit, size_t max_rises, int64_t* total);

}  // namespace birotor
