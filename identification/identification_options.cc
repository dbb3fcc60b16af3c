#include "identification/identification_options.h"

namespace birotor {

void ReadIdentificationOptions(YamlSection s, IdentificationOptions* o) {
  s.Double("strain_noise_rad", 1e-9, 1.0, &o->strain_noise_rad);
  s.Double("telemetry_noise_rad_s", 1e-6, 1e3, &o->telemetry_noise_rad_s);
  s.Double("loadcell_noise_n", 1e-6, 1e2, &o->loadcell_noise_n);
  s.Double("gyro_noise_rad_s", 1e-9, 10.0, &o->gyro_noise_rad_s);
  s.Double("accel_noise_m_s2", 1e-9, 100.0, &o->accel_noise_m_s2);
  s.Double("thrust_sample_spacing_s", 1e-3, 10.0, &o->thrust_sample_spacing_s);
  s.Double("motor_window_s", 0.01, 100.0, &o->motor_window_s);
  s.Double("bench_arm_window_s", 0.01, 100.0, &o->bench_arm_window_s);
  s.Double("flight_window_s", 0.01, 100.0, &o->flight_window_s);
  s.Int("integration_substeps", 1, 20, &o->integration_substeps);
  s.Int("flight_integration_substeps", 1, 20, &o->flight_integration_substeps);
  s.Int("flight_max_windows", 0, 1000000, &o->flight_max_windows);
  s.Bool("flight_fit_damping", &o->flight_fit_damping);
  s.Bool("flight_fit_tip_mass", &o->flight_fit_tip_mass);
  s.Double("flight_min_data_share", 0.0, 1.0, &o->flight_min_data_share);
  s.Double("flight_turbulence_knot_s", 0.0, 100.0, &o->flight_turbulence_knot_s);
  s.Double("huber_threshold", 0.1, 1e3, &o->huber_threshold);
  s.Int("map_degree", 1, 3, &o->map_degree);
  s.Bool("use_imu", &o->use_imu);
  s.Double("min_duration_s", 0.0, 1e5, &o->min_duration_s);
  s.Double("max_time_jump_s", 0.001, 1e5, &o->max_time_jump_s);
  s.Double("max_relative_sigma", 1e-6, 1e3, &o->max_relative_sigma);
  s.Double("command_step_rad_s", 1e-3, 1e4, &o->command_step_rad_s);
  s.Int("min_command_steps", 0, 1000000, &o->min_command_steps);
  s.Double("bench_frequency_floor", 0.0, 1.0, &o->bench_frequency_floor);
  s.Double("bench_damping_floor", 0.0, 1.0, &o->bench_damping_floor);
  s.Double("consistency_sigmas", 1.0, 1e6, &o->consistency_sigmas);
  s.Double("misfit_rms_warn", 1.0, 100.0, &o->misfit_rms_warn);
  s.Int("max_iterations", 1, 10000, &o->max_iterations);
  s.Int("num_threads", 1, 64, &o->num_threads);
  s.Finish();
}

IdentificationOptions LoadIdentificationOptions(const std::string& file) {
  IdentificationOptions options;
  WithFileErrors(file, [&] {
    YamlSection root = YamlSection::LoadFile(file);
    ReadIdentificationOptions(root.Section("identification"), &options);
    root.Finish();
  });
  return options;
}

}  // namespace birotor
