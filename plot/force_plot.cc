// gnuplot script of the force plot; drawn by plot/gnuplot_driver.
#include "plot/force_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include "plot/gnuplot_driver.h"
#include "plot/status_words.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kRotorColor[kBirotorRotors] = {"#d62728", "#1f77b4"};
constexpr const char* kSigmaColor[kBirotorRotors] = {"#67000d", "#08306b"};  // darker rotor colours
constexpr const char* kTrueColor = "#303030";
// An extreme further than this many bulk spans from the bulk is clipped [1].
constexpr double kOutlierSpans = 0.5;
// FORCE silent for more than this many typical intervals is drawn as a gap [1].
constexpr double kGapPeriods = 10.0;
constexpr const char* kMarkerColor = "#8c2d04";
// Panel edges on the page [fraction of the width and height]; the left and
// right edges are shared so that the time axes line up, and the keys sit to
// the right of the panels, where they never cover data. The left edge is
// LeftEdge's: room for the longest status lane label.
constexpr double kRightEdge = 0.82, kTopEdge = 0.945, kBottomEdge = 0.05;
// Width of one character of the status lane labels (sans at 8 pt, cairo's
// 72 dpi: the widest capitals measure 6.4 px) and the tic's gap to the
// axis [px]; the narrowest left edge (the y-labels of the other panels) [1].
constexpr double kLaneLabelCharPx = 6.6, kLaneLabelGapPx = 14.0, kMinLeftEdge = 0.075;

// One row of the datablock: a FORCE message and its TRUTH pair (NaN if none).
struct Row {
  double t_s;
  const ForceEstimate* estimate;
  const TruthSample* truth;
};

// A panel's y-range from its data: the clip_fraction quantiles at each end
// (the bulk), stretched to the extremes unless they lie more than
// kOutlierSpans bulk spans beyond it, widened by 8 % of the span; what lies
// outside is reported in note.
struct YRange {
  double low = 0, high = 1;
  std::string note;
};

YRange RangeOf(std::vector<std::pair<double, double>> values_and_times, double clip_fraction, double min_span,
               const std::string& unit) {
  YRange range;
  values_and_times.erase(std::remove_if(values_and_times.begin(), values_and_times.end(),
                                        [](const auto& v) { return !std::isfinite(v.first); }),
                         values_and_times.end());
  if (values_and_times.empty()) return range;
  std::vector<double> values;
  values.reserve(values_and_times.size());
  for (const auto& v : values_and_times) values.push_back(v.first);
  const size_t n = values.size();
  const size_t low_index = static_cast<size_t>(clip_fraction * static_cast<double>(n - 1));
  const size_t high_index = n - 1 - low_index;
  std::nth_element(values.begin(), values.begin() + low_index, values.end());
  const double low_quantile = values[low_index];
  std::nth_element(values.begin(), values.begin() + high_index, values.end());
  const double high_quantile = values[high_index];
  const double span = std::max(high_quantile - low_quantile, min_span);
  const double middle = 0.5 * (high_quantile + low_quantile);
  const double bulk_low = std::min(low_quantile, middle - 0.5 * span);
  const double bulk_high = std::max(high_quantile, middle + 0.5 * span);
  // The first extreme in time (values_and_times is in time order).
  const auto by_value = [](const auto& a, const auto& b) { return a.first < b.first; };
  const auto min_it = std::min_element(values_and_times.begin(), values_and_times.end(), by_value);
  const auto max_it = std::max_element(values_and_times.begin(), values_and_times.end(), by_value);
  // An extreme within kOutlierSpans of the bulk stays in view; a further one
  // (a transient) is clipped and noted.
  range.low = (min_it->first >= bulk_low - kOutlierSpans * span ? min_it->first : bulk_low) - 0.08 * span;
  range.high = (max_it->first <= bulk_high + kOutlierSpans * span ? max_it->first : bulk_high) + 0.08 * span;
  std::vector<std::string> clipped;
  if (max_it->first > range.high) {
    clipped.push_back(fmt::format("peak {:.2f}{} at {:.3f} s", max_it->first, unit, max_it->second));
  }
  if (min_it->first < range.low) {
    clipped.push_back(fmt::format("low {:.2f}{} at {:.3f} s", min_it->first, unit, min_it->second));
  }
  if (!clipped.empty()) {
    range.note = "clipped to the bulk of the data: " + clipped[0] + (clipped.size() > 1 ? ", " + clipped[1] : "");
  }
  return range;
}

std::string Number(double value) { return std::isfinite(value) ? fmt::format("{:.7g}", value) : "NaN"; }

