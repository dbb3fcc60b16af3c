// Loading config/controller.yaml and refusing bad files with file/key/range errors.
#include "params/controller_config_yaml.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/params/param_error_of.h"

namespace birotor {
namespace {

std::string ErrorOf(const std::string& text) {
  return testing::ParamErrorOf([&] { ParseControllerConfig(text, "bad.yaml"); });
}

std::string ReferenceFile() { return std::string(BIROTOR_SOURCE_DIR) + "/config/controller.yaml"; }

TEST(ControllerConfigYamlTest, ReferenceFileHoldsTheDefaults) {
  const ControllerConfig config = LoadControllerConfig(ReferenceFile());
  const ControllerConfig defaults;
  EXPECT_EQ(config.force_feedback, defaults.force_feedback);
  EXPECT_EQ(config.vehicle.arms[0].thrust_coeff_n_s2_rad2, defaults.vehicle.arms[0].thrust_coeff_n_s2_rad2);
  EXPECT_EQ(config.gains.rate_hz, defaults.gains.rate_hz);
  EXPECT_EQ(config.gains.position_kp_1_s2, defaults.gains.position_kp_1_s2);
  EXPECT_EQ(config.gains.attitude_ki_1_s3, defaults.gains.attitude_ki_1_s3);
  EXPECT_EQ(config.gains.max_attitude_integral_rad_s2, defaults.gains.max_attitude_integral_rad_s2);
  EXPECT_EQ(config.observer.position_bandwidth_rad_s, defaults.observer.position_bandwidth_rad_s);
  EXPECT_EQ(config.observer.attitude_crossover_rad_s, defaults.observer.attitude_crossover_rad_s);
  EXPECT_EQ(config.supervision.pose_timeout_s, defaults.supervision.pose_timeout_s);
  EXPECT_EQ(config.supervision.imu_timeout_s, defaults.supervision.imu_timeout_s);
  EXPECT_EQ(config.supervision.force_timeout_s, defaults.supervision.force_timeout_s);
  EXPECT_EQ(config.supervision.force_recovery_s, defaults.supervision.force_recovery_s);
  EXPECT_EQ(config.supervision.min_plausible_thrust_scale, defaults.supervision.min_plausible_thrust_scale);
  EXPECT_EQ(config.supervision.max_plausible_thrust_scale, defaults.supervision.max_plausible_thrust_scale);
  EXPECT_EQ(config.supervision.descent_rate_m_s, defaults.supervision.descent_rate_m_s);
  EXPECT_EQ(config.efficiency.flare_tilt_rad, defaults.efficiency.flare_tilt_rad);
  EXPECT_EQ(config.efficiency.flare_time_s, defaults.efficiency.flare_time_s);
  EXPECT_EQ(config.efficiency.absolute_tau_s, defaults.efficiency.absolute_tau_s);
  EXPECT_EQ(config.efficiency.absolute_settle_s, defaults.efficiency.absolute_settle_s);
  EXPECT_EQ(config.efficiency.absolute_max_relative_sigma, defaults.efficiency.absolute_max_relative_sigma);
  EXPECT_EQ(config.efficiency.absolute_threshold, defaults.efficiency.absolute_threshold);
  EXPECT_EQ(config.efficiency.min_absolute_efficiency, defaults.efficiency.min_absolute_efficiency);
  EXPECT_EQ(config.efficiency.max_absolute_efficiency, defaults.efficiency.max_absolute_efficiency);
  EXPECT_EQ(config.mpc.descent_position_weight_1_m2, defaults.mpc.descent_position_weight_1_m2);
  EXPECT_EQ(config.mpc.descent_velocity_weight_s2_m2, defaults.mpc.descent_velocity_weight_s2_m2);
  EXPECT_EQ(config.mpc.descent_tilt_weight_1_rad2, defaults.mpc.descent_tilt_weight_1_rad2);
  EXPECT_EQ(config.mpc.descent_pitch_rate_weight_s2_rad2, defaults.mpc.descent_pitch_rate_weight_s2_rad2);
  EXPECT_EQ(config.mpc.level_tilt_weight_1_rad2, defaults.mpc.level_tilt_weight_1_rad2);
  EXPECT_EQ(config.mpc.level_pitch_rate_weight_s2_rad2, defaults.mpc.level_pitch_rate_weight_s2_rad2);
  EXPECT_EQ(config.mpc.tilted_hover_tilt_weight_1_rad2, defaults.mpc.tilted_hover_tilt_weight_1_rad2);
  EXPECT_EQ(config.mpc.tilted_hover_pitch_rate_weight_s2_rad2, defaults.mpc.tilted_hover_pitch_rate_weight_s2_rad2);
  EXPECT_EQ(config.mpc.steady_pitch_rate_weight_s2_rad2, defaults.mpc.steady_pitch_rate_weight_s2_rad2);
  EXPECT_EQ(config.mpc.steady_max_accel_m_s2, defaults.mpc.steady_max_accel_m_s2);
  EXPECT_EQ(config.efficiency.spare_hover_tilt_rad, defaults.efficiency.spare_hover_tilt_rad);
}

TEST(ControllerConfigYamlTest, MissingKeysAreNamed) {
  YAML::Node reference = YAML::LoadFile(ReferenceFile());
  reference["controller"]["gains"].remove("attitude_kd_1_s");
  reference["controller"]["supervision"].remove("force_timeout_s");
  reference["controller"]["efficiency"].remove("flare_tilt_rad");
  YAML::Emitter emitter;
  emitter << reference;
  EXPECT_EQ(ErrorOf(emitter.c_str()),
            "bad.yaml: missing 3 keys: controller.gains.attitude_kd_1_s, controller.supervision.force_timeout_s, "
            "controller.efficiency.flare_tilt_rad (every key is required; the shipped reference files have them "
            "all)");
}

TEST(ControllerConfigYamlTest, ErrorsNameFileKeyAndRange) {
  std::string e = ErrorOf("controller:\n  mode: fast\n");
  EXPECT_NE(e.find("bad.yaml: key 'controller.mode'"), std::string::npos) << e;
  EXPECT_NE(e.find("force_feedback"), std::string::npos) << e;
  e = ErrorOf("controller:\n  supervision: {min_plausible_thrust_scale: 0}\n");
  EXPECT_NE(e.find("controller.supervision.min_plausible_thrust_scale"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0.01, 1]"), std::string::npos) << e;
  // The flare's tilt budget stays inside issue 25's |tilt| < 0.3 rad.
  e = ErrorOf("controller:\n  efficiency: {flare_tilt_rad: 0.4}\n");
  EXPECT_NE(e.find("controller.efficiency.flare_tilt_rad"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0, 0.3]"), std::string::npos) << e;
  e = ErrorOf("controller:\n  efficiency: {flare_tilt_fully_actuated_rad: 0.4}\n");
  EXPECT_NE(e.find("controller.efficiency.flare_tilt_fully_actuated_rad"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0, 0.3]"), std::string::npos) << e;
  // The N-input MPC's level weights (docs/mpc.md "N inputs").
  e = ErrorOf("mpc: {level_tilt_weight_1_rad2: -1}\n");
  EXPECT_NE(e.find("mpc.level_tilt_weight_1_rad2"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0, 1e+08]"), std::string::npos) << e;
  // ... and its tilted-hover weights.
  e = ErrorOf("mpc: {tilted_hover_pitch_rate_weight_s2_rad2: -1}\n");
  EXPECT_NE(e.find("mpc.tilted_hover_pitch_rate_weight_s2_rad2"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0, 1e+08]"), std::string::npos) << e;
  // ... and the birotor MPC's steady weight and threshold.
  e = ErrorOf("mpc: {steady_max_accel_m_s2: -0.1}\n");
  EXPECT_NE(e.find("mpc.steady_max_accel_m_s2"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0, 100]"), std::string::npos) << e;
  // The absolute efficiency stays inside the plausible scales and on its side of 1.
  e = ErrorOf("controller:\n  efficiency: {min_absolute_efficiency: 1.1}\n");
  EXPECT_NE(e.find("bad.yaml: key 'controller.efficiency.min_absolute_efficiency'"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed: [0.2, 1]"), std::string::npos) << e;
  EXPECT_THROW(LoadControllerConfig("/nonexistent/controller.yaml"), ParamError);
}

}  // namespace
}  // namespace birotor
