#include "params/estimator_config_yaml.h"

#include "params/vehicle_params_yaml.h"

namespace birotor {
namespace {

void ReadEkfOptions(YamlSection s, EkfOptions* o) {
  s.Double("strain_noise_rad", 1e-9, 1e-1, &o->strain_noise_rad);
  s.Double("motor_speed_noise_rad_s", 1e-3, 1e3, &o->motor_speed_noise_rad_s);
  s.Double("gyro_noise_rad_s", 1e-6, 10.0, &o->gyro_noise_rad_s);
  s.Bool("use_motor_telemetry", &o->use_motor_telemetry);
  s.Bool("use_gyro", &o->use_gyro);
  s.Bool("use_accelerometer", &o->use_accelerometer);
  s.Double("accel_noise_m_s2", 1e-5, 100.0, &o->accel_noise_m_s2);
  s.Bool("estimate_gauge_offsets", &o->estimate_gauge_offsets);
  s.Double("thrust_scale_psd_1_s", 0.0, 10.0, &o->thrust_scale_psd_1_s);
  s.Double("deflection_rate_psd_rad2_s3", 0.0, 1e4, &o->deflection_rate_psd_rad2_s3);
  s.Double("pitch_rate_psd_rad2_s3", 0.0, 1e4, &o->pitch_rate_psd_rad2_s3);
  s.Double("omega_psd_rad2_s", 0.0, 1e8, &o->omega_psd_rad2_s);
  s.Double("initial_thrust_scale_std", 1e-4, 2.0, &o->initial_thrust_scale_std);
  s.Double("initial_omega_std_rad_s", 1e-3, 1e3, &o->initial_omega_std_rad_s);
  s.Double("initial_deflection_rate_std_rad_s", 1e-6, 100.0, &o->initial_deflection_rate_std_rad_s);
  s.Double("initial_pitch_rate_std_rad_s", 1e-6, 100.0, &o->initial_pitch_rate_std_rad_s);
  s.Double("strain_gate_nis", 1.0, 1e12, &o->strain_gate_nis);
  s.Double("telemetry_gate_nis", 1.0, 1e12, &o->telemetry_gate_nis);
  s.Double("gyro_gate_nis", 1.0, 1e12, &o->gyro_gate_nis);
  s.Double("accel_gate_nis", 1.0, 1e12, &o->accel_gate_nis);
  s.Int("gate_consecutive_limit", 1, 1000000, &o->gate_consecutive_limit);
  s.Double("gate_inflation_thrust_scale_std", 0.0, 2.0, &o->gate_inflation_thrust_scale_std);
  s.Double("converged_force_std_n", 1e-6, 1e3, &o->converged_force_std_n);
  s.Double("rotor_fault_asymmetry", 0.0, 1.0, &o->rotor_fault_asymmetry);
  s.Double("rotor_fault_clear_asymmetry", 0.0, 1.0, &o->rotor_fault_clear_asymmetry);
  s.Double("thrust_deficit_scale", 0.0, 1.0, &o->thrust_deficit_scale);
  s.Double("thrust_deficit_clear_scale", 0.0, 1.0, &o->thrust_deficit_clear_scale);
  s.Double("fault_n_sigma", 0.0, 10.0, &o->fault_n_sigma);
  s.Double("fault_persistence_s", 0.0, 10.0, &o->fault_persistence_s);
  s.Double("max_prediction_step_s", 1e-5, 0.004, &o->max_prediction_step_s);
  s.Double("ground_contact_on_n", 0.0, 1e5, &o->ground_contact_on_n);
  s.Double("ground_contact_off_n", 0.0, o->ground_contact_on_n, &o->ground_contact_off_n);
  s.Double("ground_contact_filter_s", 1e-4, 10.0, &o->ground_contact_filter_s);
  s.Bool("body_held", &o->body_held);
  if (o->rotor_fault_clear_asymmetry > o->rotor_fault_asymmetry) {
    s.Fail("rotor_fault_clear_asymmetry", "above rotor_fault_asymmetry (no hysteresis)",
           RangeText(0.0, o->rotor_fault_asymmetry));
  }
  if (o->thrust_deficit_clear_scale < o->thrust_deficit_scale) {
    s.Fail("thrust_deficit_clear_scale", "below thrust_deficit_scale (no hysteresis)",
           RangeText(o->thrust_deficit_scale, 1.0));
  }
  s.Finish();
}

void ReadInversionOptions(YamlSection s, InversionOptions* o) {
  s.Int("window_samples", 3, 64, &o->window_samples);
  s.Double("force_std_n", 0.0, 1e3, &o->force_std_n);
  s.Finish();
}

void ReadMotorMapOptions(YamlSection s, MotorMapOptions* o) {
  s.Double("motor_speed_noise_rad_s", 0.0, 1e3, &o->motor_speed_noise_rad_s);
  s.Double("model_speed_std_rad_s", 0.0, 1e3, &o->model_speed_std_rad_s);
  s.Finish();
}

void ReadLinearModelOptions(YamlSection s, LinearModelOptions* o) {
  s.Double("strain_rate_hz", 10.0, 1e5, &o->strain_rate_hz);
  s.Double("force_psd_n2_s", 1e-6, 1e4, &o->force_psd_n2_s);
  s.Finish();
}

// force_bandwidth_hz at most a fifth of the strain rate (the placed pole
// stays on the positive real axis, well inside the unit circle).
void ReadLuenbergerOptions(YamlSection s, double strain_rate_hz, LuenbergerOptions* o) {
  s.Double("force_bandwidth_hz", 0.01, 0.2 * strain_rate_hz, &o->force_bandwidth_hz);
  s.Double("arm_damping_ratio", 0.05, 0.99, &o->arm_damping_ratio);
  s.Finish();
}

void ReadPipelineOptions(YamlSection s, PipelineOptions* o) {
  s.Double("reset_gap_s", 1e-3, 100.0, &o->reset_gap_s);
  s.Double("time_backwards_reset_s", 0.0, 1e6, &o->time_backwards_reset_s);
  s.Double("motor_timeout_s", 1e-3, 100.0, &o->motor_timeout_s);
  s.Double("strain_timeout_s", 1e-4, 100.0, &o->strain_timeout_s);
  s.Double("max_deflection_rad", 1e-4, 3.2, &o->max_deflection_rad);
  s.Double("max_omega_rad_s", 1.0, 1e6, &o->max_omega_rad_s);
  s.Double("max_gyro_rad_s", 1e-3, 1e4, &o->max_gyro_rad_s);
  s.Double("max_forward_jump_s", 1e-3, 1e3, &o->max_forward_jump_s);
  s.Int("forward_jump_confirm_samples", 1, 1000, &o->forward_jump_confirm_samples);
  s.Int("conflict_min_violations", 2, 16, &o->conflict_min_violations);
  s.Double("conflict_window_s", 1e-3, 100.0, &o->conflict_window_s);
  s.Double("conflict_clear_s", 1e-3, 1e4, &o->conflict_clear_s);
  s.Finish();
}

void ReadTareOptions(YamlSection s, TareOptions* o) {
  s.Bool("enabled", &o->enabled);
  s.Double("window_s", 1e-2, 1e3, &o->window_s);
  s.Double("motor_stopped_rad_s", 0.0, 1e4, &o->motor_stopped_rad_s);
  s.Double("rest_gyro_rad_s", 0.0, 100.0, &o->rest_gyro_rad_s);
  s.Double("rest_accel_m_s2", 0.0, 100.0, &o->rest_accel_m_s2);
  s.Double("input_timeout_s", 1e-3, 100.0, &o->input_timeout_s);
  s.Double("max_offset_rad", 1e-7, 0.1, &o->max_offset_rad);
  s.Double("model_std_rad", 0.0, 0.1, &o->model_std_rad);
  s.AnyString("state_file", &o->state_file);
  s.Finish();
}

void ReadHarmonicNotchOptions(YamlSection s, HarmonicNotchOptions* o) {
  s.Bool("enabled", &o->enabled);
  s.Double("bandwidth_hz", 0.1, 200.0, &o->bandwidth_hz);
  s.Double("min_speed_rad_s", 0.0, 1e5, &o->min_speed_rad_s);
  s.Double("max_dt_s", 1e-4, 1.0, &o->max_dt_s);
  s.Finish();
}

// Both sections are required, with every key (the file is complete or refused).
EstimatorConfig ReadRoot(YamlSection root) {
  EstimatorConfig config;
  ReadVehicleParams(root.Section("vehicle"), &config.vehicle);
  ReadEstimatorOptions(root.Section("estimator"), &config);
  root.Finish();
  return config;
}

}  // namespace

void ReadEstimatorOptions(YamlSection s, EstimatorConfig* config) {
  s.String("method", EstimationMethodNames(), &config->method);
  ReadEkfOptions(s.Section("ekf"), &config->ekf);
  ReadInversionOptions(s.Section("inversion"), &config->inversion);
  ReadMotorMapOptions(s.Section("motor_map"), &config->motor_map);
  ReadLinearModelOptions(s.Section("linear_model"), &config->linear_model);
  ReadLuenbergerOptions(s.Section("luenberger"), config->linear_model.strain_rate_hz, &config->luenberger);
  ReadPipelineOptions(s.Section("pipeline"), &config->pipeline);
  ReadTareOptions(s.Section("tare"), &config->tare);
  ReadHarmonicNotchOptions(s.Section("harmonic_notch"), &config->harmonic_notch);
  s.Finish();
}

EstimatorConfig LoadEstimatorConfig(const std::string& file) {
  EstimatorConfig config;
  WithFileErrors(file, [&] { config = ReadRoot(YamlSection::LoadFile(file)); });
  return config;
}

EstimatorConfig ParseEstimatorConfig(const std::string& text, const std::string& file) {
  EstimatorConfig config;
  WithFileErrors(file, [&] { config = ReadRoot(YamlSection::LoadString(text, file)); });
  return config;
}

}  // namespace birotor