// $data: t f1 f2 std1 std2 mu1 mu2 status f1_true f2_true mu1_true mu2_true err1
// err2. A blank line before a row that follows a gap of more than kGapPeriods
// typical intervals breaks every line there: no FORCE, no line.
double GapS(const std::vector<Row>& rows) {
  std::vector<double> steps_s;
  steps_s.reserve(rows.size());
  for (size_t k = 1; k < rows.size(); ++k) steps_s.push_back(rows[k].t_s - rows[k - 1].t_s);
  if (steps_s.empty()) return std::numeric_limits<double>::infinity();
  std::nth_element(steps_s.begin(), steps_s.begin() + steps_s.size() / 2, steps_s.end());
  return kGapPeriods * steps_s[steps_s.size() / 2];
}

std::string DataBlock(const std::vector<Row>& rows, double gap_s) {
  std::string block = "$data << EOD\n";
  block.reserve(rows.size() * 120);
  for (size_t k = 0; k < rows.size(); ++k) {
    const Row& row = rows[k];
    if (k > 0 && row.t_s - rows[k - 1].t_s > gap_s) block += '\n';
    const ForceEstimate& e = *row.estimate;
    const TruthSample* t = row.truth;
    fmt::format_to(std::back_inserter(block), "{:.6f} {} {} {} {} {} {} {} {} {} {} {} {} {}\n", row.t_s,
                   Number(e.force_n[0]), Number(e.force_n[1]), Number(e.force_std_n[0]), Number(e.force_std_n[1]),
                   Number(e.thrust_scale[0]), Number(e.thrust_scale[1]), e.status, Number(t ? t->force_n[0] : kNaN),
                   Number(t ? t->force_n[1] : kNaN), Number(t ? t->thrust_scale[0] : kNaN),
                   Number(t ? t->thrust_scale[1] : kNaN), Number(t ? e.force_n[0] - t->force_n[0] : kNaN),
                   Number(t ? e.force_n[1] - t->force_n[1] : kNaN));
  }
  return block + "EOD\n";
}

// The first rise of every marked status bit after the first message, with the
// number of rises: "ROTOR2_FAULT 10.037 s" or "RESET 5.000 s (3x)".
std::vector<std::pair<double, std::string>> StatusMarkers(const std::vector<Row>& rows) {
  std::vector<std::pair<double, std::string>> markers;
  for (int i = 0; i < kStatusBitCount; ++i) {
    const StatusBitName& name = kStatusBitNames[i];
    if (!(name.bit & kAlarmStatusBits)) continue;
    double first_s = kNaN;
    int rises = 0;
    for (size_t k = 1; k < rows.size(); ++k) {
      if ((rows[k].estimate->status & name.bit) && !(rows[k - 1].estimate->status & name.bit)) {
        if (rises++ == 0) first_s = rows[k].t_s;
      }
    }
    if (rises == 0) continue;
    markers.emplace_back(first_s, fmt::format("{} {:.3f} s{}", name.word, first_s,
                                              rises > 1 ? fmt::format(" ({}x)", rises) : std::string()));
  }
  return markers;
}

// The first silence of FORCE longer than gap_s, with the number of such
// silences: "no FORCE for 151 ms from 5.999 s (2x)".
void AddGapMarker(const std::vector<Row>& rows, double gap_s, std::vector<std::pair<double, std::string>>* markers) {
  int gaps = 0;
  size_t first = 0;
  for (size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].t_s - rows[k - 1].t_s > gap_s && gaps++ == 0) first = k;
  }
  if (gaps == 0) return;
  const double from_s = rows[first - 1].t_s;
  markers->emplace_back(from_s, fmt::format("no FORCE for {:.0f} ms from {:.3f} s{}", (rows[first].t_s - from_s) * 1e3,
                                            from_s, gaps > 1 ? fmt::format(" ({}x)", gaps) : std::string()));
}

// The panels' left edge [fraction of the width]: the longest status lane
// label ("MODEL_MISMATCH", 14 characters: 106 px) fits left of the axis.
double LeftEdge(int width_px) {
  size_t longest = 0;
  for (int i = 0; i < kStatusBitCount; ++i) longest = std::max(longest, std::string(kStatusBitNames[i].word).size());
  const double label_px = kLaneLabelCharPx * static_cast<double>(longest) + kLaneLabelGapPx;
  return std::max(kMinLeftEdge, label_px / static_cast<double>(width_px));
}

