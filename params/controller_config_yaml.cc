#include "params/controller_config_yaml.h"

#include "params/option_table.h"
#include "params/vehicle_description_yaml.h"

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
      Real("descent_rate_m_s", &O::descent_rate_m_s, 0.0, 5.0),
      Real("clock_future_window_s", &O::clock_future_window_s, 0.0, 10.0),
      Real("clock_past_window_s", &O::clock_past_window_s, 1e-3, 100.0),
      Real("clock_agreement_s", &O::clock_agreement_s, 1e-4, 10.0),
      Real("pose_stream_max_rate_hz", &O::pose_stream_max_rate_hz, 1.0, 1e5),
      Real("force_stream_max_rate_hz", &O::force_stream_max_rate_hz, 1.0, 1e5),
      Real("stream_rate_margin", &O::stream_rate_margin, 0.0, 10.0),
      Real("stream_seq_slack", &O::stream_seq_slack, 0.0, 1000.0),
      Real("stream_stamp_slack_s", &O::stream_stamp_slack_s, 0.0, 10.0),
      Real("stream_silence_s", &O::stream_silence_s, 1e-3, 100.0),
      Real("conflict_hold_s", &O::conflict_hold_s, 0.0, 100.0),
      Real("min_plausible_thrust_scale", &O::min_plausible_thrust_scale, 0.01, 1.0),
      Real("max_plausible_thrust_scale", &O::max_plausible_thrust_scale, 1.0, 10.0),
      Integer("at_floor_samples", &O::at_floor_samples, 1, 1000),
      Real("pose_gate_position_m", &O::pose_gate_position_m, 1e-3, 1e4),
      Real("pose_gate_angle_rad", &O::pose_gate_angle_rad, 1e-3, 10.0),
      Real("pose_gate_reset_s", &O::pose_gate_reset_s, 0.0, 100.0),
      Integer("pose_reacquire_count", &O::pose_reacquire_count, 2, 100),
      Real("pose_reacquire_position_m", &O::pose_reacquire_position_m, 1e-4, 1.0),
      Real("pose_reacquire_angle_rad", &O::pose_reacquire_angle_rad, 1e-4, 1.0),
      Real("degraded_max_tilt_rad", &O::degraded_max_tilt_rad, 0.0, 0.5),
      Real("degraded_omega_rate_rad_s2", &O::degraded_omega_rate_rad_s2, 100.0, 1e7),
  };
  return keys;
}

// controller.efficiency (defaults: controller/controller_params.h).
const OptionTable<EfficiencyParams>& EfficiencyKeys() {
  using O = EfficiencyParams;
  static const OptionTable<O> keys = {
      Real("airborne_force_fraction", &O::airborne_force_fraction, 0.0, 2.0),
      Real("airborne_s", &O::airborne_s, 0.0, 100.0),
      Real("baseline_tau_s", &O::baseline_tau_s, 1e-3, 1e3),
      Real("change_threshold", &O::change_threshold, 0.0, 10.0),
      Real("fault_tau_s", &O::fault_tau_s, 1e-3, 100.0),
      Real("max_rate_1_s", &O::max_rate_1_s, 1e-3, 1e3),
      Real("max_relative_sigma", &O::max_relative_sigma, 1e-4, 10.0),
      Real("blend_after_s", &O::blend_after_s, 0.0, 100.0),
      Real("blend_s", &O::blend_s, 0.0, 100.0),
      Real("decay_s", &O::decay_s, 1e-3, 1e3),
      Real("max_change_gain", &O::max_change_gain, 1.0, 10.0),
      Flag("mismatch_relative", &O::mismatch_relative),
      Real("mismatch_confirm_s", &O::mismatch_confirm_s, 0.0, 10.0),
      Real("mismatch_min_change", &O::mismatch_min_change, 0.0, 1.0),
      Real("mismatch_max_spread", &O::mismatch_max_spread, 0.0, 1.0),
      Real("mismatch_handover_factor", &O::mismatch_handover_factor, 0.0, 100.0),
      Real("absolute_tau_s", &O::absolute_tau_s, 0.0, 100.0),
      Real("absolute_settle_s", &O::absolute_settle_s, 0.0, 100.0),
      Real("absolute_max_relative_sigma", &O::absolute_max_relative_sigma, 1e-4, 1.0),
      Real("absolute_threshold", &O::absolute_threshold, 0.0, 0.5),
      Real("absolute_min_sigmas", &O::absolute_min_sigmas, 0.0, 10.0),
      Real("min_absolute_efficiency", &O::min_absolute_efficiency, 0.2, 1.0),
      Real("max_absolute_efficiency", &O::max_absolute_efficiency, 1.0, 2.0),
      Real("feasibility_margin", &O::feasibility_margin, 0.5, 2.0),
      Real("infeasible_s", &O::infeasible_s, 0.0, 10.0),
      Real("spare_min_share", &O::spare_min_share, 0.0, 0.5),
      Real("spare_max_share", &O::spare_max_share, 0.5, 1.0),
      Real("spare_hover_tilt_rad", &O::spare_hover_tilt_rad, 0.0, 0.5),
      Real("spare_tilted_min_share", &O::spare_tilted_min_share, 0.0, 0.5),
      Real("spare_retire_scale", &O::spare_retire_scale, 0.0, 0.5),
      Real("sink_detect_altitude_m", &O::sink_detect_altitude_m, 0.01, 10.0),
      Real("sink_detect_s", &O::sink_detect_s, 0.0, 10.0),
      Real("sink_recover_s", &O::sink_recover_s, 0.0, 10.0),
      Real("recover_min_sink_m_s", &O::recover_min_sink_m_s, 0.0, 10.0),
      Real("level_tilt_rad", &O::level_tilt_rad, 1e-3, 0.5),
      Real("level_rate_rad_s", &O::level_rate_rad_s, 1e-3, 10.0),
      Real("flare_tilt_rad", &O::flare_tilt_rad, 0.0, 0.3),
      Real("flare_tilt_fully_actuated_rad", &O::flare_tilt_fully_actuated_rad, 0.0, 0.3),
      Real("flare_time_s", &O::flare_time_s, 0.0, 1.0),
      Real("motor_lead_s", &O::motor_lead_s, 0.0, 1.0),
      Real("thrust_lead_s", &O::thrust_lead_s, 0.0, 1.0),
      Real("thrust_lead_filter_s", &O::thrust_lead_filter_s, 0.0, 1.0),
  };
  return keys;
}

