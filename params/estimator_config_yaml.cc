#include "params/estimator_config_yaml.h"

#include "estimator/fusion_report.h"
#include "params/option_table.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

// The keys of estimator.ekf (defaults: EkfOptions in estimator/estimator_config.h).
const OptionTable<EkfOptions>& EkfKeys() {
  using O = EkfOptions;
  static const OptionTable<O> keys = {
      Real("strain_noise_rad", &O::strain_noise_rad, 1e-9, 1e-1),
      Real("motor_speed_noise_rad_s", &O::motor_speed_noise_rad_s, 1e-3, 1e3),
      Real("gyro_noise_rad_s", &O::gyro_noise_rad_s, 1e-6, 10.0),
      Flag("adapt_strain_noise", &O::adapt_strain_noise),
      Real("strain_noise_window_s", &O::strain_noise_window_s, 0.01, 600.0),
      Real("strain_noise_scale_min", &O::strain_noise_scale_min, 0.1, 1.0),
      Real("strain_noise_scale_max", &O::strain_noise_scale_max, 1.0, 100.0),
      Integer("strain_noise_min_samples", &O::strain_noise_min_samples, 1, 1000000),
      Real("strain_noise_hold_s", &O::strain_noise_hold_s, 0.0, 60.0),
      Flag("adapt_accel_noise", &O::adapt_accel_noise),
      Real("accel_noise_window_s", &O::accel_noise_window_s, 0.01, 600.0),
      Real("accel_noise_scale_max", &O::accel_noise_scale_max, 1.0, 1e6),
      Integer("accel_noise_min_samples", &O::accel_noise_min_samples, 1, 1000000),
      Real("accel_noise_hold_s", &O::accel_noise_hold_s, 0.0, 60.0),
      Real("accel_noise_clip", &O::accel_noise_clip, 1.0, 1e6),
      Integer("accel_noise_trust_samples", &O::accel_noise_trust_samples, 0, 1000000),
      Real("accel_noise_trust_sigmas", &O::accel_noise_trust_sigmas, 0.0, 100.0),
      Flag("use_motor_telemetry", &O::use_motor_telemetry),
      Flag("use_gyro", &O::use_gyro),
      Flag("use_accelerometer", &O::use_accelerometer),
      Real("accel_noise_m_s2", &O::accel_noise_m_s2, 1e-5, 100.0),
      Flag("estimate_gauge_offsets", &O::estimate_gauge_offsets),
      Flag("hold_unseen_offsets", &O::hold_unseen_offsets),
      Flag("learn_strain_scale", &O::learn_strain_scale),
      Real("strain_scale_prior_std", &O::strain_scale_prior_std, 1e-6, 0.5),
      Real("strain_scale_psd_1_s", &O::strain_scale_psd_1_s, 0.0, 1e-2),
      Flag("learn_body_mass", &O::learn_body_mass),
      Real("body_mass_scale_prior_std", &O::body_mass_scale_prior_std, 1e-6, 0.5),
      Real("body_mass_scale_psd_1_s", &O::body_mass_scale_psd_1_s, 0.0, 1e-2),
      Real("body_mass_change_probability", &O::body_mass_change_probability, 1e-6, 1.0),
      Real("slow_learning_delay_s", &O::slow_learning_delay_s, 0.0, 60.0),
      Real("settling_offset_limit_sigma", &O::settling_offset_limit_sigma, 0.0, 100.0),
      Real("step_hold_s", &O::step_hold_s, 0.0, 60.0),
      Real("thrust_scale_psd_1_s", &O::thrust_scale_psd_1_s, 0.0, 10.0),
      Real("deflection_rate_psd_rad2_s3", &O::deflection_rate_psd_rad2_s3, 0.0, 1e4),
      Real("pitch_rate_psd_rad2_s3", &O::pitch_rate_psd_rad2_s3, 0.0, 1e4),
      Real("omega_psd_rad2_s", &O::omega_psd_rad2_s, 0.0, 1e8),
      Real("initial_thrust_scale_std", &O::initial_thrust_scale_std, 1e-4, 2.0),
      Real("initial_omega_std_rad_s", &O::initial_omega_std_rad_s, 1e-3, 1e3),
      Real("initial_deflection_rate_std_rad_s", &O::initial_deflection_rate_std_rad_s, 1e-6, 100.0),
      Real("initial_pitch_rate_std_rad_s", &O::initial_pitch_rate_std_rad_s, 1e-6, 100.0),
      Real("strain_gate_nis", &O::strain_gate_nis, 1.0, 1e12),
      Real("telemetry_gate_nis", &O::telemetry_gate_nis, 1.0, 1e12),
      Real("gyro_gate_nis", &O::gyro_gate_nis, 1.0, 1e12),
      Real("accel_gate_nis", &O::accel_gate_nis, 1.0, 1e12),
      Integer("gate_consecutive_limit", &O::gate_consecutive_limit, 1, 1000000),
      Real("gate_inflation_thrust_scale_std", &O::gate_inflation_thrust_scale_std, 0.0, 2.0),
      Real("gyro_liftoff_recovery_s", &O::gyro_liftoff_recovery_s, 0.0, 1000.0),
      Real("converged_force_std_n", &O::converged_force_std_n, 1e-6, 1e3),
      Real("rotor_fault_asymmetry", &O::rotor_fault_asymmetry, 0.0, 1.0),
      Real("rotor_fault_clear_asymmetry", &O::rotor_fault_clear_asymmetry, 0.0, 1.0),
      Real("thrust_deficit_scale", &O::thrust_deficit_scale, 0.0, 1.0),
      Real("thrust_deficit_clear_scale", &O::thrust_deficit_clear_scale, 0.0, 1.0),
      Real("fault_n_sigma", &O::fault_n_sigma, 0.0, 10.0),
      Real("fault_persistence_s", &O::fault_persistence_s, 0.0, 10.0),
      Real("fault_second_rotor_persistence_s", &O::fault_second_rotor_persistence_s, 0.0, 10.0),
      Real("fault_second_rotor_window_s", &O::fault_second_rotor_window_s, 0.0, 10.0),
      Real("max_prediction_step_s", &O::max_prediction_step_s, 1e-5, 0.004),
      Real("ground_contact_on_n", &O::ground_contact_on_n, 0.0, 1e5),
      Real("ground_contact_off_n", &O::ground_contact_off_n, 0.0, 1e5),  // and <= ground_contact_on_n
      Real("ground_contact_filter_s", &O::ground_contact_filter_s, 1e-4, 10.0),
      Real("ground_may_touch_m", &O::ground_may_touch_m, 0.0, 10.0),
      Real("ground_may_touch_after_s", &O::ground_may_touch_after_s, 0.0, 60.0),
      Real("ground_carry_learned_thrust_scale_std", &O::ground_carry_learned_thrust_scale_std, 0.0, 10.0),
      Flag("body_held", &O::body_held),
  };
  return keys;
}