// Places the next panel: `height` of the page below *top, from left_edge to kRightEdge.
std::string Panel(double* top, double height, bool bottom_axis, double left_edge) {
  const double bottom = *top - height;
  std::string text = fmt::format(
      "set tmargin at screen {:.4f}\nset bmargin at screen {:.4f}\nset lmargin at screen {:.4f}\nset rmargin at "
      "screen {}\n",
      *top, bottom + 0.012, left_edge, kRightEdge);
  text += bottom_axis ? "set format x '%g'\nset xlabel 't [s]'\n" : "set format x ''\nunset xlabel\n";
  *top = bottom;
  return text;
}

std::string YRangeCommands(const YRange& range) {
  std::string text = fmt::format("set yrange [{:.6g}:{:.6g}]\n", range.low, range.high);
  if (!range.note.empty()) {
    text += "set label 1 " + GnuplotQuoted(range.note) +
            " at graph 0.01, graph 0.07 left front boxed textcolor rgb '#b00000' font ',9'\n";
  }
  return text;
}

// The estimates, each with the TRUTH sample of its stamp (if any).
struct PairedRows {
  std::vector<Row> rows;
  bool with_truth = false;
};

PairedRows PairWithTruth(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                         int64_t origin_utime) {
  std::unordered_map<int64_t, const TruthSample*> truth_by_utime;
  truth_by_utime.reserve(truth.size());
  for (const TruthSample& t : truth) truth_by_utime[t.utime] = &t;
  PairedRows paired;
  paired.rows.reserve(forces.size());
  for (const ForceEstimate& e : forces) {
    const auto it = truth_by_utime.find(e.utime);
    const TruthSample* t = it == truth_by_utime.end() ? nullptr : it->second;
    paired.with_truth = paired.with_truth || t != nullptr;
    paired.rows.push_back({static_cast<double>(e.utime - origin_utime) * 1e-6, &e, t});
  }
  return paired;
}

// The median of rotor r's finite force sigmas [N]; NaN if none.
double MedianStdN(const std::vector<Row>& rows, int r) {
  std::vector<double> stds;
  stds.reserve(rows.size());
  for (const Row& row : rows) {
    if (std::isfinite(row.estimate->force_std_n[r])) stds.push_back(row.estimate->force_std_n[r]);
  }
  if (stds.empty()) return kNaN;
  std::nth_element(stds.begin(), stds.begin() + stds.size() / 2, stds.end());
  return stds[stds.size() / 2];
}

// y-ranges from the data, per panel.
struct PanelRanges {
  YRange force[kBirotorRotors];
  YRange error;
  YRange scale;
};

PanelRanges RangesOf(const std::vector<Row>& rows, const double median_std_n[kBirotorRotors],
                     const ForcePlotOptions& options) {
  std::vector<std::pair<double, double>> force_values[kBirotorRotors], error_values, scale_values;
  for (const Row& row : rows) {
    for (int r = 0; r < kBirotorRotors; ++r) {
      force_values[r].emplace_back(row.estimate->force_n[r], row.t_s);
      scale_values.emplace_back(row.estimate->thrust_scale[r], row.t_s);
      if (row.truth == nullptr) continue;
      force_values[r].emplace_back(row.truth->force_n[r], row.t_s);
      scale_values.emplace_back(row.truth->thrust_scale[r], row.t_s);
      error_values.emplace_back(row.estimate->force_n[r] - row.truth->force_n[r], row.t_s);
    }
  }
  PanelRanges ranges;
  for (int r = 0; r < kBirotorRotors; ++r) ranges.force[r] = RangeOf(force_values[r], options.clip_fraction, 0.5, " N");
  ranges.error = RangeOf(error_values, options.clip_fraction, 0.1, " N");
  // The ±1σ envelopes stay in view, so an overstated sigma shows as such.
  const double widest_median_std_n = std::max(median_std_n[0], median_std_n[1]);
  if (std::isfinite(widest_median_std_n)) {
    ranges.error.low = std::min(ranges.error.low, -1.15 * widest_median_std_n);
    ranges.error.high = std::max(ranges.error.high, 1.15 * widest_median_std_n);
  }
  ranges.scale = RangeOf(scale_values, options.clip_fraction, 0.2, "");
  // The thresholds are always in view, and 1.0 (healthy) too.
  for (const ThresholdLine& line : options.scale_lines) {
    ranges.scale.low = std::min(ranges.scale.low, line.value - 0.03);
  }
  ranges.scale.high = std::max(ranges.scale.high, 1.03);
  return ranges;
}

