#include "params/controller_config_yaml.h"

#include "params/vehicle_params_yaml.h"

namespace birotor {
namespace {

void ReadObserverParams(YamlSection s, ObserverParams* o) {
  s.Double("position_bandwidth_rad_s", 0.1, 50.0, &o->position_bandwidth_rad_s);
  s.Double("attitude_crossover_rad_s", 0.01, 50.0, &o->attitude_crossover_rad_s);
  s.Finish();
}

void ReadSupervisionParams(YamlSection s, SupervisionParams* o) {
  s.Double("pose_timeout_s", 1e-3, 10.0, &o->pose_timeout_s);
  s.Double("imu_timeout_s", 1e-4, 10.0, &o->imu_timeout_s);
  s.Double("force_timeout_s", 1e-4, 10.0, &o->force_timeout_s);
  s.Double("force_recovery_s", 0.0, 10.0, &o->force_recovery_s);
  s.Double("descent_rate_m_s", 0.0, 5.0, &o->descent_rate_m_s);
  s.Double("clock_future_window_s", 0.0, 10.0, &o->clock_future_window_s);
  s.Double("clock_past_window_s", 1e-3, 100.0, &o->clock_past_window_s);
  s.Int("stream_max_seq_step", 1, 1000000, &o->stream_max_seq_step);
  s.Double("stream_silence_s", 1e-3, 100.0, &o->stream_silence_s);
  s.Double("conflict_hold_s", 0.0, 100.0, &o->conflict_hold_s);
  s.Double("min_plausible_thrust_scale", 0.01, 1.0, &o->min_plausible_thrust_scale);
  s.Double("max_plausible_thrust_scale", 1.0, 10.0, &o->max_plausible_thrust_scale);
  s.Double("pose_gate_position_m", 1e-3, 1e4, &o->pose_gate_position_m);
  s.Double("pose_gate_angle_rad", 1e-3, 10.0, &o->pose_gate_angle_rad);
  s.Double("pose_gate_reset_s", 0.0, 100.0, &o->pose_gate_reset_s);
  s.Finish();
}

void ReadEfficiencyParams(YamlSection s, EfficiencyParams* o) {
  s.Double("airborne_force_fraction", 0.0, 2.0, &o->airborne_force_fraction);
  s.Double("airborne_s", 0.0, 100.0, &o->airborne_s);
  s.Double("baseline_tau_s", 1e-3, 1e3, &o->baseline_tau_s);
  s.Double("change_threshold", 0.0, 10.0, &o->change_threshold);
  s.Double("fault_tau_s", 1e-3, 100.0, &o->fault_tau_s);
  s.Double("max_rate_1_s", 1e-3, 1e3, &o->max_rate_1_s);
  s.Double("max_relative_sigma", 1e-4, 10.0, &o->max_relative_sigma);
  s.Double("decay_s", 1e-3, 1e3, &o->decay_s);
  s.Double("feasibility_margin", 0.5, 2.0, &o->feasibility_margin);
  s.Double("infeasible_s", 0.0, 10.0, &o->infeasible_s);
  s.Finish();
}

void ReadMpcParams(YamlSection s, MpcParams* o) {
  s.Double("rate_hz", 10.0, 1000.0, &o->rate_hz);
  s.Double("step_s", 1e-3, 0.2, &o->step_s);
  s.Int("horizon_steps", 2, 100, &o->horizon_steps);
  s.Int("input_blocks", 1, 100, &o->input_blocks);
  s.Int("tilt_check_every_steps", 1, 100, &o->tilt_check_every_steps);
  s.Double("position_weight_1_m2", 0.0, 1e8, &o->position_weight_1_m2);
  s.Double("velocity_weight_s2_m2", 0.0, 1e8, &o->velocity_weight_s2_m2);
  s.Double("tilt_weight_1_rad2", 0.0, 1e8, &o->tilt_weight_1_rad2);
  s.Double("pitch_rate_weight_s2_rad2", 0.0, 1e8, &o->pitch_rate_weight_s2_rad2);
  s.Double("input_weight_s2_rad2", 1e-9, 1.0, &o->input_weight_s2_rad2);
  s.Double("input_rate_weight_s2_rad2", 0.0, 1.0, &o->input_rate_weight_s2_rad2);
  s.Double("max_omega_rate_rad_s2", 100.0, 1e7, &o->max_omega_rate_rad_s2);
  s.Double("max_tilt_rad", 0.01, 1.5, &o->max_tilt_rad);
  s.Double("tilt_slack_weight", 1.0, 1e10, &o->tilt_slack_weight);
  s.Double("disturbance_time_constant_s", 0.01, 100.0, &o->disturbance_time_constant_s);
  s.Double("max_disturbance_m_s2", 0.0, 50.0, &o->max_disturbance_m_s2);
  s.Double("max_disturbance_rad_s2", 0.0, 500.0, &o->max_disturbance_rad_s2);
  s.Double("deadline_s", 0.0, 1.0, &o->deadline_s);
  std::string clock;
  s.String("deadline_clock", {"wall", "thread_cpu"}, &clock);
  o->deadline_on_thread_cpu_time = clock == "thread_cpu";
  std::string algorithm;
  s.String("algorithm", {"bleic", "dense_aul", "dense_ipm"}, &algorithm);
  o->algorithm = algorithm == "bleic"       ? MpcQpAlgorithm::kBleic
                 : algorithm == "dense_aul" ? MpcQpAlgorithm::kDenseAul
                                            : MpcQpAlgorithm::kDenseIpm;
  s.Double("solver_tolerance", 1e-12, 1e-2, &o->solver_tolerance);
  s.Int("max_iterations", 0, 100000, &o->max_iterations);
  s.Bool("use_thrust_scale", &o->use_thrust_scale);
  if (o->input_blocks > o->horizon_steps)
    s.Fail("input_blocks", "more blocks than horizon_steps", "[1, horizon_steps]");
  s.Finish();
}

void ReadSetpointParams(YamlSection s, SetpointParams* o) {
  s.Double("timeout_s", 0.01, 60.0, &o->timeout_s);
  s.Double("max_extrapolation_s", 0.0, 1.0, &o->max_extrapolation_s);
  s.Double("future_window_s", 0.0, 10.0, &o->future_window_s);
  s.Double("min_interval_s", 0.0, 1.0, &o->min_interval_s);
  s.Double("max_abs_position_m", 0.1, 1e4, &o->max_abs_position_m);
  s.Double("max_speed_m_s", 0.0, 100.0, &o->max_speed_m_s);
  s.Double("max_accel_m_s2", 0.0, 100.0, &o->max_accel_m_s2);
  s.Double("max_jump_m", 0.0, 100.0, &o->max_jump_m);
  s.Finish();
}

ControllerConfig ReadRoot(YamlSection root) {
  ControllerConfig config;
  ReadVehicleParams(root.Section("vehicle"), &config.vehicle);
  YamlSection c = root.Section("controller");
  std::string mode;
  c.String("mode", {"nominal", "force_feedback", "mpc"}, &mode);
  config.force_feedback = mode != "nominal";  // mpc falls back to the force-feedback cascade
  config.model_predictive = mode == "mpc";
  c.Double("rate_hz", 10.0, 1e4, &config.gains.rate_hz);
  {
    YamlSection gains = c.Section("gains");
    ReadControllerGains(gains, &config.gains);
    gains.Finish();
  }
  ReadObserverParams(c.Section("observer"), &config.observer);
  ReadSupervisionParams(c.Section("supervision"), &config.supervision);
  ReadEfficiencyParams(c.Section("efficiency"), &config.efficiency);
  ReadSetpointParams(c.Section("setpoint"), &config.setpoint);
  c.Finish();
  ReadMpcParams(root.Section("mpc"), &config.mpc);
  root.Finish();
  return config;
}

}  // namespace

void ReadControllerGains(YamlSection& c, ControllerParams* gains) {
  c.Double("position_kp_1_s2", 0.0, 1e4, &gains->position_kp_1_s2);
  c.Double("position_kd_1_s", 0.0, 1e4, &gains->position_kd_1_s);
  c.Double("position_ki_1_s3", 0.0, 1e4, &gains->position_ki_1_s3);
  c.Double("attitude_kp_1_s2", 0.0, 1e6, &gains->attitude_kp_1_s2);
  c.Double("attitude_kd_1_s", 0.0, 1e4, &gains->attitude_kd_1_s);
  c.Double("attitude_ki_1_s3", 0.0, 1e6, &gains->attitude_ki_1_s3);
  c.Double("max_tilt_rad", 1e-3, 1.5, &gains->max_tilt_rad);
  c.Double("max_integral_m_s2", 0.0, 100.0, &gains->max_integral_m_s2);
  c.Double("max_attitude_integral_rad_s2", 0.0, 1e4, &gains->max_attitude_integral_rad_s2);
}

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
