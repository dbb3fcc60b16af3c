// The method registry (estimator/estimation_method.h): names in the ladder's
// order, both ways, each factory making the named method, each method's
// gates from its own options.
#include "estimator/estimation_method.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

TEST(EstimationMethodTest, NamesAndEnumAgreeBothWays) {
  const std::vector<std::string> expected = {"ekf", "linear_kf", "luenberger", "inversion", "motor_map"};
  EXPECT_EQ(EstimationMethodNames(), expected);
  for (int i = 0; i < kNumEstimationMethods; ++i) {
    const EstimationMethod method = static_cast<EstimationMethod>(i);
    EstimationMethod parsed = EstimationMethod::kMotorMap;
    ASSERT_TRUE(ParseEstimationMethod(EstimationMethodName(method), &parsed));
    EXPECT_EQ(parsed, method);
    EstimatorConfig config;
    const std::unique_ptr<ForceEstimator> made = MakeForceEstimator(method, config);
    ASSERT_NE(made, nullptr);
    EXPECT_STREQ(made->Name(), expected[i].c_str());
  }
  EstimationMethod parsed;
  EXPECT_FALSE(ParseEstimationMethod("kalman", &parsed));
  EstimatorConfig bad;
  bad.method = "kalman";
  EXPECT_EQ(MakeForceEstimator(bad), nullptr);
}

// The gates are the method's own (EkfOptions defaults: strain 30, telemetry
// 30, gyro 25, accelerometer 25); the linear methods gate strain and gyro
// only, the baselines nothing.
TEST(EstimationMethodTest, EachMethodKnowsItsGates) {
  EstimatorConfig config;
  config.ekf.strain_gate_nis = 31.0;
  const std::unique_ptr<ForceEstimator> ekf = MakeForceEstimator(EstimationMethod::kEkf, config);
  EXPECT_EQ(ekf->Gate(FusionSource::kStrain), 31.0);
  EXPECT_EQ(ekf->Gate(FusionSource::kTelemetry), 30.0);
  EXPECT_EQ(ekf->Gate(FusionSource::kGyro), 25.0);
  EXPECT_EQ(ekf->Gate(FusionSource::kAccelerometer), 25.0);
  for (EstimationMethod linear : {EstimationMethod::kLinearKf, EstimationMethod::kLuenberger}) {
    const std::unique_ptr<ForceEstimator> m = MakeForceEstimator(linear, config);
    EXPECT_EQ(m->Gate(FusionSource::kStrain), 31.0);
    EXPECT_EQ(m->Gate(FusionSource::kGyro), 25.0);
    EXPECT_TRUE(std::isnan(m->Gate(FusionSource::kTelemetry)));
    EXPECT_TRUE(std::isnan(m->Gate(FusionSource::kAccelerometer)));
  }
  for (EstimationMethod baseline : {EstimationMethod::kInversion, EstimationMethod::kMotorMap}) {
    const std::unique_ptr<ForceEstimator> m = MakeForceEstimator(baseline, config);
    for (FusionSource s : {FusionSource::kStrain, FusionSource::kTelemetry, FusionSource::kGyro}) {
      EXPECT_TRUE(std::isnan(m->Gate(s)));
    }
  }
}

}  // namespace
}  // namespace birotor
