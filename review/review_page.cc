#include "review/review_page.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "plot/status_words.h"
#include "review/display_series.h"
#include "review/flight_headline.h"
#include "review/html_text.h"
#include "review/page_script.h"
#include "review/review_charts.h"
#include "samples/motor_command.h"

namespace birotor {
namespace {

std::string ChannelTable(const FlightData& d) {
  std::string out =
      "<table><tr><th>channel</th><th>messages</th><th>not decoded</th><th>first [s]</th><th>last [s]</th>"
      "<th>mean rate [Hz]</th></tr>\n";
  for (const auto& [name, c] : d.channels) {
    const double span_s = c.last_s - c.first_s;
    out += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{}</td></tr>\n",
                       EscapeHtml(name), c.messages, c.decode_errors, c.first_s, c.last_s,
                       span_s > 0 && c.messages > 1 ? fmt::format("{:.1f}", (c.messages - 1) / span_s) : "-");
  }
  out += "</table>\n";
  return out;
}

// Each FORCE bit's rises; an alarm bit that rose is highlighted, except the
// filter's start-up FILTER_RESET (set on its first estimate), which is not
// counted as a rise.
std::string RiseTable(const FlightData& d) {
  if (d.force.rows() == 0) return "<p>No FORCE in this log: no status bits.</p>\n";
  std::string out = "<table><tr><th>FORCE status bit</th><th>rises</th><th>first rise [s]</th></tr>\n";
  for (const ForceFlag& flag : ForceFlags(d)) {
    int64_t total = 0;
    std::vector<double> rises = BitRises(d.force, flag.column, flag.bit, 2, &total);
    const bool startup_reset = flag.column == d.ForceStatusColumn() && flag.bit == kStatusFilterReset &&
                               !rises.empty() && rises[0] == d.force.t_s[0];
    if (startup_reset) {
      rises.erase(rises.begin());
      --total;
    }
    out += fmt::format("<tr{}><td>{}{}{}</td><td>{}</td><td>{}</td></tr>\n",
                       flag.alarm && total > 0 ? " class=alarm" : "", flag.word, flag.alarm ? " (alarm)" : "",
                       startup_reset ? " (the start-up reset at t = 0 is not counted)" : "", total,
                       rises.empty() ? "-" : fmt::format("{:.3f}", rises[0]));
  }
  return out + "</table>\n";
}

// "0.200, 0.700" (", ..." when more than the listed ones): the fallbacks as
// the headline counts them (review/flight_headline.h).
std::string FallbackTimes(const FlightHeadline& h) {
  std::string times;
  int64_t listed = 0;
  for (const FlightEvent& e : h.events) {
    if (e.kind != "fallback") continue;
    times += fmt::format("{}{:.3f}", times.empty() ? "" : ", ", e.t_s);
    ++listed;
  }
  return listed < h.fallbacks ? times + ", ..." : times;
}

std::string ControllerSummary(const FlightData& d, const FlightHeadline& h) {
  if (d.motor_command.rows() == 0) return "<p>No MOTOR_COMMAND in this log: no controller flew.</p>\n";
  return fmt::format("<p>MOTOR_COMMAND: {} messages; fallbacks to the nominal law: {}{}{}.</p>\n",
                     d.motor_command.rows(), h.fallbacks, h.fallbacks > 0 ? " at t [s] = " : "", FallbackTimes(h));
}

// "x max |dev| ... rms ..." of columns x and z of table, from its first row.
std::string PositionHold(const Table& table, int x_column, int z_column, const char* source) {
  double max_dev[2] = {0.0, 0.0}, sum_sq[2] = {0.0, 0.0};
  const int columns[2] = {x_column, z_column};
  for (size_t row = 0; row < table.rows(); ++row) {
    for (int i = 0; i < 2; ++i) {
      const double dev = table.columns[columns[i]][row] - table.columns[columns[i]][0];
      max_dev[i] = std::max(max_dev[i], std::abs(dev));
      sum_sq[i] += dev * dev;
    }
  }
  const double n = static_cast<double>(table.rows());
  return fmt::format(
      "flight: position held ({}, from t = {:.3f} s): x max |dev| {:.4f} m, rms {:.4f} m; "
      "z max |dev| {:.4f} m, rms {:.4f} m\n",
      source, table.t_s[0], max_dev[0], std::sqrt(sum_sq[0] / n), max_dev[1], std::sqrt(sum_sq[1] / n));
}

std::string InputTable(const FlightData& d) {
  std::string out =
      "<table><tr><th>input</th><th>messages</th><th>mean rate [Hz]</th><th>longest gap [ms]</th>"
      "<th>at t [s]</th></tr>\n";
  for (int i = 0; i < kReviewRateInputs; ++i) {
    const std::vector<double>& t = d.input_t_s[i];
    if (t.empty()) continue;
    double gap = 0.0, at = 0.0;
    for (size_t n = 1; n < t.size(); ++n) {
      if (t[n] - t[n - 1] > gap) {
        gap = t[n] - t[n - 1];
        at = t[n - 1];
      }
    }
    const double span = t.back() - t.front();
    out +=
        fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.1f}</td><td>{:.3f}</td></tr>\n", kReviewInputNames[i],
                    t.size(), span > 0 ? fmt::format("{:.1f}", (t.size() - 1) / span) : "-", 1e3 * gap, at);
  }
  return out + "</table>\n";
}

}  // namespace

