// Loading config/estimator.yaml and refusing bad files with file/key/range errors.
#include "params/estimator_config_yaml.h"

#include <gtest/gtest.h>

#include <string>

namespace birotor {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParseEstimatorConfig(text, "bad.yaml");
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(EstimatorConfigYamlTest, ReferenceFileHoldsTheDefaults) {
  const EstimatorConfig config = LoadEstimatorConfig(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  const EstimatorConfig defaults;
  EXPECT_EQ(config.method, defaults.method);
  EXPECT_EQ(config.vehicle.arm_stiffness_n_m_rad, defaults.vehicle.arm_stiffness_n_m_rad);
  EXPECT_EQ(config.ekf.strain_noise_rad, defaults.ekf.strain_noise_rad);
  EXPECT_EQ(config.ekf.thrust_scale_psd_1_s, defaults.ekf.thrust_scale_psd_1_s);
  EXPECT_EQ(config.ekf.deflection_rate_psd_rad2_s3, defaults.ekf.deflection_rate_psd_rad2_s3);
  EXPECT_EQ(config.ekf.gate_nis_threshold, defaults.ekf.gate_nis_threshold);
  EXPECT_EQ(config.ekf.gate_consecutive_limit, defaults.ekf.gate_consecutive_limit);
  EXPECT_EQ(config.ekf.fault_thrust_scale, defaults.ekf.fault_thrust_scale);
  EXPECT_EQ(config.ekf.fault_clear_thrust_scale, defaults.ekf.fault_clear_thrust_scale);
  EXPECT_EQ(config.ekf.max_dt_s, defaults.ekf.max_dt_s);
  EXPECT_EQ(config.inversion.window_samples, defaults.inversion.window_samples);
  EXPECT_EQ(config.motor_map.model_speed_std_rad_s, defaults.motor_map.model_speed_std_rad_s);
  EXPECT_EQ(config.pipeline.reset_gap_s, defaults.pipeline.reset_gap_s);
  EXPECT_EQ(config.pipeline.time_backwards_reset_s, defaults.pipeline.time_backwards_reset_s);
  EXPECT_EQ(config.pipeline.motor_timeout_s, defaults.pipeline.motor_timeout_s);
  EXPECT_EQ(config.pipeline.max_deflection_rad, defaults.pipeline.max_deflection_rad);
  EXPECT_EQ(config.ekf.ground_contact_on_n, defaults.ekf.ground_contact_on_n);
  EXPECT_EQ(config.ekf.ground_contact_off_n, defaults.ekf.ground_contact_off_n);
  EXPECT_EQ(config.ekf.body_held, defaults.ekf.body_held);
  EXPECT_EQ(config.tare.window_s, defaults.tare.window_s);
  EXPECT_EQ(config.tare.motor_stopped_rad_s, defaults.tare.motor_stopped_rad_s);
  EXPECT_EQ(config.tare.max_offset_rad, defaults.tare.max_offset_rad);
  EXPECT_EQ(config.tare.state_file, defaults.tare.state_file);
  EXPECT_EQ(config.harmonic_notch.enabled, defaults.harmonic_notch.enabled);
  EXPECT_EQ(config.harmonic_notch.bandwidth_hz, defaults.harmonic_notch.bandwidth_hz);
}

TEST(EstimatorConfigYamlTest, EmptyFileGivesDefaultsAndOverridesApply) {
  EXPECT_EQ(ParseEstimatorConfig("{}", "x.yaml").method, "ekf");
  const EstimatorConfig c =
      ParseEstimatorConfig("estimator:\n  method: inversion\n  inversion: {window_samples: 3}\n", "x.yaml");
  EXPECT_EQ(c.method, "inversion");
  EXPECT_EQ(c.inversion.window_samples, 3);
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

  e = ErrorOf("estimator:\n  ekf: {fault_thrust_scale: 0.9, fault_clear_thrust_scale: 0.8}\n");
  EXPECT_NE(e.find("fault_clear_thrust_scale"), std::string::npos) << e;

  e = ErrorOf("estimator:\n  tare: {window_s: 0}\n");
  EXPECT_NE(e.find("estimator.tare.window_s"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  ekf: {ground_contact_on_n: 2.0, ground_contact_off_n: 3.0}\n");
  EXPECT_NE(e.find("ground_contact_off_n"), std::string::npos) << e;
  e = ErrorOf("estimator:\n  harmonic_notch: {bandwidth_hz: 0}\n");
  EXPECT_NE(e.find("estimator.harmonic_notch.bandwidth_hz"), std::string::npos) << e;

  EXPECT_THROW(LoadEstimatorConfig("/nonexistent/estimator.yaml"), ParamError);
}

}  // namespace
}  // namespace birotor
