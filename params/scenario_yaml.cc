#include "params/scenario_yaml.h"

#include <cmath>
#include <limits>

#include "numerics/time_units.h"
#include "params/birotor_params_yaml.h"
#include "params/controller_config_yaml.h"

namespace birotor {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxRateHz = 1e5;

// Sets the node at a dotted path to the YAML value text, creating mappings on the way.
void SetPath(YAML::Node node, const std::vector<std::string>& parts, size_t index, const YAML::Node& value,
             const std::string& label, const std::string& path) {
  if (!node.IsMap())
    throw ParamError(label + ": key " + Quoted(path) + ": --set reaches into a value that is not a mapping");
  if (index + 1 == parts.size()) {
    node[parts[index]] = value;
    return;
  }
  if (!node[parts[index]].IsDefined() || node[parts[index]].IsNull()) {
    node[parts[index]] = YAML::Node(YAML::NodeType::Map);
  }
  SetPath(node[parts[index]], parts, index + 1, value, label, path);
}

void ApplyOverride(YAML::Node root, const std::string& text, const std::string& label) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw ParamError(label + ": override " + Quoted(text) + ": expected section.key=value");
  const std::string path = text.substr(0, equals);
  std::vector<std::string> parts;
  size_t begin = 0;
  while (true) {
    const size_t dot = path.find('.', begin);
    parts.push_back(path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (parts.back().empty()) throw ParamError(label + ": override " + Quoted(text) + ": empty key in the path");
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  YAML::Node value;
  try {
    value = LoadYamlWithinBudget(text.substr(equals + 1), label + ": key " + Quoted(path));
  } catch (const YAML::Exception& e) {
    throw ParamError(label + ": key " + Quoted(path) + ": value is not valid YAML: " + Quoted(e.msg));
  }
  SetPath(root, parts, 0, value, label, path);
}

// A rate must give a whole number of steps per sample.
void ReadRate(YamlSection& s, const std::string& key, double step_s, double* rate_hz) {
  s.Double(key, 1e-3, kMaxRateHz, rate_hz);
  const double steps = 1.0 / (*rate_hz * step_s);
  if (steps < 1.0 - 1e-9 || std::fabs(steps - std::round(steps)) > 1e-6)
    s.Fail(key, "period is not a whole number of simulation steps of " + std::to_string(step_s) + " s",
           "1 / (n * step_s) for a whole n >= 1");
}

void ReadSensor(YamlSection& parent, const std::string& name, double step_s, SensorRate* rate,
                const std::vector<std::pair<std::string, double*>>& noises) {
  YamlSection s = parent.Section(name);
  s.Bool("enabled", &rate->enabled);
  ReadRate(s, "rate_hz", step_s, &rate->rate_hz);
  for (const auto& [key, value] : noises) s.Double(key, 0.0, kInf, value);
  s.Finish();
}

void ReadWindow(YamlSection& parent, const std::string& key, double duration_s, TimeWindow* window) {
  YamlSection s = parent.Section(key);
  s.Double("start_s", 0.0, duration_s, &window->start_s);
  s.Double("duration_s", 0.0, duration_s, &window->duration_s);
  s.Finish();
}

// One function per section of a scenario file, in file order; each reads
// into *out and checks the section's keys. The scenario: section comes
// first: the duration and the step bound the others' times.
void ReadScenarioSection(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  YamlSection scenario = root.Section("scenario");
  scenario.AnyString("name", &sc.name);
  scenario.String("mode", {"flight", "bench"}, &sc.mode);
  scenario.Double("duration_s", 1e-3, 1e6, &sc.duration_s);
  int64_t seed = static_cast<int64_t>(sc.seed);
  scenario.Int("seed", int64_t{0}, std::numeric_limits<int64_t>::max(), &seed);
  sc.seed = static_cast<uint64_t>(seed);
  scenario.Double("step_s", 1e-6, 0.01, &sc.step_s);
  if (!IsWholeMicroseconds(sc.step_s)) scenario.Fail("step_s", "not a whole number of microseconds", "k * 1e-6 s");
  const double steps = sc.duration_s / sc.step_s;
  if (std::fabs(steps - std::round(steps)) > 1e-6)
    scenario.Fail("duration_s", "not a whole number of steps of " + std::to_string(sc.step_s) + " s", "n * step_s");
  scenario.DoubleArray("start_position_m", 2, -1e4, 1e4, sc.start_position_m);
  scenario.Finish();
}

void ReadVehicle(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  // The birotor form's keys over the scenario's birotor (a scenario file
  // changes some of them).
  BirotorParams v = BirotorModelOf(sc.vehicle);
  ReadBirotorParams(root.Section("vehicle"), &v);
  sc.vehicle = BirotorDescription(v);
  // The vehicle's gauge_* keys are what an estimator believes; the true
  // gauge of a simulation is the gauge: section, so they must stay ideal here.
  const BirotorParams ideal;
  for (int i = 0; i < 2; ++i) {
    if (v.gauge_scale[i] != ideal.gauge_scale[i] || v.gauge_offset_rad[i] != ideal.gauge_offset_rad[i]) {
      root.Section("vehicle").Fail("gauge_scale", "the simulated gauge is set in the gauge: section",
                                   "gauge_scale [1, 1] and gauge_offset_rad [0, 0] here");
    }
  }
}

void ReadTrajectory(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  const double end_s = sc.duration_s;
  YamlSection trajectory = root.Section("trajectory");
  trajectory.String("kind", {"hold", "waypoints", "random_steps"}, &sc.trajectory.kind);
  double previous_end_s = 0.0;
  for (YamlSection w : trajectory.SectionList("waypoints")) {
    Waypoint waypoint;
    w.RequiredDouble("start_s", 0.0, end_s, &waypoint.start_s);
    w.RequiredDouble("duration_s", 1e-3, 1e6, &waypoint.duration_s);
    w.RequiredDouble("x_m", -1e4, 1e4, &waypoint.x_m);
    w.RequiredDouble("z_m", -1e4, 1e4, &waypoint.z_m);
    if (waypoint.start_s < previous_end_s - 1e-12)
      w.Fail("start_s", "starts before the previous move ends", "start_s >= " + std::to_string(previous_end_s));
    previous_end_s = waypoint.start_s + waypoint.duration_s;
    w.Finish();
    sc.trajectory.waypoints.push_back(waypoint);
  }
  YamlSection r = trajectory.Section("random_steps");
  RandomSteps& steps = sc.trajectory.random_steps;
  r.Double("interval_s", 1e-2, 1e4, &steps.interval_s);
  r.Double("max_step_m", 0.0, 100.0, &steps.max_step_m);
  r.Double("move_duration_s", 1e-2, 1e4, &steps.move_duration_s);
  r.Double("max_excursion_m", 0.0, 1e3, &steps.max_excursion_m);
  if (steps.move_duration_s > steps.interval_s) r.Fail("move_duration_s", "longer than interval_s", "(0, interval_s]");
  r.Finish();
  trajectory.Finish();
}

void ReadBench(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  YamlSection b = root.Section("bench");
  BenchProfile& bench = sc.bench;
  b.Double("omega_low_rad_s", 0.0, 1e5, &bench.omega_low_rad_s);
  b.Double("omega_high_rad_s", bench.omega_low_rad_s, 1e5, &bench.omega_high_rad_s);
  b.Double("segment_s", 1e-2, 1e5, &bench.segment_s);
  b.Double("step_hold_s", 1e-3, 1e5, &bench.step_hold_s);
  b.Double("chirp_start_hz", 0.0, 1e3, &bench.chirp_start_hz);
  b.Double("chirp_end_hz", 0.0, 1e3, &bench.chirp_end_hz);
  b.Finish();
}

void ReadSensors(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  YamlSection s = root.Section("sensors");
  SensorParams& sensors = sc.sensors;
  const double step = sc.step_s;
  {
    YamlSection g = s.Section("strain");
    g.Bool("enabled", &sensors.strain.enabled);
    ReadRate(g, "rate_hz", step, &sensors.strain.rate_hz);
    g.Double("noise_rad", 0.0, kInf, &sensors.strain_noise_rad);
    // Within a tenth of the sample period: a reading the stamp places in
    // another sample's slot is an out-of-order fault (faults:), not jitter.
    g.Double("stamp_jitter_s", 0.0, 0.1 / sensors.strain.rate_hz, &sensors.strain_stamp_jitter_s);
    g.Finish();
  }
  {
    YamlSection m = s.Section("motor");
    m.Bool("enabled", &sensors.motor.enabled);
    ReadRate(m, "rate_hz", step, &sensors.motor.rate_hz);
    m.Bool("telemetry", &sensors.motor_telemetry);
    m.Double("speed_noise_rad_s", 0.0, kInf, &sensors.motor_speed_noise_rad_s);
    m.Finish();
  }
  ReadSensor(s, "imu", step, &sensors.imu,
             {{"gyro_noise_rad_s", &sensors.gyro_noise_rad_s}, {"accel_noise_m_s2", &sensors.accel_noise_m_s2}});
  ReadSensor(
      s, "pose", step, &sensors.pose,
      {{"position_noise_m", &sensors.pose_position_noise_m}, {"angle_noise_rad", &sensors.pose_angle_noise_rad}});
  ReadSensor(s, "loadcell", step, &sensors.loadcell, {{"noise_n", &sensors.loadcell_noise_n}});
  ReadSensor(s, "truth", step, &sensors.truth, {});
  s.Finish();
}

// One number per arm: arm_count of them, or the two equal numbers of a
// complete scenario file written for the birotor, which every arm takes.
void ReadPerArm(YamlSection& s, const std::string& key, int arm_count, double min, double max, PerArm* values) {
  s.DoubleArray(key, arm_count, kBirotorArmCount, min, max, values->data());
}

void ReadGauge(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  const double end_s = sc.duration_s;
  const int n = sc.arm_count;
  YamlSection g = root.Section("gauge");
  GaugeParams& gauge = sc.gauge;
  ReadPerArm(g, "scale", n, 0.5, 2.0, &gauge.scale);
  ReadPerArm(g, "offset_rad", n, -0.01, 0.01, &gauge.offset_rad);
  ReadPerArm(g, "drift_rad_s", n, -1e-3, 1e-3, &gauge.drift_rad_s);
  ReadWindow(g, "drift_window", end_s, &gauge.drift_window);
  ReadPerArm(g, "harmonic_1x_rad", n, 0.0, 0.01, &gauge.harmonic_1x_rad);
  ReadPerArm(g, "harmonic_2x_rad", n, 0.0, 0.01, &gauge.harmonic_2x_rad);
  ReadPerArm(g, "harmonic_2x_phase_rad", n, -10.0, 10.0, &gauge.harmonic_2x_phase_rad);
  ReadPerArm(g, "rotor_angle_rad", n, -10.0, 10.0, &gauge.rotor_angle_rad);
  g.Finish();
}

void ReadGround(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  const double end_s = sc.duration_s;
  YamlSection g = root.Section("ground");
  GroundParams& ground = sc.ground;
  g.Bool("enabled", &ground.enabled);
  // The phase times must fit the scenario only when the phase is on: a
  // complete file keeps its defaults when it is off, whatever its duration.
  const double phase_end_s = ground.enabled ? end_s : 1e6;
  g.Double("rest_s", 0.0, phase_end_s, &ground.rest_s);
  g.Double("spool_up_s", 0.0, phase_end_s, &ground.spool_up_s);
  g.Double("idle_rad_s", 0.0, 1e5, &ground.idle_rad_s);
  g.Bool("land", &ground.land);
  g.Double("landing_duration_s", 1e-2, phase_end_s, &ground.landing_duration_s);
  g.Double("rest_after_s", 0.0, phase_end_s, &ground.rest_after_s);
  if (ground.enabled && sc.mode != "flight") g.Fail("enabled", "the ground phase needs mode flight", "false");
  const double flight_start_s = ground.FlightStartS();
  if (ground.enabled && flight_start_s >= end_s)
    g.Fail("rest_s", "rest_s + spool_up_s leaves no flight", "rest_s + spool_up_s < " + std::to_string(end_s));
  if (ground.enabled && ground.land && flight_start_s + ground.landing_duration_s + ground.rest_after_s > end_s) {
    g.Fail("landing_duration_s", "the landing does not fit after the ground phase",
           "rest_s + spool_up_s + landing_duration_s + rest_after_s <= " + std::to_string(end_s));
  }
  g.Finish();
}

void ReadFaults(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  const double end_s = sc.duration_s;
  YamlSection f = root.Section("faults");
  FaultParams& faults = sc.faults;
  ReadPerArm(f, "initial_thrust_scale", sc.arm_count, 0.0, 10.0, &faults.initial_thrust_scale);
  for (YamlSection t : f.SectionList("thrust_steps")) {
    ThrustStep step;
    t.RequiredDouble("time_s", 0.0, end_s, &step.time_s);
    t.Int("rotor", 1, sc.arm_count, &step.rotor);
    t.RequiredDouble("scale", 0.0, 10.0, &step.scale);
    t.Finish();
    faults.thrust_steps.push_back(step);
  }
  ReadWindow(f, "strain_gap", end_s, &faults.strain_gap);
  f.Double("strain_spike_probability", 0.0, 1.0, &faults.strain_spike_probability);
  f.Double("strain_spike_sigmas", 0.0, 1e6, &faults.strain_spike_sigmas);
  f.DoubleList("strain_nan_times_s", 0.0, end_s, &faults.strain_nan_times_s);
  f.DoubleList("strain_out_of_order_times_s", 0.0, end_s, &faults.strain_out_of_order_times_s);
  ReadWindow(f, "motor_telemetry_gap", end_s, &faults.motor_telemetry_gap);
  f.Finish();
}

void ReadController(YamlSection& root, Scenario* out) {
  Scenario& sc = *out;
  YamlSection c = root.Section("controller");
  ControllerParams& ctrl = sc.controller;
  ReadRate(c, "rate_hz", sc.step_s, &ctrl.rate_hz);
  ReadControllerGains(c, &ctrl);
  c.Finish();
}

// esc: the ESCs' commander rule (defaults: simulator/scenario.h EscParams).
void ReadEsc(YamlSection& root, Scenario* out) {
  YamlSection e = root.Section("esc");
  EscParams& esc = out->esc;
  e.Double("command_max_rate_hz", 1.0, 1e5, &esc.command_max_rate_hz);
  e.Double("rate_margin", 0.0, 10.0, &esc.rate_margin);
  e.Double("seq_slack", 0.0, 1000.0, &esc.seq_slack);
  e.Double("stamp_slack_s", 0.0, 10.0, &esc.stamp_slack_s);
  e.Double("conflict_hold_s", 0.0, 100.0, &esc.conflict_hold_s);
  e.Bool("follow_commander_in_conflict", &esc.follow_commander_in_conflict);
  e.Finish();
}

Scenario ReadScenario(YamlSection root, int arm_count) {
  Scenario sc;
  sc.file = root.file();
  sc.arm_count = arm_count;
  ReadScenarioSection(root, &sc);
  ReadVehicle(root, &sc);
  ReadTrajectory(root, &sc);
  ReadBench(root, &sc);
  ReadSensors(root, &sc);
  ReadGauge(root, &sc);
  ReadGround(root, &sc);
  ReadFaults(root, &sc);
  ReadController(root, &sc);
  ReadEsc(root, &sc);
  root.Finish();
  return sc;
}

void Flatten(const YAML::Node& node, const std::string& path, std::vector<std::string>* out) {
  if (node.IsMap() && node.size() > 0) {
    for (const auto& item : node) {
      const std::string key = item.first.Scalar();  // plain names only (LoadYamlMapping)
      Flatten(item.second, path.empty() ? key : path + "." + key, out);
    }
    return;
  }
  YAML::Emitter emitter;
  emitter.SetSeqFormat(YAML::Flow);
  emitter.SetMapFormat(YAML::Flow);
  emitter << node;
  out->push_back(path + "=" + emitter.c_str());
}

}  // namespace

std::vector<std::string> OverridesFromFile(const std::string& file) {
  std::vector<std::string> overrides;
  WithFileErrors(file, [&] { Flatten(LoadYamlMapping(file), "", &overrides); });
  return overrides;
}

Scenario LoadScenarioFromString(const std::string& text, const std::string& file_label,
                                const std::vector<std::string>& overrides, int arm_count) {
  if (arm_count < kBirotorArmCount || arm_count > kMaxArms) {
    throw ParamError(file_label + ": the vehicle has " + std::to_string(arm_count) +
                     " arms (allowed: " + RangeText(kBirotorArmCount, kMaxArms) + ")");
  }
  const std::string label = overrides.empty() ? file_label : file_label + " (with --set overrides)";
  Scenario scenario;
  WithFileErrors(label, [&] {
    YAML::Node root = ParseYamlMapping(text, file_label);
    for (const std::string& text_override : overrides) ApplyOverride(root, text_override, label);
    scenario = ReadScenario(YamlSection(label, root), arm_count);
  });
  scenario.file = file_label;
  return scenario;
}

Scenario LoadScenario(const std::string& file, const std::vector<std::string>& overrides, int arm_count) {
  return LoadScenarioFromString(ReadParameterFileText(file), file, overrides, arm_count);
}

}  // namespace birotor