// controller.mpc (defaults and the reason for each: controller/mpc_params.h). A
// reader of its own: it has choices and a cross-key check beside its ranges.
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
  s.Double("altitude_weight_factor", 0.1, 1e3, &o->altitude_weight_factor);
  s.Double("level_tilt_weight_1_rad2", 0.0, 1e8, &o->level_tilt_weight_1_rad2);
  s.Double("level_pitch_rate_weight_s2_rad2", 0.0, 1e8, &o->level_pitch_rate_weight_s2_rad2);
  s.Double("tilted_hover_tilt_weight_1_rad2", 0.0, 1e8, &o->tilted_hover_tilt_weight_1_rad2);
  s.Double("tilted_hover_pitch_rate_weight_s2_rad2", 0.0, 1e8, &o->tilted_hover_pitch_rate_weight_s2_rad2);
  s.Double("steady_pitch_rate_weight_s2_rad2", 0.0, 1e8, &o->steady_pitch_rate_weight_s2_rad2);
  s.Double("steady_max_accel_m_s2", 0.0, 100.0, &o->steady_max_accel_m_s2);
  s.Double("descent_position_weight_1_m2", 0.0, 1e8, &o->descent_position_weight_1_m2);
  s.Double("descent_velocity_weight_s2_m2", 0.0, 1e8, &o->descent_velocity_weight_s2_m2);
  s.Double("descent_tilt_weight_1_rad2", 0.0, 1e8, &o->descent_tilt_weight_1_rad2);
  s.Double("descent_pitch_rate_weight_s2_rad2", 0.0, 1e8, &o->descent_pitch_rate_weight_s2_rad2);
  s.Double("recovery_position_weight_1_m2", 0.0, 1e8, &o->recovery_position_weight_1_m2);
  s.Double("recovery_velocity_weight_s2_m2", 0.0, 1e8, &o->recovery_velocity_weight_s2_m2);
  s.Double("recovery_tilt_weight_1_rad2", 0.0, 1e8, &o->recovery_tilt_weight_1_rad2);
  s.Double("recovery_pitch_rate_weight_s2_rad2", 0.0, 1e8, &o->recovery_pitch_rate_weight_s2_rad2);
  s.Double("recovery_s", 0.0, 100.0, &o->recovery_s);
  s.Double("input_weight_s2_rad2", 1e-9, 1.0, &o->input_weight_s2_rad2);
  s.Double("input_rate_weight_s2_rad2", 0.0, 1.0, &o->input_rate_weight_s2_rad2);
  s.Double("max_omega_rate_rad_s2", 100.0, 1e7, &o->max_omega_rate_rad_s2);
  s.Double("max_tilt_rad", 0.01, 1.5, &o->max_tilt_rad);
  s.Double("tilt_slack_weight", 1.0, 1e10, &o->tilt_slack_weight);
  s.Double("disturbance_time_constant_s", 0.01, 100.0, &o->disturbance_time_constant_s);
  s.Double("max_disturbance_m_s2", 0.0, 50.0, &o->max_disturbance_m_s2);
  s.Double("max_disturbance_rad_s2", 0.0, 500.0, &o->max_disturbance_rad_s2);
  s.Double("disturbance_pitch_step_rad_s2", 0.0, 500.0, &o->disturbance_pitch_step_rad_s2);
  s.Double("deadline_s", 0.0, 1.0, &o->deadline_s);
  std::string clock;
  s.String("deadline_clock", {"wall", "thread_cpu", "work"}, &clock);
  o->deadline_clock = clock == "work"         ? MpcDeadlineClock::kWork
                      : clock == "thread_cpu" ? MpcDeadlineClock::kThreadCpu
                                              : MpcDeadlineClock::kWall;
  s.Int("deadline_work", 1, 1000000, &o->deadline_work);
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

