#include "params/controller_config_yaml.h"

#include "params/option_table.h"
#include "params/vehicle_params_yaml.h"

namespace birotor {
namespace {

// The keys of controller.observer and controller.supervision (defaults:
// controller/controller_params.h).
const OptionTable<ObserverParams>& ObserverKeys() {
  using O = ObserverParams;
  static const OptionTable<O> keys = {
      Real("position_bandwidth_rad_s", &O::position_bandwidth_rad_s, 0.1, 50.0),
      Real("attitude_crossover_rad_s", &O::attitude_crossover_rad_s, 0.01, 50.0),
  };
  return keys;
}

const OptionTable<SupervisionParams>& SupervisionKeys() {
  using O = SupervisionParams;
  static const OptionTable<O> keys = {
      Real("pose_timeout_s", &O::pose_timeout_s, 1e-3, 10.0),
      Real("imu_timeout_s", &O::imu_timeout_s, 1e-4, 10.0),
      Real("force_timeout_s", &O::force_timeout_s, 1e-4, 10.0),
      Real("force_recovery_s", &O::force_recovery_s, 0.0, 10.0),
      Real("min_thrust_scale", &O::min_thrust_scale, 0.05, 1.0),
      Real("max_thrust_scale", &O::max_thrust_scale, 1.0, 10.0),
      Real("descent_rate_m_s", &O::descent_rate_m_s, 0.0, 5.0),
  };
  return keys;
}

// The gain keys (every key of ControllerParams but rate_hz).
const OptionTable<ControllerParams>& GainKeys() {
  using O = ControllerParams;
  static const OptionTable<O> keys = {
      Real("position_kp_1_s2", &O::position_kp_1_s2, 0.0, 1e4),
      Real("position_kd_1_s", &O::position_kd_1_s, 0.0, 1e4),
      Real("position_ki_1_s3", &O::position_ki_1_s3, 0.0, 1e4),
      Real("attitude_kp_1_s2", &O::attitude_kp_1_s2, 0.0, 1e6),
      Real("attitude_kd_1_s", &O::attitude_kd_1_s, 0.0, 1e4),
      Real("attitude_ki_1_s3", &O::attitude_ki_1_s3, 0.0, 1e6),
      Real("max_tilt_rad", &O::max_tilt_rad, 1e-3, 1.5),
      Real("max_integral_m_s2", &O::max_integral_m_s2, 0.0, 100.0),
      Real("max_attitude_integral_rad_s2", &O::max_attitude_integral_rad_s2, 0.0, 1e4),
  };
  return keys;
}

ControllerConfig ReadRoot(YamlSection root) {
  ControllerConfig config;
  ReadVehicleParams(root.Section("vehicle"), &config.vehicle);
  YamlSection c = root.Section("controller");
  std::string mode;
  c.String("mode", {"nominal", "force_feedback"}, &mode);
  config.force_feedback = mode == "force_feedback";
  c.Double("rate_hz", 10.0, 1e4, &config.gains.rate_hz);
  {
    YamlSection gains = c.Section("gains");
    ReadControllerGains(gains, &config.gains);
    gains.Finish();
  }
  ReadOptionSection(c.Section("observer"), ObserverKeys(), &config.observer);
  ReadOptionSection(c.Section("supervision"), SupervisionKeys(), &config.supervision);
  c.Finish();
  root.Finish();
  return config;
}

}  // namespace

void ReadControllerGains(YamlSection& c, ControllerParams* gains) { ReadOptions(c, GainKeys(), gains); }

ControllerConfig LoadControllerConfig(const std::string& file) {
  ControllerConfig config;
  WithFileErrors(file, [&] { config = ReadRoot(YamlSection::LoadFile(file)); });
  return config;
}

ControllerConfig ParseControllerConfig(const std::string& text, const std::string& file) {
  ControllerConfig config;
  WithFileErrors(file, [&] { config = ReadRoot(YamlSection::LoadString(text, file)); });
  return config;
}

}  // namespace birotor
