#include "review/display_series.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/percentile.h"
#include "samples/samples.h"

namespace birotor {
namespace {

// One series' extremes in each bucket.
struct Bucketed {
  std::vector<double> low, high;            // min and max of the value (the lane's bit: both the max)
  std::vector<double> band_low, band_high;  // min(value - sigma), max(value + sigma)
  std::vector<char> has;
  std::vector<char> seen;  // rows fell in the bucket (all NaN or infinite when !has: a gap)
};

Bucketed BucketSeries(const SeriesSpec& spec, int buckets, double width_s) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Bucketed b{std::vector<double>(buckets, kInf), std::vector<double>(buckets, -kInf),
             std::vector<double>(buckets, kInf), std::vector<double>(buckets, -kInf),
             std::vector<char>(buckets, 0),      std::vector<char>(buckets, 0)};
  const Table& t = *spec.table;
  const std::vector<double>& values = t.columns[spec.column];
  for (size_t row = 0; row < t.rows(); ++row) {
    const int k = std::clamp(static_cast<int>(t.t_s[row] / width_s), 0, buckets - 1);
    double v = values[row];
    b.seen[k] = 1;
    if (!std::isfinite(v)) continue;  // before the lane's cast: NaN has no bits
    if (spec.bit != 0) v = (static_cast<int64_t>(v) & spec.bit) != 0 ? 1.0 : 0.0;
    b.has[k] = 1;
    b.low[k] = std::min(b.low[k], v);
    b.high[k] = std::max(b.high[k], v);
    if (spec.sigma_column >= 0 && std::isfinite(t.columns[spec.sigma_column][row])) {
      // A NaN or infinite sigma leaves the band out for this sample only.
      const double sigma = t.columns[spec.sigma_column][row];
      b.band_low[k] = std::min(b.band_low[k], v - sigma);
      b.band_high[k] = std::max(b.band_high[k], v + sigma);
    }
  }
  if (spec.bit != 0) {  // a lane: set anywhere in the bucket shows as set
    for (int k = 0; k < buckets; ++k) b.low[k] = b.high[k] = spec.lane + 0.8 * b.high[k];
  }
  return b;
}

// A number for JSON; NaN and infinities (which JSON cannot carry and which
// would stop the page's script) as null, a gap.
void AppendValue(double v, std::string* out) {
  if (!std::isfinite(v)) {
    *out += "null";
    return;
  }
  fmt::format_to(std::back_inserter(*out), "{:.6g}", v);
}

}  // namespace

DisplayChart MakeChart(const std::string& id, const std::string& title, const std::string& y_label,
                       const std::vector<SeriesSpec>& all_series, double duration_s) {
  DisplayChart chart;
  chart.id = id;
  chart.title = title;
  chart.y_label = y_label;
  chart.labels = {"t [s]"};
  std::vector<const SeriesSpec*> series;
  size_t largest = 0;
  for (const SeriesSpec& spec : all_series) {
    if (spec.table == nullptr || spec.table->rows() == 0) continue;
    series.push_back(&spec);
    chart.labels.push_back(spec.label);
    chart.bands = chart.bands || spec.sigma_column >= 0;
    chart.lanes = chart.lanes || spec.bit != 0;
    chart.colors.push_back(spec.color);
    if (spec.dashed) chart.dashed.push_back(spec.label);
    largest = std::max(largest, spec.table->rows());
  }
  // Samples behind the chart: each table once.
  std::vector<const Table*> tables;
  for (const SeriesSpec* spec : series) {
    if (std::find(tables.begin(), tables.end(), spec->table) == tables.end()) tables.push_back(spec->table);
  }
  for (const Table* table : tables) chart.samples += static_cast<int64_t>(table->rows());
  if (series.empty()) return chart;
  if (std::find(chart.colors.begin(), chart.colors.end(), "") != chart.colors.end()) chart.colors.clear();
  chart.bands = chart.bands || chart.lanes;  // a lane is a band filled from its base

  const int buckets = static_cast<int>(std::min<size_t>(largest, kMaxDisplayBuckets));
  const double width_s = std::max(duration_s, 1e-6) * (1.0 + 1e-9) / buckets;
  std::vector<Bucketed> bucketed;
  for (const SeriesSpec* spec : series) bucketed.push_back(BucketSeries(*spec, buckets, width_s));
  std::string& out = chart.rows_json;
  out.reserve(static_cast<size_t>(buckets) * series.size() * 40);
  out += '[';
  for (int k = 0; k < buckets; ++k) {
    bool any = false;
    for (const Bucketed& b : bucketed) any = any || b.seen[k];
    if (!any) continue;
    // Two rows: the bucket's minimum at its start, its maximum at its middle.
    for (int half = 0; half < 2; ++half) {
      if (chart.rows > 0) out += ',';
      out += '[';
      AppendValue((k + 0.5 * half) * width_s, &out);
      for (size_t s = 0; s < series.size(); ++s) {
        const Bucketed& b = bucketed[s];
        out += ',';
        if (!b.has[k]) {
          out += b.seen[k] ? "\"NaN\"" : "null";  // the page's script turns "NaN" into a gap
          continue;
        }
        const double v = half == 0 ? b.low[k] : b.high[k];
        if (!chart.bands) {
          AppendValue(v, &out);
          continue;
        }
        const bool band = series[s]->sigma_column >= 0 && std::isfinite(b.band_low[k]);
        out += '[';
        AppendValue(series[s]->bit != 0 ? series[s]->lane : band ? b.band_low[k] : v, &out);
        out += ',';
        AppendValue(v, &out);
        out += ',';
        AppendValue(band ? b.band_high[k] : v, &out);
        out += ']';
      }
      out += ']';
      ++chart.rows;
    }
  }
  out += ']';
  return chart;
}