// controller.setpoint (defaults: controller/controller_params.h).
const OptionTable<SetpointParams>& SetpointKeys() {
  using O = SetpointParams;
  static const OptionTable<O> keys = {
      Real("timeout_s", &O::timeout_s, 0.01, 60.0),
      Real("max_extrapolation_s", &O::max_extrapolation_s, 0.0, 1.0),
      Real("future_window_s", &O::future_window_s, 0.0, 10.0),
      Real("min_interval_s", &O::min_interval_s, 0.0, 1.0),
      Real("max_abs_position_m", &O::max_abs_position_m, 0.1, 1e4),
      Real("max_feed_forward_speed_m_s", &O::max_feed_forward_speed_m_s, 0.0, 100.0),
      Real("max_feed_forward_accel_m_s2", &O::max_feed_forward_accel_m_s2, 0.0, 100.0),
      Real("max_speed_m_s", &O::max_speed_m_s, 0.01, 100.0),
      Real("max_accel_m_s2", &O::max_accel_m_s2, 0.01, 100.0),
      Real("max_jump_m", &O::max_jump_m, 0.0, 100.0),
      Real("shaping_position_tolerance_m", &O::shaping_position_tolerance_m, 0.0, 1.0),
      Real("shaping_velocity_tolerance_m_s", &O::shaping_velocity_tolerance_m_s, 0.0, 10.0),
      Real("shaping_bandwidth_rad_s", &O::shaping_bandwidth_rad_s, 0.1, 100.0),
      Real("start_snap_m", &O::start_snap_m, 0.0, 1.0),
      Real("ff_velocity_tolerance_m_s", &O::ff_velocity_tolerance_m_s, 0.0, 100.0),
      Real("ff_accel_tolerance_m_s2", &O::ff_accel_tolerance_m_s2, 0.0, 1000.0),
      Real("ff_interval_floor_s", &O::ff_interval_floor_s, 1e-4, 1.0),
      Real("lock_max_rate_hz", &O::lock_max_rate_hz, 1.0, 1e5),
      Real("lock_rate_margin", &O::lock_rate_margin, 0.0, 10.0),
      Real("lock_seq_slack", &O::lock_seq_slack, 0.0, 1e6),
      Real("lock_stamp_slack_s", &O::lock_stamp_slack_s, 0.0, 10.0),
      Real("conflict_hold_s", &O::conflict_hold_s, 0.0, 60.0),
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
  ReadVehicleDescription(root.Section("vehicle"), &config.vehicle);
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
  ReadOptionSection(c.Section("observer"), ObserverKeys(), &config.observer);
  ReadOptionSection(c.Section("supervision"), SupervisionKeys(), &config.supervision);
  ReadOptionSection(c.Section("efficiency"), EfficiencyKeys(), &config.efficiency);
  ReadOptionSection(c.Section("setpoint"), SetpointKeys(), &config.setpoint);
  c.Finish();
  ReadMpcParams(root.Section("mpc"), &config.mpc);
  root.Finish();
  if (!root.HasMissingKeys()) RequireBirotor(root.file(), "birotor-controller", config.vehicle);
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
