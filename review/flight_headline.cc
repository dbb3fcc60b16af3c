#include "review/flight_headline.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "review/display_series.h"
#include "review/html_text.h"
#include "samples/flight_figures.h"
#include "samples/motor_command.h"
#include "samples/samples.h"

namespace birotor {
namespace {

// The shared verdict on columns z and phi of track, against the newest
// SETPOINT altitude at each row (the first row's altitude before any), and
// the first time it said lost (-1: never). The log does not say where the
// ground is: no ground-hit test.
FlightVerdict VerdictOf(const Table& track, int z_column, int phi_column, const Table& setpoint, double* lost_at_s) {
  FlightJudge judge;
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  size_t next_setpoint = 0;
  double z_reference_m = kUnknown;
  *lost_at_s = -1.0;
  for (size_t row = 0; row < track.rows(); ++row) {
    while (next_setpoint < setpoint.rows() && setpoint.t_s[next_setpoint] <= track.t_s[row]) {
      z_reference_m = setpoint.columns[1][next_setpoint++];
    }
    judge.Add(track.t_s[row], track.columns[z_column][row], z_reference_m, track.columns[phi_column][row], kUnknown,
              kUnknown);
    if (*lost_at_s < 0 && judge.Result().lost) *lost_at_s = track.t_s[row];
  }
  return judge.Result();
}

// Rises of bit in column of table as events; returns their number.
int64_t AddRises(const Table& table, int column, int bit, const std::string& kind, const std::string& label,
                 std::vector<FlightEvent>* events) {
  int64_t total = 0;
  for (const double t : BitRises(table, column, bit, kMaxListedRises, &total)) events->push_back({t, kind, label});
  return total;
}

// Mean of column over rows with t in [from_s, to_s) (from row `first` on).
double MeanOver(const Table& table, const std::vector<double>& column, size_t first, double from_s, double to_s) {
  double sum = 0.0;
  int64_t n = 0;
  for (size_t row = first; row < table.rows() && table.t_s[row] < to_s; ++row) {
    if (table.t_s[row] >= from_s && std::isfinite(column[row])) {
      sum += column[row];
      ++n;
    }
  }
  return n > 0 ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

// The first time each rotor's true thrust scale leaves its level of the
// first kTrueFaultReferenceS (a mean: the turbulence moves it by ~1 %) by
// more than kTrueFaultScaleStep, with the mean over kTrueFaultReferenceS / 10
// from there as the new level.
void AddTrueFaults(const FlightData& d, std::vector<FlightEvent>* events) {
  const Table& truth = d.truth;
  if (truth.rows() == 0) return;
  for (int rotor = 0; rotor < d.rotor_count; ++rotor) {
    const std::vector<double>& scale = truth.columns[d.TruthScaleColumn(rotor)];
    const double level = MeanOver(truth, scale, 0, truth.t_s[0], truth.t_s[0] + kTrueFaultReferenceS);
    for (size_t row = 1; row < truth.rows(); ++row) {
      if (!(std::abs(scale[row] - level) > kTrueFaultScaleStep)) continue;
      const double t = truth.t_s[row];
      const double after = MeanOver(truth, scale, row, t, t + 0.1 * kTrueFaultReferenceS);
      events->push_back({t, "true fault", fmt::format("rotor {} thrust {:.2f} -> {:.2f}", rotor + 1, level, after)});
      break;
    }
  }
}

void AddForceFacts(const FlightData& d, FlightHeadline* h) {
  const Table& force = d.force;
  const int status_column = d.ForceStatusColumn();
  h->force_estimates = static_cast<int64_t>(force.rows());
  for (size_t row = 0; row < force.rows(); ++row) {
    if ((static_cast<int64_t>(force.columns[status_column][row]) & kStatusValid) == 0) continue;
    if (h->valid_estimates++ == 0) h->first_valid_s = force.t_s[row];
  }
  for (int rotor = 0; rotor < d.rotor_count; ++rotor) {
    h->rotor_fault_rises[rotor] = AddRises(force, d.ForceFaultColumn(), int32_t{1} << rotor, "fault",
                                           fmt::format("ROTOR{}_FAULT", rotor + 1), &h->events);
  }
  h->mismatch_rises = AddRises(force, status_column, kStatusModelMismatch, "mismatch", "MODEL_MISMATCH", &h->events);
  // The filter starts with FILTER_RESET set: not an alarm. A later rise is.
  std::vector<FlightEvent> resets;
  AddRises(force, status_column, kStatusFilterReset, "reset", "FILTER_RESET", &resets);
  for (const FlightEvent& reset : resets) {
    if (force.rows() > 0 && reset.t_s == force.t_s[0]) {
      h->startup_reset_s = reset.t_s;
    } else {
      h->events.push_back(reset);
    }
  }
}

// The fallback events, by the one rule of samples/flight_figures.h (the
// controller's: entries into FALLBACK_ACTIVE, the start counting as in the
// fallback, NO_POSE_YET commands skipped), in every mode: force feedback and
// mpc on FORCE alike: the count FlightFigures gives on the same MOTOR_COMMAND.
void AddFallbacks(const FlightData& d, FlightHeadline* h) {
  const Table& commands = d.motor_command;
  h->commands = static_cast<int64_t>(commands.rows());
  bool in_fallback = true;
  size_t listed = 0;
  for (size_t row = 0; row < commands.rows(); ++row) {
    const int32_t status = static_cast<int32_t>(commands.columns[d.CommandStatusColumn()][row]);
    const bool fallback = (status & kCommandFallbackActive) != 0;
    if ((status & kCommandNoPoseYet) == 0 && !fallback && h->force_used_s < 0 &&
        commands.columns[d.CommandModeColumn()][row] == kModeForceFeedback) {
      h->force_used_s = commands.t_s[row];
    }
    h->fallback_commands += fallback ? 1 : 0;
    if (!EntersFallback(status, &in_fallback)) continue;
    ++h->fallbacks;
    if (listed++ < kMaxListedRises) h->events.push_back({commands.t_s[row], "fallback", "fallback"});
  }
}

std::string Times(const std::vector<FlightEvent>& events, const std::string& kind, const std::string& label) {
  std::string out;
  for (const FlightEvent& e : events) {
    if (e.kind == kind && (label.empty() || e.label == label)) {
      out += fmt::format("{}{:.3f}", out.empty() ? "" : ", ", e.t_s);
    }
  }
  return out;
}

struct HeadlineRow {
  std::string question;
  std::string answer;
  bool alarm = false;
};

std::vector<HeadlineRow> Rows(const FlightHeadline& h) {
  std::vector<HeadlineRow> rows;
  const FlightVerdict& v = h.verdict;
  const bool judged = !h.verdict_source.empty() && v.samples > 0;
  std::string lost = "no position in this log";
  if (judged) lost = (v.lost ? fmt::format("yes, from {:.3f} s", h.lost_at_s) : "no") + " (" + h.verdict_source + ")";
  rows.push_back({"lost", lost, judged && v.lost});
  std::string faults;
  for (const FlightEvent& e : h.events) {
    if (e.kind == "fault" || e.kind == "true fault") {
      faults += fmt::format("{}{} at {:.3f} s{}", faults.empty() ? "" : "; ", e.label, e.t_s,
                            e.kind == "true fault" ? " (TRUTH)" : "");
    }
  }
  if (faults.empty()) faults = h.force_estimates > 0 ? "none" : "no FORCE in this log";
  rows.push_back({"rotor faults", faults, faults != "none" && h.force_estimates > 0});
  rows.push_back({"max tilt", judged ? fmt::format("{:.3f} rad ({:.1f} deg) at {:.3f} s", v.max_tilt_rad,
                                                   v.max_tilt_rad * 180.0 / M_PI, v.tilt_at_s)
                                     : "-"});
  rows.push_back({"altitude loss",
                  judged ? fmt::format("{:.3f} m at {:.3f} s", v.max_altitude_loss_m, v.altitude_loss_at_s) : "-"});
  std::string valid = "no FORCE in this log";
  if (h.force_estimates > 0) {
    valid = fmt::format("{:.1f} % ({} of {} estimates)", 100.0 * h.valid_estimates / h.force_estimates,
                        h.valid_estimates, h.force_estimates);
  }
  if (h.mismatch_rises > 0) valid += "; MODEL_MISMATCH at " + Times(h.events, "mismatch", "") + " s";
  const bool valid_alarm =
      h.force_estimates > 0 && (h.mismatch_rises > 0 || h.valid_estimates < kValidShareAlarm * h.force_estimates);
  rows.push_back({"FORCE VALID", valid, valid_alarm});
  std::string fallbacks = h.has_command ? std::to_string(h.fallbacks) : "no MOTOR_COMMAND in this log";
  if (h.fallbacks > 0) fallbacks += " at " + Times(h.events, "fallback", "") + " s";
  if (h.fallback_commands > 0) {
    fallbacks += fmt::format("; in the fallback in {:.1f} % of MOTOR_COMMAND",
                             100.0 * h.fallback_commands / static_cast<double>(h.commands));
  }
  if (h.force_used_s >= 0) fallbacks += fmt::format("; FORCE flown on from {:.3f} s", h.force_used_s);
  if (h.force_used_s < 0 && h.fallback_commands > 0) fallbacks += "; FORCE never flown on";
  if (h.figures.mpc_fallbacks > 0) fallbacks += fmt::format("; MPC fallback periods {}", h.figures.mpc_fallbacks);
  rows.push_back({"fallbacks", fallbacks});
  rows.push_back({"figures", h.has_truth ? h.figures.Line() : "no TRUTH in this log"});
  const std::string resets = Times(h.events, "reset", "");
  rows.push_back({"filter resets",
                  h.force_estimates == 0 ? "-"
                  : resets.empty()       ? "none after the start-up reset"
                                         : "at " + resets + " s",
                  !resets.empty()});
  return rows;
}

}  // namespace

FlightHeadline ComputeHeadline(const FlightData& d) {
  FlightHeadline h;
  if (d.truth.rows() > 0) {
    h.verdict = VerdictOf(d.truth, d.TruthZColumn(), d.TruthPhiColumn(), d.setpoint, &h.lost_at_s);
    h.verdict_source = "TRUTH";
  } else if (d.pose.rows() > 0) {
    h.verdict = VerdictOf(d.pose, 1, 2, d.setpoint, &h.lost_at_s);
    h.verdict_source = "POSE";
  }
  h.has_truth = d.truth.rows() > 0;
  h.has_command = d.motor_command.rows() > 0;
  AddForceFacts(d, &h);
  AddTrueFaults(d, &h.events);
  AddFallbacks(d, &h);
  h.figures = d.figures.Result();
  if (h.lost_at_s >= 0) h.events.push_back({h.lost_at_s, "lost", "lost"});
  std::stable_sort(h.events.begin(), h.events.end(),
                   [](const FlightEvent& a, const FlightEvent& b) { return a.t_s < b.t_s; });
  return h;
}

std::string HeadlineTableHtml(const std::vector<const FlightData*>& logs,
                              const std::vector<FlightHeadline>& headlines) {
  std::vector<std::vector<HeadlineRow>> columns;
  for (const FlightHeadline& h : headlines) columns.push_back(Rows(h));
  std::string out = "<table id=headline><tr><th></th>";
  for (size_t k = 0; k < logs.size(); ++k) {
    out += fmt::format("<th>{}{}</th>", logs.size() > 1 ? std::string(1, char('A' + k)) + ": " : "",
                       EscapeHtml(logs[k]->path));
  }
  out += "</tr>\n";
  for (size_t row = 0; row < columns[0].size(); ++row) {
    out += "<tr><th>" + columns[0][row].question + "</th>";
    for (const std::vector<HeadlineRow>& column : columns) {
      out += fmt::format("<td{}>{}</td>", column[row].alarm ? " class=alarm" : "", EscapeHtml(column[row].answer));
    }
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

std::string HeadlineText(const FlightHeadline& headline) {
  std::string out;
  for (const HeadlineRow& row : Rows(headline)) out += "headline: " + row.question + ": " + row.answer + "\n";
  return out;
}

}  // namespace birotor
