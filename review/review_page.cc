#include "review/review_page.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "plot/status_words.h"
#include "review/display_series.h"
#include "samples/flight_verdict.h"

namespace birotor {
namespace {

// Bits of motor_command_t.status (lcmtypes/motor_command_t.lcm), for lanes.
struct CommandBit {
  int bit;
  const char* word;
};
constexpr CommandBit kCommandBits[] = {
    {1, "FALLBACK_ACTIVE"}, {2, "INPUT_STALE"}, {4, "DESCENDING"}, {8, "SATURATED"}, {16, "NO_POSE_YET"}};
constexpr int kFallbackBit = 1;

std::string Escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// A JSON string that is also safe inside <script>.
std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '<') {
      out += "\\u003c";
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::vector<DisplayChart> Charts(const FlightData& d, const Table& rates) {
  const double T = d.duration_s;
  std::vector<DisplayChart> charts;
  charts.push_back(MakeChart("forces", "Rotor forces: estimate with its 1-sigma band, truth", "force [N]",
                             {{&d.force, 0, 2, 0, 0, "force 1 [N]"},
                              {&d.force, 1, 3, 0, 0, "force 2 [N]"},
                              {&d.truth, 0, -1, 0, 0, "true force 1 [N]"},
                              {&d.truth, 1, -1, 0, 0, "true force 2 [N]"}},
                             T));
  charts.push_back(MakeChart("thrust", "Thrust efficiency (actual / nominal c_T omega^2)", "thrust scale [1]",
                             {{&d.force, 4, -1, 0, 0, "thrust scale 1"},
                              {&d.force, 5, -1, 0, 0, "thrust scale 2"},
                              {&d.truth, 2, -1, 0, 0, "true thrust scale 1"},
                              {&d.truth, 3, -1, 0, 0, "true thrust scale 2"}},
                             T));
  std::vector<SeriesSpec> lanes;
  for (int i = 0; i < kStatusBitCount; ++i) {
    lanes.push_back({&d.force, 6, -1, kStatusBitNames[i].bit, double(i), kStatusBitNames[i].word});
  }
  charts.push_back(MakeChart("status", "FORCE status bits (a lane per bit; up = set)", "", lanes, T));
  std::vector<SeriesSpec> nis, fusion, rate_series, gap_series;
  for (int i = 0; i < kReviewInputs; ++i) {
    nis.push_back({&d.status, i, -1, 0, 0, d.status.labels[i]});
    fusion.push_back({&d.status, kReviewInputs + i, -1, 0, 0, d.status.labels[kReviewInputs + i]});
    fusion.push_back({&d.status, 2 * kReviewInputs + i, -1, 0, 0, d.status.labels[2 * kReviewInputs + i]});
  }
  for (int i = 0; i < kReviewRateInputs; ++i) {
    if (d.input_t_s[i].empty()) continue;
    rate_series.push_back({&rates, i, -1, 0, 0, rates.labels[i]});
    gap_series.push_back({&rates, kReviewRateInputs + i, -1, 0, 0, rates.labels[kReviewRateInputs + i]});
  }
  charts.push_back(MakeChart("nis", "Normalised innovation squared per input (ESTIMATOR_STATUS, mean per period)",
                             "NIS [1]", nis, T));
  charts.push_back(
      MakeChart("fusion", "Fused and rejected samples per input since start (ESTIMATOR_STATUS)", "samples", fusion, T));
  charts.push_back(MakeChart("rates", "Input rates (messages per second in each bucket)", "rate [Hz]", rate_series, T));
  charts.push_back(
      MakeChart("gaps", "Longest interval between two input messages in each bucket", "gap [ms]", gap_series, T));
  charts.push_back(MakeChart("position", "Position (POSE and truth)", "[m]",
                             {{&d.pose, 0, -1, 0, 0, "x [m]"},
                              {&d.pose, 1, -1, 0, 0, "z [m]"},
                              {&d.truth, 4, -1, 0, 0, "true x [m]"},
                              {&d.truth, 5, -1, 0, 0, "true z [m]"}},
                             T));
  charts.push_back(MakeChart(
      "commands", "Motor commands (MOTOR_COMMAND)", "omega [rad/s]",
      {{&d.motor_command, 0, -1, 0, 0, "omega cmd 1 [rad/s]"}, {&d.motor_command, 1, -1, 0, 0, "omega cmd 2 [rad/s]"}},
      T));
  std::vector<SeriesSpec> command_lanes;
  int lane = 0;
  for (const CommandBit& bit : kCommandBits) {
    command_lanes.push_back({&d.motor_command, 3, -1, bit.bit, double(lane++), bit.word});
  }
  command_lanes.push_back({&d.motor_command, 2, -1, 1, double(lane), "FORCE_FEEDBACK mode"});
  charts.push_back(
      MakeChart("controller_lanes", "Controller mode and status bits (MOTOR_COMMAND)", "", command_lanes, T));
  charts.push_back(MakeChart("controller_counts", "Controller counters since start (CONTROLLER_STATUS)", "count",
                             {{&d.controller_status, 0, -1, 0, 0, "fallbacks"},
                              {&d.controller_status, 1, -1, 0, 0, "descents"},
                              {&d.controller_status, 2, -1, 0, 0, "saturated"}},
                             T));
  // Rates and gaps are drawn per bucket but come from every input message.
  int64_t input_messages = 0;
  for (const std::vector<double>& t : d.input_t_s) input_messages += static_cast<int64_t>(t.size());
  for (DisplayChart& chart : charts) {
    if (chart.id == "rates" || chart.id == "gaps") chart.samples = input_messages;
  }
  charts.erase(std::remove_if(charts.begin(), charts.end(), [](const DisplayChart& c) { return c.rows == 0; }),
               charts.end());
  return charts;
}

std::string ChannelTable(const FlightData& d) {
  std::string out =
      "<table><tr><th>channel</th><th>messages</th><th>not decoded</th><th>first [s]</th><th>last [s]</th>"
      "<th>mean rate [Hz]</th></tr>\n";
  for (const auto& [name, c] : d.channels) {
    const double span_s = c.last_s - c.first_s;
    out += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{}</td></tr>\n",
                       Escape(name), c.messages, c.decode_errors, c.first_s, c.last_s,
                       span_s > 0 && c.messages > 1 ? fmt::format("{:.1f}", (c.messages - 1) / span_s) : "-");
  }
  out += "</table>\n";
  for (const auto& [name, c] : d.channels) {
    if (name.size() >= 8 && name.compare(name.size() - 8, 8, "SETPOINT") == 0) {
      out += fmt::format("<p>{}: {} messages; this build of birotor-review does not draw SETPOINT.</p>\n", Escape(name),
                         c.messages);
    }
  }
  return out;
}

std::string RiseTable(const FlightData& d) {
  std::string out = "<table><tr><th>FORCE status bit</th><th>rises</th><th>first rise [s]</th></tr>\n";
  for (int i = 0; i < kStatusBitCount; ++i) {
    int64_t total = 0;
    const std::vector<double> rises = BitRises(d.force, 6, kStatusBitNames[i].bit, 1, &total);
    const bool alarm = (kAlarmStatusBits & kStatusBitNames[i].bit) != 0;
    out += fmt::format("<tr{}><td>{}{}</td><td>{}</td><td>{}</td></tr>\n", alarm && total > 0 ? " class=alarm" : "",
                       kStatusBitNames[i].word, alarm ? " (alarm)" : "", total,
                       rises.empty() ? "-" : fmt::format("{:.3f}", rises[0]));
  }
  return out + "</table>\n";
}

std::string ControllerSummary(const FlightData& d) {
  if (d.motor_command.rows() == 0) return "<p>No MOTOR_COMMAND in this log: no controller flew.</p>\n";
  int64_t total = 0;
  const std::vector<double> rises = BitRises(d.motor_command, 3, kFallbackBit, 20, &total);
  std::string times;
  for (const double t : rises) times += fmt::format("{}{:.3f}", times.empty() ? "" : ", ", t);
  if (static_cast<int64_t>(rises.size()) < total) times += ", ...";
  return fmt::format("<p>MOTOR_COMMAND: {} messages; fallbacks to the nominal law: {}{}{}.</p>\n",
                     d.motor_command.rows(), total, total > 0 ? " at t [s] = " : "", times);
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

constexpr const char* kPageScript = R"JS(
var graphs = [], syncing = false, errors = [];
window.addEventListener('error', function (e) { errors.push(String(e.message)); });
function syncRange(me, initial) {
  if (initial || syncing) return;
  syncing = true;
  var range = me.xAxisRange();
  graphs.forEach(function (g) {
    if (g === me) return;
    var r = g.xAxisRange();
    if (r[0] !== range[0] || r[1] !== range[1]) g.updateOptions({dateWindow: range});
  });
  syncing = false;
}
function laneTicker(names) {
  return function () { return names.map(function (n, i) { return {v: i + 0.4, label: n}; }); };
}
REVIEW.charts.forEach(function (c) {
  var box = document.createElement('div');
  box.className = 'chart';
  box.innerHTML = '<h3></h3><div class=plot></div><p class=note></p>';
  box.querySelector('h3').textContent = c.title;
  box.querySelector('.note').textContent = c.samples + ' log samples, drawn as ' + c.rows +
      ' rows (min and max per bucket)';
  document.getElementById('charts').appendChild(box);
  var options = {labels: c.labels, ylabel: c.ylabel, xlabel: 't [s]', customBars: c.bands,
                 connectSeparatedPoints: true, legend: 'always', labelsSeparateLines: false,
                 drawCallback: syncRange, animatedZooms: false};
  if (c.lanes) {
    options.stepPlot = true;
    options.valueRange = [-0.2, c.labels.length - 1 + 0.2];
    options.axes = {y: {ticker: laneTicker(c.labels.slice(1)), axisLabelWidth: 140}};
    options.legend = 'onmouseover';
  }
  var g = new Dygraph(box.querySelector('.plot'), c.data, options);
  g.reviewChart = c;
  graphs.push(g);
});
document.getElementById('reset').onclick = function () {
  graphs.forEach(function (g) { g.updateOptions({dateWindow: null}); });
};
document.getElementById('review-summary').textContent = JSON.stringify({
  charts: graphs.map(function (g) {
    return {id: g.reviewChart.id, samples: g.reviewChart.samples, rows: g.numRows()};
  }),
  errors: errors});
)JS";

constexpr const char* kPageStyle = R"CSS(
body { font-family: sans-serif; margin: 1em 2em; }
.chart .plot { width: 100%; height: 260px; }
.chart h3 { margin: 1.2em 0 0.2em 0; font-size: 1em; }
.note { color: #666; font-size: 0.8em; margin: 0.2em 0; }
table { border-collapse: collapse; margin: 0.5em 0; }
td, th { border: 1px solid #ccc; padding: 2px 8px; text-align: right; }
td:first-child { text-align: left; }
tr.alarm td { background: #fdd; }
#verdict.lost { background: #fdd; padding: 4px; }
#review-summary { display: none; }
)CSS";

}  // namespace

// The shared verdict (samples/flight_verdict.h) on columns z and phi of track,
// against the newest SETPOINT altitude at each row (the first row's altitude
// before any). The log does not say where the ground is: no ground-hit test.
FlightVerdict VerdictOf(const Table& track, int z_column, int phi_column, const Table& setpoint) {
  FlightJudge judge;
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  size_t next_setpoint = 0;
  double z_reference_m = kUnknown;
  for (size_t row = 0; row < track.rows(); ++row) {
    while (next_setpoint < setpoint.rows() && setpoint.t_s[next_setpoint] <= track.t_s[row]) {
      z_reference_m = setpoint.columns[1][next_setpoint++];
    }
    judge.Add(track.t_s[row], track.columns[z_column][row], z_reference_m, track.columns[phi_column][row], kUnknown,
              kUnknown);
  }
  return judge.Result();
}

// The verdict in the page's first lines: TRUTH where the log has it, else POSE.
std::string VerdictParagraph(const FlightData& d) {
  if (d.truth.rows() == 0 && d.pose.rows() == 0) return "<p id=verdict>Verdict: no position in this log.</p>\n";
  const FlightVerdict v =
      d.truth.rows() > 0 ? VerdictOf(d.truth, 5, 6, d.setpoint) : VerdictOf(d.pose, 1, 2, d.setpoint);
  return fmt::format("<p id=verdict class={}><b>Verdict:</b> {} ({})</p>\n", v.lost ? "lost" : "kept", Escape(v.Line()),
                     d.truth.rows() > 0 ? "TRUTH" : "POSE");
}

std::string FlightSummaryText(const FlightData& d) {
  std::string out = fmt::format("flight: {} events over {:.3f} s\n", d.events, d.duration_s);
  if (d.truth.rows() > 0) {
    out += PositionHold(d.truth, 4, 5, "TRUTH");
    out += "flight: verdict: " + VerdictOf(d.truth, 5, 6, d.setpoint).Line() + " (TRUTH)\n";
  } else if (d.pose.rows() > 0) {
    out += PositionHold(d.pose, 0, 1, "POSE");
    out += "flight: verdict: " + VerdictOf(d.pose, 1, 2, d.setpoint).Line() + " (POSE)\n";
  }
  if (d.motor_command.rows() > 0) {
    int64_t fallbacks = 0;
    const std::vector<double> at = BitRises(d.motor_command, 3, kFallbackBit, 20, &fallbacks);
    int64_t force_feedback = 0;
    for (const double mode : d.motor_command.columns[2]) force_feedback += mode == 1.0 ? 1 : 0;
    std::string times;
    for (const double t : at) times += fmt::format("{}{:.3f}", times.empty() ? "" : ", ", t);
    if (static_cast<int64_t>(at.size()) < fallbacks) times += ", ...";
    out += fmt::format("flight: {} MOTOR_COMMAND ({:.1f} % in force_feedback mode); {} fallbacks{}{}\n",
                       d.motor_command.rows(), 100.0 * force_feedback / d.motor_command.rows(), fallbacks,
                       fallbacks > 0 ? " at t [s] = " : "", times);
  }
  if (d.controller_status.rows() > 0) {
    const Table& c = d.controller_status;
    out += fmt::format("flight: CONTROLLER_STATUS at the end: {:.0f} fallbacks, {:.0f} descents, {:.0f} saturated\n",
                       c.columns[0].back(), c.columns[1].back(), c.columns[2].back());
  }
  return out;
}

std::string ReviewPageHtml(const FlightData& d) {
  const Table rates = InputRatesAndGaps(d, std::clamp(static_cast<int>(d.duration_s * 10.0), 10, 600));
  const std::vector<DisplayChart> charts = Charts(d, rates);
  std::string json = "{\"charts\":[";
  for (size_t i = 0; i < charts.size(); ++i) {
    const DisplayChart& c = charts[i];
    std::string labels;
    for (const std::string& label : c.labels) labels += (labels.empty() ? "" : ",") + JsonString(label);
    json += fmt::format(
        "{}{{\"id\":{},\"title\":{},\"ylabel\":{},\"labels\":[{}],\"bands\":{},\"lanes\":{},\"samples\":{},"
        "\"rows\":{},\"data\":{}}}",
        i > 0 ? ",\n" : "", JsonString(c.id), JsonString(c.title), JsonString(c.y_label), labels, c.bands, c.lanes,
        c.samples, c.rows, c.rows_json);
  }
  json += "]}";
  std::string html;
  html.reserve(json.size() + 200000);
  html += "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">\n<title>birotor review: " + Escape(d.path) +
          "</title>\n<style>\n";
  html += kDygraphCss;
  html += kPageStyle;
  html += "</style>\n<script>\n";
  html += kDygraphJs;
  html += "\n</script>\n</head><body>\n";
  html += fmt::format(
      "<h1>Flight review</h1>\n<p>{}: {} events, {:.3f} s. t = 0 at the first message (utime {}). Drag to zoom, "
      "shift-drag to pan, double-click to zoom out; every chart follows. <button id=reset>whole flight</button></p>\n",
      Escape(d.path), d.events, d.duration_s, d.t0_utime);
  html += VerdictParagraph(d);
  html += "<h2>Channels</h2>\n" + ChannelTable(d);
  html += "<h2>Alarms</h2>\n" + RiseTable(d);
  html += "<h2>Inputs</h2>\n" + InputTable(d);
  html += "<h2>Controller</h2>\n" + ControllerSummary(d);
  html += "<div id=charts></div>\n<pre id=review-summary></pre>\n<script>\nvar REVIEW = " + json + ";\n";
  html += kPageScript;
  html += "</script>\n</body></html>\n";
  return html;
}

}  // namespace birotor