namespace {

// The values of spec that set a y range: finite, not CONVERGING; a band's
// edges value +- sigma too.
void AppendRangeValues(const SeriesSpec& spec, std::vector<double>* values) {
  const Table& t = *spec.table;
  for (size_t row = 0; row < t.rows(); ++row) {
    if (spec.converging_column >= 0 &&
        (static_cast<int64_t>(t.columns[spec.converging_column][row]) & kStatusConverging) != 0) {
      continue;
    }
    const double v = t.columns[spec.column][row];
    if (!std::isfinite(v)) continue;
    values->push_back(v);
    if (spec.sigma_column < 0) continue;
    const double sigma = t.columns[spec.sigma_column][row];
    if (!std::isfinite(sigma)) continue;
    values->push_back(v - sigma);
    values->push_back(v + sigma);
  }
}

}  // namespace

void SetRobustYRange(const std::vector<SeriesSpec>& series, DisplayChart* chart) {
  if (chart->lanes) return;
  std::vector<double> values;
  for (const SeriesSpec& spec : series) {
    if (spec.table != nullptr && spec.bit == 0) AppendRangeValues(spec, &values);
  }
  if (values.empty()) return;
  const double low = Percentile(values, 0.5 * (1.0 - kRobustRangeShare));
  const double high = Percentile(values, 0.5 * (1.0 + kRobustRangeShare));
  const double pad =
      high > low ? kRobustRangePad * (high - low) : std::max(kRobustRangeFlatPad * std::abs(low), kRobustRangeFlatPad);
  chart->has_y_range = true;
  chart->y_low = low - pad;
  chart->y_high = high + pad;
  chart->outside_y_range = 0;
  for (const double v : values) chart->outside_y_range += (v < chart->y_low || v > chart->y_high) ? 1 : 0;
}

Table InputRatesAndGaps(const FlightData& data, int buckets) {
  std::vector<std::string> labels;
  for (int i = 0; i < kReviewRateInputs; ++i) labels.push_back(std::string(kReviewInputNames[i]) + " rate [Hz]");
  for (int i = 0; i < kReviewRateInputs; ++i) labels.push_back(std::string(kReviewInputNames[i]) + " gap [ms]");
  Table table(labels);
  const double width_s = std::max(data.duration_s, 1e-6) * (1.0 + 1e-9) / buckets;
  std::vector<std::vector<double>> count(kReviewRateInputs, std::vector<double>(buckets, 0.0));
  std::vector<std::vector<double>> gap(kReviewRateInputs, std::vector<double>(buckets, 0.0));
  for (int i = 0; i < kReviewRateInputs; ++i) {
    const std::vector<double>& t = data.input_t_s[i];
    for (size_t n = 0; n < t.size(); ++n) {
      const int k = std::clamp(static_cast<int>(t[n] / width_s), 0, buckets - 1);
      count[i][k] += 1.0;
      if (n > 0) gap[i][k] = std::max(gap[i][k], 1e3 * (t[n] - t[n - 1]));
    }
  }
  for (int k = 0; k < buckets; ++k) {
    table.t_s.push_back((k + 0.5) * width_s);
    for (int i = 0; i < kReviewRateInputs; ++i) {
      table.columns[i].push_back(data.input_t_s[i].empty() ? NAN : count[i][k] / width_s);
      table.columns[kReviewRateInputs + i].push_back(data.input_t_s[i].empty() ? NAN : gap[i][k]);
    }
  }
  return table;
}

std::vector<double> BitRises(const Table& table, int column, int bit, size_t max_rises, int64_t* total) {
  std::vector<double> rises;
  *total = 0;
  bool was_set = false;
  for (size_t row = 0; row < table.rows(); ++row) {
    const bool set = (static_cast<int64_t>(table.columns[column][row]) & bit) != 0;
    if (set && !was_set) {
      ++*total;
      if (rises.size() < max_rises) rises.push_back(table.t_s[row]);
    }
    was_set = set;
  }
  return rises;
}

}  // namespace birotor
