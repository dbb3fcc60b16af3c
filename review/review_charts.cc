#include "review/review_charts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "plot/status_words.h"
#include "samples/motor_command.h"

namespace birotor {
namespace {

// Colours per log and slot: [0], [1] the estimate (or measurement) of
// rotor / axis 1 and 2, [2], [3] their truth (dashed), [4], [5] the
// reference (dashed). Log B has other hues, so A and B never share a colour.
constexpr const char* kPalette[2][6] = {
    {"#1f77b4", "#d62728", "#000000", "#7f7f7f", "#2ca02c", "#8c564b"},
    {"#17becf", "#ff7f0e", "#9467bd", "#bcbd22", "#e377c2", "#393b79"},
};
// Rotors 3 to 6 (vehicles with more arms): estimate and truth hues per log.
constexpr const char* kMoreRotors[2][2][kMaxArms - kBirotorRotors] = {
    {{"#2ca02c", "#9467bd", "#e377c2", "#bcbd22"}, {"#98df8a", "#c5b0d5", "#f7b6d2", "#dbdb8d"}},
    {{"#8c564b", "#393b79", "#637939", "#843c39"}, {"#c49c94", "#9c9ede", "#b5cf6b", "#d6616b"}},
};

struct CommandBit {
  int bit;
  const char* word;
};
constexpr CommandBit kCommandBits[] = {{kCommandFallbackActive, "FALLBACK_ACTIVE"},
                                       {kCommandInputStale, "INPUT_STALE"},
                                       {kCommandDescending, "DESCENDING"},
                                       {kCommandSaturated, "SATURATED"},
                                       {kCommandNoPoseYet, "NO_POSE_YET"}};

// Builds one log's series for each chart: labels prefixed, colours by slot.
class LogSeries {
 public:
  LogSeries(const ChartedLog& log, int index, bool overlay)
      : d_(*log.data),
        rates_(*log.rates),
        index_(index),
        prefix_(overlay ? std::string(1, char('A' + index)) + ": " : "") {}

