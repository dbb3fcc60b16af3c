// Formatting of birotor-monitor's view.
#include "monitor/monitor_view.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "samples/samples.h"
#include "transport/channels.h"
#include "transport/wire_text.h"

namespace birotor {
namespace {

// Every terminal line is cleared to its end (ESC[K) so a shorter redraw leaves no debris.
constexpr const char* kEnd = "\x1b[K\n";
// The estimator's inputs in the order of estimator_status_t.inputs.
constexpr const char* kInputs[] = {kStrainChannel, kMotorChannel, kImuChannel, kPoseChannel};

int64_t OriginUtime(const MonitorCollector& c) {
  if (c.has_truth()) return c.truth().front().utime;
  return c.has_force() ? c.forces().front().utime : 0;
}

double SecondsSinceOrigin(const MonitorCollector& c, int64_t utime) {
  return static_cast<double>(utime - OriginUtime(c)) * 1e-6;
}

std::string TimeAndProgress(const MonitorCollector& c, const ViewContext& context) {
  const double elapsed_s = ElapsedS(c);
  if (context.scenario_duration_s > 0) {
    return fmt::format("t={:6.2f}/{:.2f} s {}", elapsed_s, context.scenario_duration_s,
                       ProgressBar(elapsed_s, context.scenario_duration_s, 20));
  }
  return fmt::format("t={:6.2f} s", elapsed_s);
}

std::string Number(double value, int width, int decimals) {
  return std::isfinite(value) ? fmt::format("{:{}.{}f}", value, width, decimals) : fmt::format("{:>{}}", "-", width);
}

std::string Force(double force_n) { return Number(force_n, 6, 3); }

bool Waiting(const MonitorCollector& c, const ViewContext& context) {
  return !c.has_force() || (context.truth_expected && !c.has_truth());
}

std::string WaitingText(const MonitorCollector& c, const ViewContext& context) {
  if (context.truth_expected) {
    return fmt::format("waiting: TRUTH {} FORCE {} STATUS {}", c.truth().size(), c.forces().size(),
                       c.status_messages());
  }
  return fmt::format("waiting: FORCE {} STATUS {}", c.forces().size(), c.status_messages());
}

// Samples an input lost or had refused before fusion: out of order,
// duplicates, undecodable packets.
int64_t BadPackets(const input_health_t& input) { return input.out_of_order + input.duplicates + input.decode_errors; }

std::string InputRow(const char* name, const input_health_t* input, const ViewContext& context) {
  if (input == nullptr) return fmt::format("{:<7} (not in ESTIMATOR_STATUS)", name);
  const bool stale = !std::isfinite(input->age_s) || input->age_s > context.stale_age_s;
  return fmt::format("{:<7} {:>8} {:>8} {:>9} {:>9} {:>8} {:>8} {:>9} {:>9}{}", name, Number(input->rate_hz, 8, 1),
                     Number(input->age_s * 1e3, 8, 1), input->fused, input->rejected_gate, input->rejected_invalid,
                     input->missing_samples, BadPackets(*input), input->dropped_overload,
                     stale && input->received > 0 ? "  STALE" : (input->received == 0 ? "  none received" : ""));
}

std::string EstimatorLine(const MonitorCollector& c) {
  if (!c.has_status()) return "estimator: no ESTIMATOR_STATUS yet";
  const estimator_status_t& s = c.latest_status();
  return fmt::format("estimator {}  resets {} (last: {})  strain NIS mean {} max {} gate {}  time p99 {} us",
                     PrintableWireText(s.method), s.resets,
                     s.last_reset_reason.empty() ? "none" : PrintableWireText(s.last_reset_reason),
                     Number(s.strain_nis_mean, 0, 2), Number(s.strain_nis_max, 0, 1), Number(s.strain_gate, 0, 1),
                     Number(s.processing_time_p99_us, 0, 0));
}

// One learned value: "0.712 ±0.004", or "1.000" when its sigma is NaN (not learned).
std::string LearnedValue(double value, double sigma, int decimals) {
  return std::isfinite(sigma) ? fmt::format("{} ±{}", Number(value, 0, decimals), Number(sigma, 0, decimals))
                              : Number(value, 0, decimals);
}

}  // namespace

std::string LearnedLine(const estimator_status_t& s) {
  auto source = [](const std::string& text) { return text.empty() ? std::string("-") : PrintableWireText(text); };
  return fmt::format("learned: strain scale g {} / {} ({})  body mass {} kg ({})",
                     LearnedValue(s.strain_scale[0], s.strain_scale_std[0], 3),
                     LearnedValue(s.strain_scale[1], s.strain_scale_std[1], 3), source(s.strain_scale_source),
                     LearnedValue(s.body_mass_kg, s.body_mass_std_kg, 3), source(s.body_mass_source));
}

double ElapsedS(const MonitorCollector& c) {
  int64_t newest = OriginUtime(c);
  if (c.has_truth()) newest = std::max(newest, c.latest_truth().utime);
  if (c.has_force()) newest = std::max(newest, c.latest_force().utime);
  return SecondsSinceOrigin(c, newest);
}

std::string ProgressBar(double elapsed_s, double total_s, int width) {
  if (total_s <= 0) return fmt::format("{:.1f} s", elapsed_s);
  const double fraction = std::clamp(elapsed_s / total_s, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(fraction * width));
  return fmt::format("[{}{}] {:3.0f}%", std::string(filled, '#'), std::string(width - filled, '-'), fraction * 100.0);
}

std::string FirstAlarms(const MonitorCollector& c) {
  std::string text;
  for (int i = 0; i < kStatusBitCount; ++i) {
    const StatusBitName& name = kStatusBitNames[i];
    if (!(name.bit & kAlarmStatusBits)) continue;
    const FlagRises& rises = c.rises(name.bit);
    if (rises.count == 0) continue;
    if (!text.empty()) text += ", ";
    text += fmt::format("{} {:.3f} s", name.word, SecondsSinceOrigin(c, rises.first_utime));
    if (rises.count > 1) text += fmt::format(" ({}x)", rises.count);
  }
  return text.empty() ? "none" : text;
}

std::string PlainViewLine(const MonitorCollector& c, const ViewContext& context) {
  std::string line = TimeAndProgress(c, context);
  if (Waiting(c, context)) return line + "  " + WaitingText(c, context);
  const ForceEstimate& e = c.latest_force();
  const bool truth = c.has_truth();
  for (int r = 0; r < 2; ++r) {
    line += fmt::format("  f{} ", r + 1);
    if (truth) line += fmt::format("true {} est ", Force(c.latest_truth().force_n[r]));
    line += fmt::format("{} ±{:.3f} N", Force(e.force_n[r]), e.force_std_n[r]);
  }
  for (int r = 0; r < 2; ++r) {
    line += truth ? fmt::format("  mu{} {:.3f}/{:.3f}", r + 1, c.latest_truth().thrust_scale[r], e.thrust_scale[r])
                  : fmt::format("  mu{} {:.3f}", r + 1, e.thrust_scale[r]);
  }
  line += fmt::format("  {}  first alarms: {}", StatusWords(e.status), FirstAlarms(c));
  if (const input_health_t* strain = c.input(kStrainChannel)) {
    line += fmt::format("  strain {} Hz gate-rejected {} bad packets {}  resets {}", Number(strain->rate_hz, 0, 0),
                        strain->rejected_gate, BadPackets(*strain), c.latest_status().resets);
  }
  return line;
}

std::string TerminalView(const MonitorCollector& c, const ViewContext& context) {
  std::string view =
      fmt::format("{}  FORCE {:.0f} Hz  STATUS {:.1f} Hz{}{}", TimeAndProgress(c, context), context.force_rate_hz,
                  context.status_rate_hz, context.truth_expected ? "" : "  (no TRUTH: vehicle view)", kEnd);
  int lines = 1;
  const auto add = [&](const std::string& line) {
    view += line + kEnd;
    ++lines;
  };
  if (Waiting(c, context)) {
    add(WaitingText(c, context) + " ...");
  } else {
    const ForceEstimate& e = c.latest_force();
    const bool truth = c.has_truth();
    add(truth ? "           true   estimated   ±1 sigma      error" : "         estimated   ±1 sigma");
    for (int r = 0; r < 2; ++r) {
      if (truth) {
        const double true_n = c.latest_truth().force_n[r];
        add(fmt::format("f{} [N]   {}    {}    ±{:.3f}    {:+.3f}", r + 1, Force(true_n), Force(e.force_n[r]),
                        e.force_std_n[r], e.force_n[r] - true_n));
      } else {
        add(fmt::format("f{} [N]     {}    ±{:.3f}", r + 1, Force(e.force_n[r]), e.force_std_n[r]));
      }
    }
    std::string scale = "thrust efficiency mu  ";
    if (truth) {
      scale += fmt::format("true {:.3f} {:.3f}   ", c.latest_truth().thrust_scale[0], c.latest_truth().thrust_scale[1]);
    }
    add(scale + fmt::format("est {:.3f} {:.3f}   ({})", e.thrust_scale[0], e.thrust_scale[1], context.thresholds));
    add(fmt::format("status {}   first alarms: {}", StatusWords(e.status), FirstAlarms(c)));
    const ForceStreamStats& f = c.force_stats();
    add(fmt::format("FORCE valid {:.1f} %  non-finite {}  seq gaps {} ({} missing)  resets after start {}",
                    100.0 * static_cast<double>(f.valid) / static_cast<double>(c.forces().size()), f.nonfinite,
                    f.seq_gaps, f.seq_missing, f.resets_after_start));
  }
  add(EstimatorLine(c));
  add(c.has_status() ? LearnedLine(c.latest_status()) : std::string("learned: -"));
  add(fmt::format("{:<7} {:>8} {:>8} {:>9} {:>9} {:>8} {:>8} {:>9} {:>9}", "input", "rate Hz", "age ms", "fused",
                  "gate rej", "invalid", "missing", "bad pkts", "overload"));
  for (const char* name : kInputs) {
    add(c.has_status() ? InputRow(name, c.input(name), context) : std::string(name));
  }
  while (lines < kTerminalViewLines) add("");
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

std::string VehicleSummaryText(const MonitorCollector& c) {
  if (!c.has_force()) return "no FORCE received\n";
  const ForceStreamStats& f = c.force_stats();
  const double n = static_cast<double>(c.forces().size());
  const double span_s = ElapsedS(c);
  double std_sum_n[2] = {0, 0};
  for (const ForceEstimate& e : c.forces()) {
    for (int r = 0; r < 2; ++r) std_sum_n[r] += std::isfinite(e.force_std_n[r]) ? e.force_std_n[r] : 0.0;
  }
  const ForceEstimate& last = c.latest_force();
  std::string text = fmt::format("FORCE {} messages over {:.2f} s ({} Hz), VALID {:.1f} %, non-finite {}\n",
                                 c.forces().size(), span_s, Number(span_s > 0 ? (n - 1) / span_s : NAN, 0, 1),
                                 100.0 * static_cast<double>(f.valid) / n, f.nonfinite);
  text +=
      fmt::format("mean 1-sigma f1 {:.4f} N f2 {:.4f} N; at the end f1 {:.3f} N f2 {:.3f} N, mu {:.3f} {:.3f}, {}\n",
                  std_sum_n[0] / n, std_sum_n[1] / n, last.force_n[0], last.force_n[1], last.thrust_scale[0],
                  last.thrust_scale[1], StatusWords(last.status));
  text += fmt::format("first alarms: {}\n", FirstAlarms(c));
  if (c.has_status()) {
    // The last report may cover a period after the inputs stopped (NIS NaN),
    // so the NIS is the run's, not the last period's.
    const estimator_status_t& s = c.latest_status();
    text += fmt::format(
        "estimator {}: resets {} (last: {}); strain NIS over the run mean {} (2 for a consistent "
        "filter), max {}, gate {}\n",
        PrintableWireText(s.method), s.resets,
        s.last_reset_reason.empty() ? "none" : PrintableWireText(s.last_reset_reason),
        Number(c.strain_nis_mean_over_run(), 0, 2), Number(c.strain_nis_max_over_run(), 0, 1),
        Number(s.strain_gate, 0, 1));
  } else {
    text += "estimator: no ESTIMATOR_STATUS received\n";
  }
  if (const input_health_t* strain = c.input(kStrainChannel)) {
    text += fmt::format("strain: fused {}, gate-rejected {}, invalid {}, missing {}, bad packets {}, overload {}\n",
                        strain->fused, strain->rejected_gate, strain->rejected_invalid, strain->missing_samples,
                        BadPackets(*strain), strain->dropped_overload);
  }
  if (c.has_status()) {
    const estimator_status_t& s = c.latest_status();
    const input_health_t& a = s.accelerometer;
    text += fmt::format(
        "gauge offsets {:.2e} / {:.2e} rad +- {:.1e} / {:.1e} (from {}, learned in flight); accelerometer: fused {}, "
        "gate-rejected {}, not fused {} (on the ground or off)\n",
        s.gauge_offset_rad[0], s.gauge_offset_rad[1], s.gauge_offset_std_rad[0], s.gauge_offset_std_rad[1],
        s.gauge_offset_source.empty() ? "-" : PrintableWireText(s.gauge_offset_source), a.fused, a.rejected_gate,
        a.not_fused);
    text += LearnedLine(s) + "\n";
  }
  return text;
}

// seq going back this many times means interleaved publishers, not restarts.
constexpr int64_t kSeveralPublishersBackwardSteps = 3;

std::string DeliveryNote(const MonitorCollector& c) {
  const ForceStreamStats& f = c.force_stats();
  std::string note;
  int64_t lost_forces = 0;
  // Two publishers on one FORCE channel (a log played back beside the
  // daemon, a second estimator on the prefix) interleave two seq streams:
  // seq goes back on every switch and the forward jumps are the distance
  // between the streams, not lost messages. A restart goes back once.
  if (f.seq_backwards >= kSeveralPublishersBackwardSteps) {
    return fmt::format(
        "FORCE comes from more than one publisher: seq went back {} times (two interleaved streams, e.g. a log played "
        "back beside the daemon or a second estimator on this prefix); its seq gaps are not losses",
        f.seq_backwards);
  }
  if (f.seq_missing > 0) {
    // A strain sample the estimator never fused leaves a hole in FORCE seq too.
    int64_t upstream = 0;
    if (const input_health_t* strain = c.input(kStrainChannel)) {
      upstream = strain->missing_samples + strain->rejected_invalid + strain->dropped_overload;
    }
    lost_forces = std::max<int64_t>(0, f.seq_missing - upstream);
    note += fmt::format(
        "FORCE seq: {} gaps, {} messages missing; the estimator reports {} strain samples missing, invalid or shed "
        "(input faults), so about {} FORCE messages were lost on the way to this monitor",
        f.seq_gaps, f.seq_missing, upstream, lost_forces);
  }
  if (f.seq_backwards > 0) {
    note +=
        fmt::format("{}FORCE seq went back {} times (estimator restarted?)", note.empty() ? "" : "; ", f.seq_backwards);
  }
  if (c.truth_gaps() > 0) {
    note += fmt::format("{}{} TRUTH gaps (packets lost on the way to this monitor)", note.empty() ? "" : "; ",
                        c.truth_gaps());
  }
  if ((lost_forces > 0 || c.truth_gaps() > 0) && c.has_truth()) {
    note += "; the figures differ slightly from birotor-eval's";
  }
  return note;
}

}  // namespace birotor