// The hysteresis pairs: each "clear" threshold on the healthy side of its "set".
void ReadEkfOptions(YamlSection s, EkfOptions* o) {
  ReadOptions(s, EkfKeys(), o);
  if (o->ground_contact_off_n > o->ground_contact_on_n) {
    s.Fail("ground_contact_off_n", "above ground_contact_on_n (no hysteresis)", RangeText(0.0, o->ground_contact_on_n));
  }
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

const OptionTable<InversionOptions>& InversionKeys() {
  using O = InversionOptions;
  static const OptionTable<O> keys = {
      Integer("window_samples", &O::window_samples, 3, 64),
      Real("force_std_n", &O::force_std_n, 0.0, 1e3),
  };
  return keys;
}

const OptionTable<MotorMapOptions>& MotorMapKeys() {
  using O = MotorMapOptions;
  static const OptionTable<O> keys = {
      Real("motor_speed_noise_rad_s", &O::motor_speed_noise_rad_s, 0.0, 1e3),
      Real("model_speed_std_rad_s", &O::model_speed_std_rad_s, 0.0, 1e3),
  };
  return keys;
}

const OptionTable<LinearModelOptions>& LinearModelKeys() {
  using O = LinearModelOptions;
  static const OptionTable<O> keys = {
      Real("strain_rate_hz", &O::strain_rate_hz, 10.0, 1e5),
      Real("force_psd_n2_s", &O::force_psd_n2_s, 1e-6, 1e4),
  };
  return keys;
}

const OptionTable<LuenbergerOptions>& LuenbergerKeys() {
  using O = LuenbergerOptions;
  static const OptionTable<O> keys = {
      Real("force_bandwidth_hz", &O::force_bandwidth_hz, 0.01, 2e4),  // and <= strain_rate_hz / 5
      Real("arm_damping_ratio", &O::arm_damping_ratio, 0.05, 0.99),
  };
  return keys;
}

// force_bandwidth_hz at most a fifth of the strain rate (the placed pole
// stays on the positive real axis, well inside the unit circle).
void ReadLuenbergerOptions(YamlSection s, double strain_rate_hz, LuenbergerOptions* o) {
  ReadOptions(s, LuenbergerKeys(), o);
  if (o->force_bandwidth_hz > 0.2 * strain_rate_hz) {
    s.Fail("force_bandwidth_hz", "above a fifth of linear_model.strain_rate_hz", RangeText(0.01, 0.2 * strain_rate_hz));
  }
  s.Finish();
}

const OptionTable<PipelineOptions>& PipelineKeys() {
  using O = PipelineOptions;
  static const OptionTable<O> keys = {
      Real("reset_gap_s", &O::reset_gap_s, 1e-3, 100.0),
      Real("time_backwards_reset_s", &O::time_backwards_reset_s, 0.0, 1e6),
      Real("motor_timeout_s", &O::motor_timeout_s, 1e-3, 100.0),
      Real("strain_timeout_s", &O::strain_timeout_s, 1e-4, 100.0),
      Real("max_deflection_rad", &O::max_deflection_rad, 1e-4, 3.2),
      Real("max_omega_rad_s", &O::max_omega_rad_s, 1.0, 1e6),
      Real("max_gyro_rad_s", &O::max_gyro_rad_s, 1e-3, 1e4),
      Real("max_forward_jump_s", &O::max_forward_jump_s, 1e-3, 1e3),
      Integer("forward_jump_confirm_samples", &O::forward_jump_confirm_samples, 1, 1000),
      Integer("conflict_min_violations", &O::conflict_min_violations, 2, 16),
      Real("conflict_window_s", &O::conflict_window_s, 1e-3, 100.0),
      Real("conflict_clear_s", &O::conflict_clear_s, 1e-3, 1e4),
  };
  return keys;
}

const OptionTable<TareOptions>& TareKeys() {
  using O = TareOptions;
  static const OptionTable<O> keys = {
      Flag("enabled", &O::enabled),
      Real("window_s", &O::window_s, 1e-2, 1e3),
      Real("motor_stopped_rad_s", &O::motor_stopped_rad_s, 0.0, 1e4),
      Real("rest_gyro_rad_s", &O::rest_gyro_rad_s, 0.0, 100.0),
      Real("rest_accel_m_s2", &O::rest_accel_m_s2, 0.0, 100.0),
      Real("input_timeout_s", &O::input_timeout_s, 1e-3, 100.0),
      Real("max_offset_rad", &O::max_offset_rad, 1e-7, 0.1),
      Real("model_std_rad", &O::model_std_rad, 0.0, 0.1),
      Text("state_file", &O::state_file),
  };
  return keys;
}

const OptionTable<HarmonicNotchOptions>& HarmonicNotchKeys() {
  using O = HarmonicNotchOptions;
  static const OptionTable<O> keys = {
      Flag("enabled", &O::enabled),
      Flag("multi_arm_enabled", &O::multi_arm_enabled),
      Real("bandwidth_hz", &O::bandwidth_hz, 0.1, 200.0),
      Real("multi_arm_bandwidth_hz", &O::multi_arm_bandwidth_hz, 0.1, 200.0),
      Real("min_speed_rad_s", &O::min_speed_rad_s, 0.0, 1e5),
      Real("max_dt_s", &O::max_dt_s, 1e-4, 1.0),
  };
  return keys;
}

// The keys of estimator.model_consistency (defaults: ModelConsistencyOptions
// in estimator/estimator_config.h; docs/mismatch.md).
const OptionTable<ModelConsistencyOptions>& ModelConsistencyKeys() {
  using O = ModelConsistencyOptions;
  static const OptionTable<O> keys = {
      Flag("enabled", &O::enabled),
      Real("window_s", &O::window_s, 0.01, 10.0),
      Real("rejected_share_limit", &O::rejected_share_limit, 0.0, 1.0),
      Integer("min_reports", &O::min_reports, 1, 1000000),
      Integer("raise_windows", &O::raise_windows, 1, 1000),
      Integer("clear_windows", &O::clear_windows, 1, 1000),
      Real("fast_cusum_clip", &O::fast_cusum_clip, 0.0, 1e3),
      Real("fast_cusum_drift", &O::fast_cusum_drift, 0.0, 1e3),
      Real("fast_cusum_limit", &O::fast_cusum_limit, 0.0, 1e6),  // 0: off
      Integer("confirm_windows", &O::confirm_windows, 1, 1000),
      Flag("valid_needs_confirmation", &O::valid_needs_confirmation),
      Real("thrust_scale_deviation", &O::thrust_scale_deviation, 0.0, 1.0),
      Flag("arm_mode_enabled", &O::arm_mode_enabled),
      Real("arm_mode_limit", &O::arm_mode_limit, 0.001, 1.0),
      Real("arm_mode_raise_s", &O::arm_mode_raise_s, 0.0, 100.0),
      Real("arm_mode_clear_s", &O::arm_mode_clear_s, 0.0, 1000.0),
      Real("arm_mode_band_q", &O::arm_mode_band_q, 0.5, 20.0),
      Real("arm_mode_time_constant_s", &O::arm_mode_time_constant_s, 0.01, 100.0),
      Real("arm_mode_settle_s", &O::arm_mode_settle_s, 0.0, 10.0),
      Real("arm_mode_min_excitation", &O::arm_mode_min_excitation, 0.0, 1e6),
      Real("arm_mode_multi_arm_min_excitation", &O::arm_mode_multi_arm_min_excitation, 0.0, 1e6),
      Flag("arm_mode_valid_needs_reading", &O::arm_mode_valid_needs_reading),
      Real("arm_mode_unconfirmed_tip_mass_std", &O::arm_mode_unconfirmed_tip_mass_std, 0.0, 1.0),
      Flag("arm_mode_learn_tip_mass", &O::arm_mode_learn_tip_mass),
      Real("arm_mode_tip_mass_change_probability", &O::arm_mode_tip_mass_change_probability, 1e-6, 1.0),
      Real("arm_mode_tip_mass_file_accepted_below", &O::arm_mode_tip_mass_file_accepted_below, 0.0, 1.0),
      Real("arm_mode_reading_std", &O::arm_mode_reading_std, 1e-4, 1.0),
      Real("arm_mode_partial_gauge_reading_bias", &O::arm_mode_partial_gauge_reading_bias, 0.0, 0.2),
      Real("arm_mode_band_pull", &O::arm_mode_band_pull, 0.1, 1.0),
      Real("arm_mode_explained_sigmas", &O::arm_mode_explained_sigmas, 0.5, 10.0),
      Real("arm_mode_learn_min_excitation", &O::arm_mode_learn_min_excitation, 0.0, 1e6),
      Real("offset_departure_limit", &O::offset_departure_limit, 0.0, 1e3),  // 0: off
      Real("offset_departure_hold_s", &O::offset_departure_hold_s, 0.0, 100.0),
      Real("offset_departure_in_sigma_above", &O::offset_departure_in_sigma_above, -1.0, 1e3),  // negative: off
      Real("scale_attribution_stiffness_std", &O::scale_attribution_stiffness_std, 1e-3, 1.0),
      Real("scale_attribution_gauge_scale_std", &O::scale_attribution_gauge_scale_std, 1e-3, 1.0),
      Real("scale_attribution_tolerance", &O::scale_attribution_tolerance, 1e-4, 0.5),
      Real("scale_attribution_limit", &O::scale_attribution_limit, 0.1, 1e3),
      Real("scale_attribution_payload_weight", &O::scale_attribution_payload_weight, 0.0, 1.0),
      Real("scale_attribution_stand_weight", &O::scale_attribution_stand_weight, 0.0, 1.0),
  };
  return keys;
}

// The per-source limits (strain, telemetry, gyro, accelerometer) and the
// fast test's rule: a clip at or below the drift could never raise.
void ReadModelConsistencyOptions(YamlSection s, ModelConsistencyOptions* o) {
  ReadOptions(s, ModelConsistencyKeys(), o);
  s.DoubleArray("nis_ratio_limit", kNumFusionSources, 1.0, 1e6, o->nis_ratio_limit);
  s.DoubleArray("bias_limit", kNumFusionSources, 0.01, 1e3, o->bias_limit);
  if (o->fast_cusum_limit > 0 && o->fast_cusum_clip <= o->fast_cusum_drift) {
    s.Fail("fast_cusum_clip", "not above fast_cusum_drift (the test could never raise)",
           RangeText(o->fast_cusum_drift, 1e3));
  }
  s.Finish();
}

// Both sections are required, with every key (the file is complete or refused).
EstimatorConfig ReadRoot(YamlSection root) {
  EstimatorConfig config;
  ReadVehicleDescription(root.Section("vehicle"), &config.vehicle);
  ReadEstimatorOptions(root.Section("estimator"), &config);
  root.Finish();
  if (!root.HasMissingKeys()) RequireBirotor(root.file(), "birotor-estimator", config.vehicle);
  return config;
}

}  // namespace

void ReadEstimatorOptions(YamlSection s, EstimatorConfig* config) {
  s.String("method", EstimationMethodNames(), &config->method);
  ReadEkfOptions(s.Section("ekf"), &config->ekf);
  ReadOptionSection(s.Section("inversion"), InversionKeys(), &config->inversion);
  ReadOptionSection(s.Section("motor_map"), MotorMapKeys(), &config->motor_map);
  ReadOptionSection(s.Section("linear_model"), LinearModelKeys(), &config->linear_model);
  ReadLuenbergerOptions(s.Section("luenberger"), config->linear_model.strain_rate_hz, &config->luenberger);
  ReadOptionSection(s.Section("pipeline"), PipelineKeys(), &config->pipeline);
  ReadOptionSection(s.Section("tare"), TareKeys(), &config->tare);
  ReadOptionSection(s.Section("harmonic_notch"), HarmonicNotchKeys(), &config->harmonic_notch);
  ReadModelConsistencyOptions(s.Section("model_consistency"), &config->model_consistency);
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