  SeriesSpec Of(const Table& table, int column, const std::string& label, int slot, int sigma_column = -1) const {
    return With(table, column, label, kPalette[index_][slot], slot >= 2, sigma_column);
  }
  SeriesSpec With(const Table& table, int column, const std::string& label, const char* color, bool dashed,
                  int sigma_column = -1) const {
    SeriesSpec spec{&table, column, sigma_column, 0, 0.0, prefix_ + label, color, dashed, -1};
    if (&table == &d_.force) spec.converging_column = d_.ForceStatusColumn();
    return spec;
  }
  // Rotor i's colour: the palette's slots 0/1 (estimate) and 2/3 (truth)
  // for rotors 1 and 2, kMoreRotors beyond.
  const char* RotorColor(int rotor, bool truth) const {
    if (rotor < kBirotorRotors) return kPalette[index_][rotor + (truth ? 2 : 0)];
    return kMoreRotors[index_][truth ? 1 : 0][rotor - kBirotorRotors];
  }
  // Per rotor: the estimate's column (with its sigma band) then the truth's.
  std::vector<SeriesSpec> PerRotor(const char* name, int (FlightData::*estimate)(int) const,
                                   int (FlightData::*truth)(int) const, bool band) const {
    std::vector<SeriesSpec> out;
    const int n = d_.rotor_count;
    for (int i = 0; i < n; ++i) {
      out.push_back(With(d_.force, (d_.*estimate)(i), fmt::format("{} {}", name, i + 1), RotorColor(i, false), false,
                         band ? d_.ForceSigmaColumn(i) : -1));
    }
    for (int i = 0; i < n; ++i) {
      out.push_back(With(d_.truth, (d_.*truth)(i), fmt::format("true {} {}", name, i + 1), RotorColor(i, true), true));
    }
    return out;
  }
  std::vector<SeriesSpec> Forces() const {
    std::vector<SeriesSpec> out = PerRotor("force", &FlightData::ForceColumn, &FlightData::TruthForceColumn, true);
    for (SeriesSpec& spec : out) spec.label += " [N]";
    return out;
  }
  std::vector<SeriesSpec> Thrust() const {
    return PerRotor("thrust scale", &FlightData::ForceScaleColumn, &FlightData::TruthScaleColumn, false);
  }
  std::vector<SeriesSpec> Position() const {
    return {Of(d_.pose, 0, "x [m]", 0),
            Of(d_.pose, 1, "z [m]", 1),
            Of(d_.truth, d_.TruthXColumn(), "true x [m]", 2),
            Of(d_.truth, d_.TruthZColumn(), "true z [m]", 3),
            Of(d_.setpoint, 0, "x ref [m]", 4),
            Of(d_.setpoint, 1, "z ref [m]", 5)};
  }
  std::vector<SeriesSpec> Attitude() const {
    return {Of(d_.pose, 2, "pitch (POSE) [rad]", 0), Of(d_.truth, d_.TruthPhiColumn(), "true pitch [rad]", 2)};
  }
  std::vector<SeriesSpec> PitchRate() const { return {Of(d_.imu, 0, "pitch rate (IMU gyro) [rad/s]", 0)}; }
  std::vector<SeriesSpec> StatusColumns(int first) const {  // NIS (0), fused and rejected (kReviewInputs, ...)
    std::vector<SeriesSpec> out;
    for (int i = 0; i < kReviewInputs; ++i) {
      out.push_back(Of(d_.status, first + i, d_.status.labels[first + i], 0));
      out.back().color.clear();  // five inputs: dygraphs' own hues
    }
    return out;
  }
  std::vector<SeriesSpec> Rates(int first) const {  // rates (0) or gaps (kReviewRateInputs)
    std::vector<SeriesSpec> out;
    for (int i = 0; i < kReviewRateInputs; ++i) {
      if (d_.input_t_s[i].empty()) continue;
      out.push_back(Of(rates_, first + i, rates_.labels[first + i], 0));
      out.back().color.clear();
    }
    return out;
  }
  std::vector<SeriesSpec> Commands() const {
    std::vector<SeriesSpec> out;
    for (int i = 0; i < d_.rotor_count; ++i) {
      out.push_back(With(d_.motor_command, d_.CommandColumn(i), fmt::format("omega cmd {} [rad/s]", i + 1),
                         RotorColor(i, false), false));
    }
    return out;
  }
  std::vector<SeriesSpec> Counters() const {
    return {Of(d_.controller_status, 0, "fallbacks", 0), Of(d_.controller_status, 1, "descents", 1),
            Of(d_.controller_status, 2, "saturated", 4)};
  }
  static SeriesSpec Lane(const Table& table, int column, int bit, int lane, const std::string& label) {
    return SeriesSpec{&table, column, -1, bit, double(lane), label, "", false, -1};
  }
  // Lanes: a bit per lane, drawn as a band filled from the lane's base.
  std::vector<SeriesSpec> StatusLanes() const {
    std::vector<SeriesSpec> lanes;
    for (const ForceFlag& flag : ForceFlags(d_)) {
      lanes.push_back(Lane(d_.force, flag.column, flag.bit, static_cast<int>(lanes.size()), flag.word));
    }
    return lanes;
  }
  std::vector<SeriesSpec> CommandLanes() const {
    std::vector<SeriesSpec> lanes;
    int lane = 0;
    for (const CommandBit& bit : kCommandBits) {
      lanes.push_back(Lane(d_.motor_command, d_.CommandStatusColumn(), bit.bit, lane++, bit.word));
    }
    lanes.push_back(Lane(d_.motor_command, d_.CommandModeColumn(), 1, lane, "FORCE_FEEDBACK mode"));
    return lanes;
  }
  std::string Suffix() const { return prefix_.empty() ? "" : " (" + prefix_.substr(0, 1) + ")"; }
  std::string IdSuffix() const { return index_ == 0 ? "" : "_" + prefix_.substr(0, 1); }

 private:
  const FlightData& d_;
  const Table& rates_;
  int index_;
  std::string prefix_;
};

using SeriesOf = std::vector<SeriesSpec> (LogSeries::*)() const;

struct ChartBuilder {
  std::vector<LogSeries> logs;
  double duration_s = 0.0;
  std::vector<DisplayChart> charts;

