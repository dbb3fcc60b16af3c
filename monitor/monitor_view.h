// Text of birotor-monitor's live view and final summary: a progress bar toward
// the scenario duration, one plain line per update for logs and CI, a fixed
// block of lines for a terminal, and the closing words. With TRUTH it shows
// true against estimated; without (a real vehicle) the estimates with their
// 1-sigma, the thrust efficiency, the flags and the estimator's input health.
#pragma once

#include <cstdint>
#include <string>

#include "estimator/estimator_config.h"
#include "evaluation/eval_metrics.h"
#include "monitor/monitor_collector.h"
#include "plot/force_plot.h"
#include "plot/status_words.h"

namespace birotor {

// "[#####-----]  50%" for elapsed_s of total_s; without a known total
// (total_s <= 0) just the elapsed time.
std::string ProgressBar(double elapsed_s, double total_s, int width);

// What the view needs besides the collector.
struct ViewContext {
  double scenario_duration_s = 0;  // progress target [s]; 0 if unknown
  double force_rate_hz = 0;        // FORCE messages per wall second, last interval [Hz]
  double status_rate_hz = 0;       // ESTIMATOR_STATUS messages per wall second [Hz]
  bool truth_expected = true;      // false: vehicle view, never waits for TRUTH
  // Shown next to the thrust efficiency: the estimator's thresholds in words.
  std::string thresholds = ThresholdWords(ThrustScaleLines(EkfOptions{}));
  // An input whose newest sample is older than this is shown as stale [s].
  double stale_age_s = 0.1;
};

// Vehicle time of the newest sample since the first TRUTH (or, without TRUTH,
// the first FORCE) [s].
double ElapsedS(const MonitorCollector& collector);

// One line, no control characters (non-TTY output):
// "t=  3.20/15.00 s ...  f1 true 3.412 est 3.405 ±0.012 N  f2 ...  VALID  ...".
std::string PlainViewLine(const MonitorCollector& collector, const ViewContext& context);

// A block of exactly kTerminalViewLines lines for a terminal, each ending in
// ESC[K '\n'; the caller moves the cursor back up that many lines to redraw.
inline constexpr int kTerminalViewLines = 14;
std::string TerminalView(const MonitorCollector& collector, const ViewContext& context);

// The slow vehicle parameters of an ESTIMATOR_STATUS in one line:
// "learned: strain scale g 0.712 ±0.004 / 1.000 (learned)  body mass 4.000 kg (params)"
// (a value without sigma is the parameter file's: not learned).
std::string LearnedLine(const estimator_status_t& status);

// "ROTOR2_FAULT 10.037 s, STALE 3.100 s (4x)": the first rise of every alarm
// bit, in seconds since the view's origin; "none" when nothing rose.
std::string FirstAlarms(const MonitorCollector& collector);

// The final figures in words, one rotor per line (what birotor-eval's table row says).
std::string SummaryText(const EvalResult& result);

// The final words without TRUTH: the FORCE stream, the flags, the estimator's
// last health report.
std::string VehicleSummaryText(const MonitorCollector& collector);

// Packets lost or inputs missing, in words; empty on a clean run (the
// estimator's start-up reset is not a loss).
std::string DeliveryNote(const MonitorCollector& collector);

}  // namespace birotor