// Vertical lines in every panel (arrows persist, appended to script); the
// labels, for the top panel, returned.
std::string MarkerCommands(std::vector<std::pair<double, std::string>> markers, std::string* script) {
  std::sort(markers.begin(), markers.end());
  std::string marker_labels;
  for (size_t k = 0; k < markers.size(); ++k) {
    *script += fmt::format(
        "set arrow {} from first {:.6f}, graph 0 to first {:.6f}, graph 1 nohead front lw 1.5 "
        "dt 2 lc rgb '{}'\n",
        k + 1, markers[k].first, markers[k].first, kMarkerColor);
    marker_labels += fmt::format(
        "set label {} {} at first {:.6f}, graph {:.3f} left offset 0.4,0 front boxed "
        "textcolor rgb '{}' font ',9'\n",
        k + 10, GnuplotQuoted(markers[k].second), markers[k].first, 0.93 - 0.085 * static_cast<double>(k % 6),
        kMarkerColor);
  }
  return marker_labels;
}

// Rotor r's force panel: the ±1σ band, the truth and the estimate.
std::string ForcePanelPlot(int r, double median_std_n, bool with_truth) {
  std::string text = fmt::format(
      "set ylabel 'f{} [N]'\nplot $data u 1:(${}-${}):(${}+${}) w filledcurves fc rgb '{}' "
      "fs transparent solid 0.25 noborder t '±1σ, median {:.3f} N'",
      r + 1, 2 + r, 4 + r, 2 + r, 4 + r, kRotorColor[r], median_std_n);
  if (with_truth) text += fmt::format(", $data u 1:{} w l lw 2 lc rgb '{}' t 'true'", 9 + r, kTrueColor);
  text +=
      fmt::format(", $data u 1:{} w l lw 1 lc rgb '{}' t 'estimated f{}'\nunset label\n", 2 + r, kRotorColor[r], r + 1);
  return text;
}

// The error panel: the errors first, the ±1σ envelopes drawn over them so
// that they stay visible.
std::string ErrorPanelPlot() {
  std::string text = fmt::format(
      "set ylabel 'error [N]'\nplot $data u 1:13 w l lc rgb '{}' t 'f1 est - true', "
      "$data u 1:14 w l lc rgb '{}' t 'f2 est - true'",
      kRotorColor[0], kRotorColor[1]);
  for (int r = 0; r < kBirotorRotors; ++r) {
    text += fmt::format(
        ", $data u 1:{} w l lw 1.5 lc rgb '{}' t '±1σ f{}', $data u 1:(-${}) w l lw 1.5 lc rgb '{}' notitle", 4 + r,
        kSigmaColor[r], r + 1, 4 + r, kSigmaColor[r]);
  }
  return text + "\nunset label\n";
}

// The thrust-efficiency panel with the fault thresholds: the estimates
// first, the true μ dashed over them, so that where they agree both show.
std::string ScalePanelPlot(const std::vector<ThresholdLine>& scale_lines, bool with_truth) {
  std::string text = "set ylabel 'thrust efficiency μ [1]'\nplot ";
  for (const ThresholdLine& line : scale_lines) {
    text += fmt::format("{:.6g} w l lw 1.5 dt 3 lc rgb '#b00000' t {}, ", line.value, GnuplotQuoted(line.label));
  }
  for (int r = 0; r < kBirotorRotors; ++r) {
    text += fmt::format("$data u 1:{} w l lc rgb '{}' t 'estimated μ{}'{}", 6 + r, kRotorColor[r], r + 1,
                        r == 0 || with_truth ? ", " : "");
  }
  for (int r = 0; with_truth && r < kBirotorRotors; ++r) {
    text += fmt::format("$data u 1:{} w l lw 1.5 dt (6,6) lc rgb '{}' t 'true μ{}'{}", 11 + r, kTrueColor, r + 1,
                        r == 0 ? ", " : "");
  }
  return text + "\nunset label\n";
}

// Status strip: one row per bit, a thick line where it is set (a square
// for a single message, e.g. a RESET).
std::string StatusPanelPlot() {
  std::string text =
      fmt::format("set yrange [0.4:{}.6]\nunset grid\nset grid x\nunset key\nset ytics (", kStatusBitCount);
  for (int i = 0; i < kStatusBitCount; ++i) {
    text += fmt::format("{}{} {}", i == 0 ? "" : ", ", GnuplotQuoted(kStatusBitNames[i].word), kStatusBitCount - i);
  }
  text += ") font ',8'\nunset ylabel\nplot ";
  for (int i = 0; i < kStatusBitCount; ++i) {
    const bool alarm = kStatusBitNames[i].bit & kAlarmStatusBits;
    text += fmt::format("$data u 1:((int($8) & {}) ? {} : NaN) w lp lw 5 pt 5 ps 0.3 lc rgb '{}' notitle{}",
                        kStatusBitNames[i].bit, kStatusBitCount - i, alarm ? "#b00000" : "#2ca02c",
                        i + 1 < kStatusBitCount ? ", " : "\n");
  }
  return text;
}

}  // namespace