std::string FlightSummaryText(const FlightData& d) {
  std::string out = fmt::format("flight: {} events over {:.3f} s\n", d.events, d.duration_s);
  const FlightHeadline headline = ComputeHeadline(d);
  if (d.truth.rows() > 0) {
    out += PositionHold(d.truth, d.TruthXColumn(), d.TruthZColumn(), "TRUTH");
  } else if (d.pose.rows() > 0) {
    out += PositionHold(d.pose, 0, 1, "POSE");
  }
  if (!headline.verdict_source.empty()) {
    out += "flight: verdict: " + headline.verdict.Line() + " (" + headline.verdict_source + ")\n";
  }
  if (d.motor_command.rows() > 0) {
    int64_t force_feedback = 0;
    for (const double mode : d.motor_command.columns[d.CommandModeColumn()])
      force_feedback += mode == kModeForceFeedback ? 1 : 0;
    out += fmt::format("flight: {} MOTOR_COMMAND ({:.1f} % in force_feedback mode); {} fallbacks{}{}\n",
                       d.motor_command.rows(), 100.0 * force_feedback / d.motor_command.rows(), headline.fallbacks,
                       headline.fallbacks > 0 ? " at t [s] = " : "", FallbackTimes(headline));
  }
  if (d.controller_status.rows() > 0) {
    const Table& c = d.controller_status;
    out += fmt::format("flight: CONTROLLER_STATUS at the end: {:.0f} fallbacks, {:.0f} descents, {:.0f} saturated\n",
                       c.columns[0].back(), c.columns[1].back(), c.columns[2].back());
  }
  // "flight: headline: ..." so that readers of the "flight:" lines (tools/demo.sh, the
  // count parsers of the tests) need no change.
  std::istringstream in(HeadlineText(headline));
  for (std::string line; std::getline(in, line);) out += "flight: " + line + "\n";
  return out;
}

std::string ReviewPageHtml(const FlightData& data) { return ReviewPageHtml(std::vector<const FlightData*>{&data}); }

std::string ReviewPageHtml(const std::vector<const FlightData*>& logs) {
  std::vector<Table> rates;
  std::vector<FlightHeadline> headlines;
  for (const FlightData* d : logs) {
    rates.push_back(InputRatesAndGaps(*d, std::clamp(static_cast<int>(d->duration_s * 10.0), 10, 600)));
    headlines.push_back(ComputeHeadline(*d));
  }
  std::vector<ChartedLog> charted;
  for (size_t k = 0; k < logs.size(); ++k) charted.push_back({logs[k], &rates[k], &headlines[k]});
  const std::string json = ReviewJson(charted, ReviewCharts(charted));
  std::string html;
  html.reserve(json.size() + 200000);
  std::string title;
  for (const FlightData* d : logs) title += (title.empty() ? "" : " vs ") + EscapeHtml(d->path);
  html +=
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">\n<title>birotor review: " + title + "</title>\n<style>\n";
  html += kDygraphCss;
  html += kReviewPageStyle;
  html += "</style>\n<script>\n";
  html += kDygraphJs;
  html += "\n</script>\n</head><body>\n<h1>Flight review: " + title + "</h1>\n";
  html += HeadlineTableHtml(logs, headlines);
  for (const FlightData* d : logs) {
    html += fmt::format("<p class=note>{}: {} events, {:.3f} s; t = 0 at its first message (utime {}).</p>\n{}",
                        EscapeHtml(d->path), d->events, d->duration_s, d->t0_utime, MissingDataHtml(*d));
  }
  html +=
      "<p class=note>Drag to zoom, shift-drag to pan, double-click to zoom out; every chart follows. Lines: "
      "rotor faults red, the true fault dark red dashed, MODEL_MISMATCH blue, fallbacks orange, filter resets "
      "purple, the loss black. "
      "<button id=reset>whole flight</button> <button id=fit-all>fit every value</button></p>\n";
  html += "<div id=charts></div>\n<h2>Details</h2>\n";
  for (size_t k = 0; k < logs.size(); ++k) {
    const FlightData* d = logs[k];
    const std::string name = logs.size() > 1 ? " (" + EscapeHtml(d->path) + ")" : "";
    html += "<h3>Channels" + name + "</h3>\n" + ChannelTable(*d);
    html += "<h3>FORCE status bits" + name + "</h3>\n" + RiseTable(*d);
    html += "<h3>Inputs" + name + "</h3>\n" + InputTable(*d);
    html += "<h3>Controller" + name + "</h3>\n" + ControllerSummary(*d, headlines[k]);
  }
  html += "<pre id=review-summary></pre>\n<script>\nvar REVIEW = " + json + ";\n";
  html += kReviewPageScript;
  html += "</script>\n</body></html>\n";
  return html;
}

}  // namespace birotor
