// Loading config/estimator.yaml and refusing bad files with file/key/range errors.
#include "params/estimator_config_yaml.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/params/param_error_of.h"

namespace birotor {
namespace {

std::string ErrorOf(const std::string& text) {
  return testing::ParamErrorOf([&] { ParseEstimatorConfig(text, "bad.yaml"); });
}

TEST(EstimatorConfigYamlTest, ReferenceFileHoldsTheDefaults) {
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  const EstimatorConfig defaults;
  EXPECT_EQ(config.method, defaults.method);
  EXPECT_EQ(config.vehicle.arms[0].stiffness_n_m_rad, defaults.vehicle.arms[0].stiffness_n_m_rad);
  EXPECT_EQ(config.ekf.strain_noise_rad, defaults.ekf.strain_noise_rad);
  EXPECT_EQ(config.ekf.thrust_scale_psd_1_s, defaults.ekf.thrust_scale_psd_1_s);
  EXPECT_EQ(config.ekf.deflection_rate_psd_rad2_s3, defaults.ekf.deflection_rate_psd_rad2_s3);
  EXPECT_EQ(config.ekf.strain_gate_nis, defaults.ekf.strain_gate_nis);
  EXPECT_EQ(config.ekf.telemetry_gate_nis, defaults.ekf.telemetry_gate_nis);
  EXPECT_EQ(config.ekf.gyro_gate_nis, defaults.ekf.gyro_gate_nis);
  EXPECT_EQ(config.ekf.gate_consecutive_limit, defaults.ekf.gate_consecutive_limit);
  EXPECT_EQ(config.ekf.rotor_fault_asymmetry, defaults.ekf.rotor_fault_asymmetry);
  EXPECT_EQ(config.ekf.rotor_fault_clear_asymmetry, defaults.ekf.rotor_fault_clear_asymmetry);
  EXPECT_EQ(config.ekf.thrust_deficit_scale, defaults.ekf.thrust_deficit_scale);
  EXPECT_EQ(config.ekf.thrust_deficit_clear_scale, defaults.ekf.thrust_deficit_clear_scale);
  EXPECT_EQ(config.ekf.fault_persistence_s, defaults.ekf.fault_persistence_s);
  EXPECT_EQ(config.ekf.adapt_strain_noise, defaults.ekf.adapt_strain_noise);
  EXPECT_EQ(config.ekf.strain_noise_window_s, defaults.ekf.strain_noise_window_s);
  EXPECT_EQ(config.ekf.strain_noise_scale_min, defaults.ekf.strain_noise_scale_min);
  EXPECT_EQ(config.ekf.strain_noise_scale_max, defaults.ekf.strain_noise_scale_max);
  EXPECT_EQ(config.ekf.strain_noise_min_samples, defaults.ekf.strain_noise_min_samples);
  EXPECT_EQ(config.ekf.strain_noise_hold_s, defaults.ekf.strain_noise_hold_s);
  EXPECT_EQ(config.inversion.window_samples, defaults.inversion.window_samples);
  EXPECT_EQ(config.motor_map.model_speed_std_rad_s, defaults.motor_map.model_speed_std_rad_s);
  EXPECT_EQ(config.pipeline.reset_gap_s, defaults.pipeline.reset_gap_s);
  EXPECT_EQ(config.pipeline.time_backwards_reset_s, defaults.pipeline.time_backwards_reset_s);
  EXPECT_EQ(config.pipeline.motor_timeout_s, defaults.pipeline.motor_timeout_s);
  EXPECT_EQ(config.pipeline.max_deflection_rad, defaults.pipeline.max_deflection_rad);
  EXPECT_EQ(config.ekf.ground_contact_on_n, defaults.ekf.ground_contact_on_n);
  EXPECT_EQ(config.ekf.ground_contact_off_n, defaults.ekf.ground_contact_off_n);
  EXPECT_EQ(config.ekf.body_held, defaults.ekf.body_held);
  EXPECT_EQ(config.ekf.hold_unseen_offsets, defaults.ekf.hold_unseen_offsets);
  EXPECT_EQ(config.tare.window_s, defaults.tare.window_s);
  EXPECT_EQ(config.tare.motor_stopped_rad_s, defaults.tare.motor_stopped_rad_s);
  EXPECT_EQ(config.tare.max_offset_rad, defaults.tare.max_offset_rad);
  EXPECT_EQ(config.tare.state_file, defaults.tare.state_file);
  EXPECT_EQ(config.harmonic_notch.enabled, defaults.harmonic_notch.enabled);
  EXPECT_EQ(config.harmonic_notch.bandwidth_hz, defaults.harmonic_notch.bandwidth_hz);
  EXPECT_EQ(config.harmonic_notch.multi_arm_enabled, defaults.harmonic_notch.multi_arm_enabled);
  EXPECT_EQ(config.harmonic_notch.multi_arm_bandwidth_hz, defaults.harmonic_notch.multi_arm_bandwidth_hz);
  EXPECT_EQ(config.pipeline.max_forward_jump_s, defaults.pipeline.max_forward_jump_s);
  EXPECT_EQ(config.pipeline.forward_jump_confirm_samples, defaults.pipeline.forward_jump_confirm_samples);
  EXPECT_EQ(config.pipeline.conflict_min_violations, defaults.pipeline.conflict_min_violations);
  EXPECT_EQ(config.pipeline.conflict_window_s, defaults.pipeline.conflict_window_s);
  EXPECT_EQ(config.pipeline.conflict_clear_s, defaults.pipeline.conflict_clear_s);
}

TEST(EstimatorConfigYamlTest, EmptyOrPartialFileIsRefusedNamingEachMissingKey) {
  // Issue 14: these used to start the daemon on the reference values.
  EXPECT_EQ(ErrorOf("{}"),
            "bad.yaml: missing 2 keys: vehicle, estimator (every key is required; the shipped reference files have "
            "them all)");
  EXPECT_EQ(ErrorOf("estimator:\n"), ErrorOf("{}"));
  // The whole reference file without one vehicle key and one EKF key.
  YAML::Node reference = YAML::LoadFile(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  reference["vehicle"].remove("body_mass_kg");
  reference["estimator"]["ekf"].remove("use_gyro");
  YAML::Emitter emitter;
  emitter << reference;
  EXPECT_EQ(ErrorOf(emitter.c_str()),
            "bad.yaml: missing 2 keys: vehicle.body_mass_kg, estimator.ekf.use_gyro (every key is required; the "
            "shipped reference files have them all)");
}

TEST(EstimatorConfigYamlTest, ReferenceTextWithOneValueChangedLoads) {
  YAML::Node reference = YAML::LoadFile(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  reference["estimator"]["method"] = "inversion";
  reference["estimator"]["inversion"]["window_samples"] = 3;
  YAML::Emitter emitter;
  emitter << reference;
  const EstimatorConfig c = ParseEstimatorConfig(emitter.c_str(), "x.yaml");
  EXPECT_EQ(c.method, "inversion");
  EXPECT_EQ(c.inversion.window_samples, 3);
}

// The vehicle is a description: the N-arm form of the birotor loads as the
// same vehicle; the trirotor is refused naming the key and the reason.
TEST(EstimatorConfigYamlTest, VehicleSectionInEitherFormAndOnlyABirotor) {
  const std::string source = BIROTOR_SOURCE_DIR;
  const EstimatorConfig shipped = LoadEstimatorConfig(source + "/config/estimator.yaml");
  YAML::Node text = YAML::LoadFile(source + "/config/estimator.yaml");
  text["vehicle"] = YAML::LoadFile(source + "/config/vehicles/birotor.yaml")["vehicle"];
  YAML::Emitter birotor;
  birotor << text;
  const EstimatorConfig n_arm_form = ParseEstimatorConfig(birotor.c_str(), "x.yaml");
  EXPECT_EQ(FirstDifference(n_arm_form.vehicle, shipped.vehicle), "");

  text["vehicle"] = YAML::LoadFile(source + "/config/vehicles/trirotor.yaml")["vehicle"];
  YAML::Emitter trirotor;
  trirotor << text;
  const std::string e = ErrorOf(trirotor.c_str());
  EXPECT_NE(e.find("bad.yaml: key 'vehicle': birotor-estimator runs the birotor's model"), std::string::npos) << e;
  EXPECT_NE(e.find("arm_count is 3"), std::string::npos) << e;
}

// estimator.model_consistency (issue 27, docs/mismatch.md): the shipped
// values are the compiled defaults, and a bad value is refused by name.
TEST(EstimatorConfigYamlTest, ModelConsistencySectionHoldsTheDefaultsAndRefusesBadValues) {
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  const ModelConsistencyOptions defaults;
  const ModelConsistencyOptions& c = config.model_consistency;
  EXPECT_EQ(c.enabled, defaults.enabled);
  EXPECT_EQ(c.window_s, defaults.window_s);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(c.nis_ratio_limit[k], defaults.nis_ratio_limit[k]);
    EXPECT_EQ(c.bias_limit[k], defaults.bias_limit[k]);
  }
  EXPECT_EQ(c.rejected_share_limit, defaults.rejected_share_limit);
  EXPECT_EQ(c.min_reports, defaults.min_reports);
  EXPECT_EQ(c.raise_windows, defaults.raise_windows);
  EXPECT_EQ(c.clear_windows, defaults.clear_windows);
  EXPECT_EQ(c.fast_cusum_clip, defaults.fast_cusum_clip);
  EXPECT_EQ(c.fast_cusum_drift, defaults.fast_cusum_drift);
  EXPECT_EQ(c.fast_cusum_limit, 30.0);  // docs/mismatch.md: matching files <= 15.9, mismatches >= 51
  EXPECT_EQ(c.fast_cusum_limit, defaults.fast_cusum_limit);
  EXPECT_EQ(c.confirm_windows, defaults.confirm_windows);
  EXPECT_EQ(c.valid_needs_confirmation, defaults.valid_needs_confirmation);
  EXPECT_EQ(c.thrust_scale_deviation, defaults.thrust_scale_deviation);
  EXPECT_EQ(c.arm_mode_enabled, defaults.arm_mode_enabled);
  EXPECT_EQ(c.arm_mode_limit,
            0.040);  // docs/mismatch.md: sustained on the matching files < 0.025, tip mass +20 % > 0.055
  EXPECT_EQ(c.arm_mode_limit, defaults.arm_mode_limit);
  EXPECT_EQ(c.arm_mode_raise_s, defaults.arm_mode_raise_s);
  EXPECT_EQ(c.arm_mode_clear_s, defaults.arm_mode_clear_s);
  EXPECT_EQ(c.arm_mode_band_q, defaults.arm_mode_band_q);
  EXPECT_EQ(c.arm_mode_time_constant_s, defaults.arm_mode_time_constant_s);
  EXPECT_EQ(c.arm_mode_settle_s, defaults.arm_mode_settle_s);
  EXPECT_EQ(c.arm_mode_min_excitation, defaults.arm_mode_min_excitation);
  EXPECT_EQ(c.arm_mode_multi_arm_min_excitation, defaults.arm_mode_multi_arm_min_excitation);
  EXPECT_EQ(c.arm_mode_valid_needs_reading, defaults.arm_mode_valid_needs_reading);
  EXPECT_EQ(c.arm_mode_unconfirmed_tip_mass_std, defaults.arm_mode_unconfirmed_tip_mass_std);

  std::string e = ErrorOf("estimator:\n  model_consistency: {fast_cusum_limit: -1}\n");
  EXPECT_NE(e.find("estimator.model_consistency.fast_cusum_limit"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  model_consistency: {bias_limit: [1, 1, 1]}\n");
  EXPECT_NE(e.find("estimator.model_consistency.bias_limit"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  model_consistency: {nis_ratio_limit: [2.5, 2.5, 0.5, 2.5]}\n");
  EXPECT_NE(e.find("estimator.model_consistency.nis_ratio_limit"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  model_consistency: {fast_cusum_clip: 2, fast_cusum_drift: 2, fast_cusum_limit: 30}\n");
  EXPECT_NE(e.find("estimator.model_consistency.fast_cusum_clip"), std::string::npos) << e;
  EXPECT_NE(e.find("not above fast_cusum_drift"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  model_consistency: {arm_mode_limit: 0}\n");
  EXPECT_NE(e.find("estimator.model_consistency.arm_mode_limit"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  model_consistency: {arm_mode_band_q: 0.1}\n");
  EXPECT_NE(e.find("estimator.model_consistency.arm_mode_band_q"), std::string::npos) << e;
}

TEST(EstimatorConfigYamlTest, MisspeltSectionListsTheSchemasSections) {
  // Issue 14: the list used to be built from the keys the file had.
  EXPECT_EQ(ErrorOf("estimater: {}\n"), "bad.yaml: key 'estimater': unknown key; did you mean 'estimator'?");
}

TEST(EstimatorConfigYamlTest, ErrorsNameFileKeyAndRange) {
  std::string e = ErrorOf("estimator:\n  ekf: {strain_noise_rad: -1}\n");
  EXPECT_NE(e.find("bad.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("estimator.ekf.strain_noise_rad"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed"), std::string::npos) << e;

  e = ErrorOf("estimator:\n  method: kalman\n");
  EXPECT_NE(e.find("estimator.method"), std::string::npos) << e;
  EXPECT_NE(e.find("ekf"), std::string::npos) << e;

  e = ErrorOf("estimator:\n  pipeline: {reset_gap: 0.1}\n");
  EXPECT_NE(e.find("reset_gap"), std::string::npos) << e;

  e = ErrorOf("estimator:\n  inversion: {window_samples: 2}\n");
  EXPECT_NE(e.find("estimator.inversion.window_samples"), std::string::npos) << e;

  e = ErrorOf("estimater: {}\n");
  EXPECT_NE(e.find("estimater"), std::string::npos) << e;

  e = ErrorOf("vehicle: {arm_stiffness_n_m_rad: 0}\n");
  EXPECT_NE(e.find("vehicle.arm_stiffness_n_m_rad"), std::string::npos) << e;

  e = ErrorOf("estimator:\n  ekf: {rotor_fault_asymmetry: 0.1, rotor_fault_clear_asymmetry: 0.2}\n");
  EXPECT_NE(e.find("rotor_fault_clear_asymmetry"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  ekf: {thrust_deficit_scale: 0.95, thrust_deficit_clear_scale: 0.9}\n");
  EXPECT_NE(e.find("thrust_deficit_clear_scale"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  ekf: {max_dt_s: 0.1}\n");  // one reset gap: estimator.pipeline.reset_gap_s
  EXPECT_NE(e.find("max_dt_s"), std::string::npos) << e;

  e = ErrorOf("estimator:\n  tare: {window_s: 0}\n");
  EXPECT_NE(e.find("estimator.tare.window_s"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  ekf: {ground_contact_on_n: 2.0, ground_contact_off_n: 3.0}\n");
  EXPECT_NE(e.find("ground_contact_off_n"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  harmonic_notch: {bandwidth_hz: 0}\n");
  EXPECT_NE(e.find("estimator.harmonic_notch.bandwidth_hz"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  harmonic_notch: {multi_arm_bandwidth_hz: 0}\n");
  EXPECT_NE(e.find("estimator.harmonic_notch.multi_arm_bandwidth_hz"), std::string::npos) << e;

  // The learned strain noise: never below the file's by default, and bounded.
  e = ErrorOf("estimator:\n  ekf: {strain_noise_scale_max: 0.5}\n");
  EXPECT_NE(e.find("estimator.ekf.strain_noise_scale_max"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  ekf: {strain_noise_scale_min: 2}\n");
  EXPECT_NE(e.find("estimator.ekf.strain_noise_scale_min"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  ekf: {strain_noise_window_s: 0}\n");
  EXPECT_NE(e.find("estimator.ekf.strain_noise_window_s"), std::string::npos) << e;

  EXPECT_THROW(LoadEstimatorConfig("/nonexistent/estimator.yaml"), ParamError);
}

}  // namespace
}  // namespace birotor
