// Formatting of birotor-monitor's view.
#include "monitor/monitor_view.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "estimator/samples.h"

namespace birotor {
namespace {

struct StatusName {
  int32_t bit;
  const char* word;
};

// Order and meaning as in lcmtypes/force_estimate_t.lcm.
constexpr StatusName kStatusNames[] = {
    {kStatusValid, "VALID"},       {kStatusConverging, "CONVERGING"},    {kStatusMeasurementRejected, "REJECTED"},
    {kStatusInputStale, "STALE"},  {kStatusRotor1Fault, "ROTOR1_FAULT"}, {kStatusRotor2Fault, "ROTOR2_FAULT"},
    {kStatusFilterReset, "RESET"}, {kStatusNoMotorInput, "NO_MOTOR"},
};

// Vehicle time of the newest sample of either stream, since the first TRUTH [s].
double ElapsedS(const MonitorCollector& c) {
  if (!c.has_truth()) return 0.0;
  int64_t newest = c.latest_truth().utime;
  if (c.has_force()) newest = std::max(newest, c.latest_force().utime);
  return static_cast<double>(newest - c.truth().front().utime) * 1e-6;
}

std::string TimeAndProgress(const MonitorCollector& c, const ViewContext& context) {
  const double elapsed_s = ElapsedS(c);
  if (context.scenario_duration_s > 0) {
    return fmt::format("t={:6.2f}/{:.2f} s {}", elapsed_s, context.scenario_duration_s,
                       ProgressBar(elapsed_s, context.scenario_duration_s, 20));
  }
  return fmt::format("t={:6.2f} s", elapsed_s);
}

std::string Force(double force_n) {
  return std::isfinite(force_n) ? fmt::format("{:6.3f}", force_n) : std::string("   nan");
}

}  // namespace

std::string StatusWords(int32_t status) {
  std::string words;
  int32_t known = 0;
  for (const StatusName& name : kStatusNames) {
    known |= name.bit;
    if (!(status & name.bit)) continue;
    if (!words.empty()) words += '|';
    words += name.word;
  }
  if (status & ~known) words += fmt::format("{}0x{:x}", words.empty() ? "" : "|", status & ~known);
  return words.empty() ? "none" : words;
}

std::string ProgressBar(double elapsed_s, double total_s, int width) {
  if (total_s <= 0) return fmt::format("{:.1f} s", elapsed_s);
  const double fraction = std::clamp(elapsed_s / total_s, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(fraction * width));
  return fmt::format("[{}{}] {:3.0f}%", std::string(filled, '#'), std::string(width - filled, '-'), fraction * 100.0);
}

std::string PlainViewLine(const MonitorCollector& c, const ViewContext& context) {
  std::string line = TimeAndProgress(c, context);
  if (!c.has_truth() || !c.has_force()) {
    return line + fmt::format("  waiting: TRUTH {} FORCE {} STATUS {}", c.truth().size(), c.forces().size(),
                              c.status_messages());
  }
  const TruthSample& t = c.latest_truth();
  const ForceEstimate& e = c.latest_force();
  line +=
      fmt::format("  f1 true {} est {} N  f2 true {} est {} N  mu1 {:.3f}/{:.3f} mu2 {:.3f}/{:.3f}  {}",
                  Force(t.force_n[0]), Force(e.force_n[0]), Force(t.force_n[1]), Force(e.force_n[1]), t.thrust_scale[0],
                  e.thrust_scale[0], t.thrust_scale[1], e.thrust_scale[1], StatusWords(e.status));
  return line;
}

std::string TerminalView(const MonitorCollector& c, const ViewContext& context) {
  // Every line is cleared to its end (ESC[K) so a shorter redraw leaves no debris.
  constexpr const char* kEnd = "\x1b[K\n";
  std::string view = fmt::format("{}  FORCE {:.0f} Hz{}", TimeAndProgress(c, context), context.force_rate_hz, kEnd);
  if (!c.has_truth() || !c.has_force()) {
    view += fmt::format("waiting for TRUTH ({}) and FORCE ({}) ...{}", c.truth().size(), c.forces().size(), kEnd);
    for (int i = 2; i < kTerminalViewLines; ++i) view += kEnd;
    return view;
  }
  const TruthSample& t = c.latest_truth();
  const ForceEstimate& e = c.latest_force();
  view += fmt::format("           true      estimated  (+- 1 sigma)   error{}", kEnd);
  for (int r = 0; r < 2; ++r) {
    view += fmt::format("f{} [N]   {}    {}     (+- {:.3f})    {:+.3f}{}", r + 1, Force(t.force_n[r]),
                        Force(e.force_n[r]), e.force_std_n[r], e.force_n[r] - t.force_n[r], kEnd);
  }
  view += fmt::format("thrust efficiency mu  true {:.3f} {:.3f}   est {:.3f} {:.3f}{}", t.thrust_scale[0],
                      t.thrust_scale[1], e.thrust_scale[0], e.thrust_scale[1], kEnd);
  const MonitorHealth& h = c.health();
  view += fmt::format("status {}  | {} strain recv {} fused {} faults {} overload {} resets {}{}",
                      StatusWords(e.status), h.received ? h.method : std::string("(no status yet)"), h.strain_received,
                      h.strain_fused, h.strain_faults, h.dropped_overload, h.resets, kEnd);
  return view;
}

std::string SummaryText(const EvalResult& r) {
  std::string text;
  for (int i = 0; i < 2; ++i) {
    text += fmt::format("rotor {}: MAE {:.4f} N  RMSE {:.4f} N  p95 {:.4f} N  max {:.4f} N  ({} scored)\n", i + 1,
                        r.rotor[i].mae_n, r.rotor[i].rmse_n, r.rotor[i].p95_n, r.rotor[i].max_n, r.rotor[i].count);
  }
  text += fmt::format("paired {}  unpaired {}  invalid {}  non-finite {}  false alarms {}", r.paired, r.unpaired,
                      r.invalid, r.nonfinite, r.false_alarms);
  if (r.step_rotor != 0) {
    text += fmt::format(
        "\nthrust step on rotor {} at {:.3f} s: detected after {}, scale error {:.4f} 100 ms later", r.step_rotor,
        r.step_time_s,
        std::isnan(r.detection_delay_s) ? std::string("(never)") : fmt::format("{:.0f} ms", r.detection_delay_s * 1e3),
        r.scale_error_after_step);
  }
  return text + "\n";
}

}  // namespace birotor