  // One chart overlaying every log's series.
  void Overlay(const std::string& id, const std::string& title, const std::string& y_label, SeriesOf of) {
    std::vector<SeriesSpec> series;
    for (const LogSeries& log : logs) {
      for (SeriesSpec& spec : (log.*of)()) series.push_back(std::move(spec));
    }
    Add(id, title, y_label, series);
  }
  void Add(const std::string& id, const std::string& title, const std::string& y_label,
           const std::vector<SeriesSpec>& series) {
    DisplayChart chart = MakeChart(id, title, y_label, series, duration_s);
    SetRobustYRange(series, &chart);
    if (chart.rows > 0) charts.push_back(std::move(chart));
  }
};

}  // namespace

std::vector<DisplayChart> ReviewCharts(const std::vector<ChartedLog>& logs) {
  ChartBuilder b;
  for (size_t k = 0; k < logs.size(); ++k) {
    b.logs.emplace_back(logs[k], static_cast<int>(k), logs.size() > 1);
    b.duration_s = std::max(b.duration_s, logs[k].data->duration_s);
  }
  b.Overlay("forces", "Rotor forces: estimate (solid) with its 1-sigma band, truth (dashed)", "force [N]",
            &LogSeries::Forces);
  b.Overlay("position", "Position: POSE (solid), truth and SETPOINT reference (dashed)", "[m]", &LogSeries::Position);
  b.Overlay("attitude", "Attitude: pitch from POSE (solid) and truth (dashed)", "pitch [rad]", &LogSeries::Attitude);
  for (const LogSeries& log : b.logs) {
    b.Add("status" + log.IdSuffix(), "FORCE status bits" + log.Suffix() + " (a lane per bit; filled = set)", "",
          log.StatusLanes());
  }
  b.Overlay("thrust", "Thrust efficiency (actual / nominal c_T omega^2): estimate (solid), truth (dashed)",
            "thrust scale [1]", &LogSeries::Thrust);
  b.Overlay("pitch_rate", "Pitch rate (IMU gyro_y)", "rate [rad/s]", &LogSeries::PitchRate);
  std::vector<SeriesSpec> nis, fusion, rates, gaps;
  for (const LogSeries& log : b.logs) {
    for (SeriesSpec& s : log.StatusColumns(0)) nis.push_back(s);
    for (SeriesSpec& s : log.StatusColumns(kReviewInputs)) fusion.push_back(s);
    for (SeriesSpec& s : log.StatusColumns(2 * kReviewInputs)) fusion.push_back(s);
    for (SeriesSpec& s : log.Rates(0)) rates.push_back(s);
    for (SeriesSpec& s : log.Rates(kReviewRateInputs)) gaps.push_back(s);
  }
  b.Add("nis", "Normalised innovation squared per input (ESTIMATOR_STATUS, mean per period)", "NIS [1]", nis);
  b.Add("fusion", "Fused and rejected samples per input since start (ESTIMATOR_STATUS)", "samples", fusion);
  b.Add("rates", "Input rates (messages per second in each bucket)", "rate [Hz]", rates);
  b.Add("gaps", "Longest interval between two input messages in each bucket", "gap [ms]", gaps);
  b.Overlay("commands", "Motor commands (MOTOR_COMMAND)", "omega [rad/s]", &LogSeries::Commands);
  for (const LogSeries& log : b.logs) {
    b.Add("controller_lanes" + log.IdSuffix(),
          "Controller mode and status bits (MOTOR_COMMAND)" + log.Suffix() + "; filled = set", "", log.CommandLanes());
  }
  b.Overlay("controller_counts", "Controller counters since start (CONTROLLER_STATUS)", "count", &LogSeries::Counters);
  // Rates and gaps are drawn per bucket but come from every input message.
  int64_t input_messages = 0;
  for (const ChartedLog& log : logs) {
    for (const std::vector<double>& t : log.data->input_t_s) input_messages += static_cast<int64_t>(t.size());
  }
  for (DisplayChart& chart : b.charts) {
    if (chart.id == "rates" || chart.id == "gaps") chart.samples = input_messages;
  }
  return b.charts;
}

namespace {

// A JSON string that is also safe inside <script>; control characters as \u00XX.
std::string JsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '<') {
      out += "\\u003c";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += fmt::format("\\u{:04x}", static_cast<int>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string JsonNumber(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "null"; }

std::string JsonStrings(const std::vector<std::string>& texts) {
  std::string out;
  for (const std::string& text : texts) out += (out.empty() ? "" : ",") + JsonString(text);
  return "[" + out + "]";
}

std::string ChartJson(const DisplayChart& c) {
  return fmt::format(
      "{{\"id\":{},\"title\":{},\"ylabel\":{},\"labels\":{},\"colors\":{},\"dashed\":{},\"bands\":{},\"lanes\":{},"
      "\"yrange\":{},\"outside\":{},\"samples\":{},\"rows\":{},\"data\":{}}}",
      JsonString(c.id), JsonString(c.title), JsonString(c.y_label), JsonStrings(c.labels), JsonStrings(c.colors),
      JsonStrings(c.dashed), c.bands, c.lanes,
      c.has_y_range ? "[" + JsonNumber(c.y_low) + "," + JsonNumber(c.y_high) + "]" : "null", c.outside_y_range,
      c.samples, c.rows, c.rows_json);
}

// Columns x and z of table as [[x, z], ...], at most kMaxPathPoints.
std::string PathPoints(const Table& table, int x_column, int z_column) {
  const size_t stride = std::max<size_t>(1, (table.rows() + kMaxPathPoints - 1) / kMaxPathPoints);
  std::string out;
  for (size_t row = 0; row < table.rows(); row += stride) {
    out += fmt::format("{}[{},{}]", out.empty() ? "" : ",", JsonNumber(table.columns[x_column][row]),
                       JsonNumber(table.columns[z_column][row]));
  }
  return "[" + out + "]";
}

// Where the vehicle was at each event: the first row of track at or after it.
std::string PathMarks(const Table& track, int x_column, int z_column, const FlightHeadline& headline,
                      const std::string& prefix) {
  std::string out;
  for (const FlightEvent& e : headline.events) {
    const auto it = std::lower_bound(track.t_s.begin(), track.t_s.end(), e.t_s);
    if (it == track.t_s.end()) continue;
    const size_t row = static_cast<size_t>(it - track.t_s.begin());
    out += fmt::format("{}{{\"x\":{},\"z\":{},\"kind\":{},\"label\":{}}}", out.empty() ? "" : ",",
                       JsonNumber(track.columns[x_column][row]), JsonNumber(track.columns[z_column][row]),
                       JsonString(e.kind), JsonString(prefix + e.label));
  }
  return out;
}

std::string PathsJson(const std::vector<ChartedLog>& logs) {
  std::string paths, marks;
  auto add = [&paths](const std::string& label, const char* color, bool dashed, const std::string& points) {
    paths += fmt::format("{}{{\"label\":{},\"color\":\"{}\",\"dashed\":{},\"points\":{}}}", paths.empty() ? "" : ",",
                         JsonString(label), color, dashed, points);
  };
  for (size_t k = 0; k < logs.size(); ++k) {
    const FlightData& d = *logs[k].data;
    const std::string prefix = logs.size() > 1 ? std::string(1, char('A' + k)) + ": " : "";
    if (d.pose.rows() > 0) add(prefix + "POSE", kPalette[k][0], false, PathPoints(d.pose, 0, 1));
    if (d.truth.rows() > 0) {
      add(prefix + "truth", kPalette[k][2], true, PathPoints(d.truth, d.TruthXColumn(), d.TruthZColumn()));
    }
    if (d.setpoint.rows() > 0) add(prefix + "SETPOINT", kPalette[k][4], true, PathPoints(d.setpoint, 0, 1));
    const bool truth = d.truth.rows() > 0;
    const std::string m = PathMarks(truth ? d.truth : d.pose, truth ? d.TruthXColumn() : 0,
                                    truth ? d.TruthZColumn() : 1, *logs[k].headline, prefix);
    if (!m.empty()) marks += (marks.empty() ? "" : ",") + m;
  }
  return "{\"lines\":[" + paths + "],\"marks\":[" + marks + "]}";
}

std::string EventsJson(const std::vector<ChartedLog>& logs) {
  std::string out;
  for (size_t k = 0; k < logs.size(); ++k) {
    const std::string prefix = logs.size() > 1 ? std::string(1, char('A' + k)) + ": " : "";
    for (const FlightEvent& e : logs[k].headline->events) {
      out += fmt::format("{}{{\"t\":{},\"kind\":{},\"label\":{}}}", out.empty() ? "" : ",", JsonNumber(e.t_s),
                         JsonString(e.kind), JsonString(prefix + e.label));
    }
  }
  return "[" + out + "]";
}

}  // namespace

std::string ReviewJson(const std::vector<ChartedLog>& logs, const std::vector<DisplayChart>& charts) {
  std::string json = "{\"charts\":[";
  for (size_t i = 0; i < charts.size(); ++i) json += (i > 0 ? ",\n" : "") + ChartJson(charts[i]);
  return json + "],\n\"path\":" + PathsJson(logs) + ",\n\"events\":" + EventsJson(logs) + "}";
}

std::string MissingDataHtml(const FlightData& d) {
  std::string out;
  auto say = [&out](const std::string& sentence) { out += "<li>" + sentence + "</li>\n"; };
  if (d.force.rows() == 0) {
    say("No FORCE: this log holds no force estimate (a birotor-sim --output log without --controller has the "
        "sensors and the truth only; birotor-replay --log on it writes one with FORCE). No estimate, status-bit "
        "lanes, alarm table or VALID share.");
  }
  if (d.truth.rows() == 0) {
    say("No TRUTH: a real flight (or a log without the simulator's truth): no true forces; the verdict is "
        "judged on POSE.");
  }
  if (d.pose.rows() == 0 && d.truth.rows() == 0) say("No POSE and no TRUTH: no position, attitude, path or verdict.");
  if (d.setpoint.rows() == 0) {
    say("No SETPOINT: the reference is not known; the altitude loss is measured from the first altitude.");
  }
  if (d.status.rows() == 0) {
    say("No ESTIMATOR_STATUS: no NIS or fusion counts (birotor-replay's output and the live estimator's "
        "recording have them).");
  }
  if (d.motor_command.rows() == 0) say("No MOTOR_COMMAND: no controller flew in this log; no commands or fallbacks.");
  if (d.imu.rows() == 0) say("No IMU: no pitch rate.");
  return out.empty() ? "" : "<ul id=missing>\n" + out + "</ul>\n";
}

}  // namespace birotor
