// Text of birotor-monitor's live view and final summary: status bits as words,
// a progress bar toward the scenario duration, one plain line per update for
// logs and CI, and a few refreshing lines for a terminal.
#pragma once

#include <cstdint>
#include <string>

#include "evaluation/eval_metrics.h"
#include "monitor/monitor_collector.h"

namespace birotor {

// Status bits of force_estimate_t as words, e.g. "VALID" or
// "CONVERGING|NO_MOTOR"; "none" for 0.
std::string StatusWords(int32_t status);

// "[#####-----]  50%" for elapsed_s of total_s; without a known total
// (total_s <= 0) just the elapsed time.
std::string ProgressBar(double elapsed_s, double total_s, int width);

// What the view needs besides the collector.
struct ViewContext {
  double scenario_duration_s = 0;  // progress target [s]; 0 if unknown
  double force_rate_hz = 0;        // FORCE messages per wall second, last interval [Hz]
};

// One line, no control characters (non-TTY output):
// "t=  3.20/15.00 s  42%  f1 true 3.412 est 3.405 N  f2 ...  mu 1.000/0.998 ...  VALID".
std::string PlainViewLine(const MonitorCollector& collector, const ViewContext& context);

// A block of lines for a terminal, each ending in '\n'; the caller moves the
// cursor back up kTerminalViewLines lines before redrawing.
inline constexpr int kTerminalViewLines = 6;
std::string TerminalView(const MonitorCollector& collector, const ViewContext& context);

// The final figures in words, one rotor per line (what birotor-eval's table row says).
std::string SummaryText(const EvalResult& result);

}  // namespace birotor