std::vector<ThresholdLine> ThrustScaleLines(const EkfOptions& ekf) {
  // EkfOptions: a rotor fault is relative, rotor i is flagged when it is
  // rotor_fault_asymmetry (plus n_sigma std) below the other; against a rotor
  // at 1 that is the line 1 - asymmetry. THRUST_DEFICIT: both below thrust_deficit_scale.
  const double rotor_line = 1.0 - ekf.rotor_fault_asymmetry;
  return {{rotor_line, fmt::format("rotor fault below {:.2f}", rotor_line)}};
}

std::string ThresholdWords(const std::vector<ThresholdLine>& lines) {
  std::string words;
  for (const ThresholdLine& line : lines) words += (words.empty() ? "" : ", ") + line.label;
  return words;
}

std::string ForcePlotTitle(const std::string& log_path) {
  const size_t slash = log_path.find_last_of('/');
  return "Rotor forces, thrust efficiencies and status flags of " +
         (slash == std::string::npos ? log_path : log_path.substr(slash + 1));
}

PlotMarker ThrustStepMarker(int rotor, double step_time_s) {
  return {static_cast<int64_t>(std::llround(step_time_s * 1e6)), fmt::format("true thrust step rotor {}", rotor)};
}

std::string ForcePlotScript(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                            const ForcePlotOptions& options) {
  int64_t origin_utime = forces.front().utime;
  if (!truth.empty()) origin_utime = std::min(origin_utime, truth.front().utime);
  const auto seconds = [origin_utime](int64_t utime) { return static_cast<double>(utime - origin_utime) * 1e-6; };
  const PairedRows paired = PairWithTruth(forces, truth, origin_utime);
  const std::vector<Row>& rows = paired.rows;
  const bool with_truth = paired.with_truth;
  const double median_std_n[kBirotorRotors] = {MedianStdN(rows, 0), MedianStdN(rows, 1)};
  const PanelRanges ranges = RangesOf(rows, median_std_n, options);

  std::string script = fmt::format(
      "set terminal pngcairo size {},{} noenhanced font 'sans,10'\n"
      "set encoding utf8\nset grid\nset key at screen {:.3f}, graph 1 left top vertical Left reverse font ',9'\n"
      "set style textbox opaque noborder\n"
      "set multiplot title {}\n",
      options.width_px, options.height_px, kRightEdge + 0.01,
      GnuplotQuoted(options.title + (with_truth ? "" : "  (no TRUTH: estimates only)")));
  const double gap_s = GapS(rows);
  script += DataBlock(rows, gap_s);
  script += fmt::format("set xrange [{:.6f}:{:.6f}]\n", rows.front().t_s, rows.back().t_s);

  std::vector<std::pair<double, std::string>> markers = StatusMarkers(rows);
  AddGapMarker(rows, gap_s, &markers);
  for (const PlotMarker& m : options.markers) {
    markers.emplace_back(seconds(m.utime), fmt::format("{} {:.3f} s", m.label, seconds(m.utime)));
  }
  const std::string marker_labels = MarkerCommands(std::move(markers), &script);

  const double status_height = 0.15;
  const double scale_height = 0.17;
  const double error_height = with_truth ? 0.17 : 0.0;
  const double force_height = (kTopEdge - kBottomEdge - status_height - scale_height - error_height) / 2.0;
  const double left = LeftEdge(options.width_px);
  double top = kTopEdge;
  for (int r = 0; r < kBirotorRotors; ++r) {
    script += Panel(&top, force_height, false, left) + YRangeCommands(ranges.force[r]);
    if (r == 0) script += marker_labels;
    script += ForcePanelPlot(r, median_std_n[r], with_truth);
  }
  if (with_truth) script += Panel(&top, error_height, false, left) + YRangeCommands(ranges.error) + ErrorPanelPlot();
  script += Panel(&top, scale_height, false, left) + YRangeCommands(ranges.scale);
  script += ScalePanelPlot(options.scale_lines, with_truth);
  script += Panel(&top, status_height, true, left) + StatusPanelPlot();
  script += "unset multiplot\n";
  return script;
}

bool WriteForcePlot(const std::vector<ForceEstimate>& forces, const std::vector<TruthSample>& truth,
                    const ForcePlotOptions& options, const std::string& png_path, std::string* error) {
  if (forces.empty()) {
    *error = "no FORCE message to plot";
    return false;
  }
  return RenderGnuplotPng(ForcePlotScript(forces, truth, options), png_path, error);
}

}  // namespace birotor
