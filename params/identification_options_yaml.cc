#include "params/identification_options_yaml.h"

#include "params/option_table.h"

namespace birotor {
namespace {

// Every key of the identification: section (defaults:
// identification/identification_options.h). The calibration fact comes from
// the command line only.
const OptionTable<IdentificationOptions>& IdentificationKeys() {
  using O = IdentificationOptions;
  static const OptionTable<O> keys = {
      Real("strain_noise_rad", &O::strain_noise_rad, 1e-9, 1.0),
      Real("telemetry_noise_rad_s", &O::telemetry_noise_rad_s, 1e-6, 1e3),
      Real("loadcell_noise_n", &O::loadcell_noise_n, 1e-6, 1e2),
      Real("gyro_noise_rad_s", &O::gyro_noise_rad_s, 1e-9, 10.0),
      Real("accel_noise_m_s2", &O::accel_noise_m_s2, 1e-9, 100.0),
      Real("thrust_sample_spacing_s", &O::thrust_sample_spacing_s, 1e-3, 10.0),
      Real("motor_window_s", &O::motor_window_s, 0.01, 100.0),
      Real("bench_arm_window_s", &O::bench_arm_window_s, 0.01, 100.0),
      Real("flight_window_s", &O::flight_window_s, 0.01, 100.0),
      Integer("integration_substeps", &O::integration_substeps, 1, 20),
      Integer("flight_integration_substeps", &O::flight_integration_substeps, 1, 20),
      Integer("flight_max_windows", &O::flight_max_windows, 0, 1000000),
      Flag("flight_fit_damping", &O::flight_fit_damping),
      Flag("flight_fit_tip_mass", &O::flight_fit_tip_mass),
      Real("flight_min_data_share", &O::flight_min_data_share, 0.0, 1.0),
      Real("flight_turbulence_knot_s", &O::flight_turbulence_knot_s, 0.0, 100.0),
      Real("huber_threshold", &O::huber_threshold, 0.1, 1e3),
      Integer("map_degree", &O::map_degree, 1, 3),
      Flag("use_imu", &O::use_imu),
      Real("min_duration_s", &O::min_duration_s, 0.0, 1e5),
      Real("max_time_jump_s", &O::max_time_jump_s, 0.001, 1e5),
      Real("max_relative_sigma", &O::max_relative_sigma, 1e-6, 1e3),
      Real("command_step_rad_s", &O::command_step_rad_s, 1e-3, 1e4),
      Integer("min_command_steps", &O::min_command_steps, 0, 1000000),
      Real("bench_frequency_floor", &O::bench_frequency_floor, 0.0, 1.0),
      Real("bench_damping_floor", &O::bench_damping_floor, 0.0, 1.0),
      Real("consistency_sigmas", &O::consistency_sigmas, 1.0, 1e6),
      Real("misfit_rms_warn", &O::misfit_rms_warn, 1.0, 100.0),
      Integer("max_iterations", &O::max_iterations, 1, 10000),
      Integer("num_threads", &O::num_threads, 1, 64),
  };
  return keys;
}

}  // namespace

void ReadIdentificationOptions(YamlSection s, IdentificationOptions* o) {
  ReadOptions(s, IdentificationKeys(), o);
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
