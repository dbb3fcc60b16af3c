// Vehicle parameter files: the reference file loads, bad values are refused.
#include "params/birotor_params_yaml.h"

#include <gtest/gtest.h>

#include "tests/params/temp_file.h"

namespace birotor {
namespace {

std::string WriteTemp(const std::string& text) { return testing::WriteTempFile("vehicle_params_", text); }

TEST(BirotorParamsYaml, ReferenceFileGivesReferenceVehicle) {
  const BirotorParams p = LoadBirotorParams("config/reference_vehicle.yaml");
  const BirotorParams defaults;
  EXPECT_DOUBLE_EQ(p.arm_stiffness_n_m_rad, defaults.arm_stiffness_n_m_rad);
  EXPECT_DOUBLE_EQ(p.tip_mass_kg, defaults.tip_mass_kg);
  EXPECT_DOUBLE_EQ(p.thrust_coeff_n_s2_rad2, defaults.thrust_coeff_n_s2_rad2);
}

TEST(BirotorParamsYaml, RoundTripsThroughText) {
  BirotorParams p;
  p.arm_stiffness_n_m_rad = 3100.0;
  p.motor_time_constant_s = 0.045;
  const BirotorParams q = LoadBirotorParams(WriteTemp(BirotorParamsYaml(p)));
  EXPECT_DOUBLE_EQ(q.arm_stiffness_n_m_rad, 3100.0);
  EXPECT_DOUBLE_EQ(q.motor_time_constant_s, 0.045);
}

// The file text is refused with a message naming the file, the key and the
// allowed range.
void ExpectRefusedNaming(const std::string& text, const std::string& key, const std::string& range) {
  const std::string path = WriteTemp(text);
  try {
    LoadBirotorParams(path);
    ADD_FAILURE() << "accepted " << text;
  } catch (const ParamError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(key), std::string::npos) << msg;
    EXPECT_NE(msg.find(range), std::string::npos) << msg;
  }
}

TEST(BirotorParamsYaml, NegativeMassIsRefusedWithKeyAndRange) {
  ExpectRefusedNaming("vehicle:\n  body_mass_kg: -4.0\n", "vehicle.body_mass_kg", "allowed: [0.001, 1000]");
}

TEST(BirotorParamsYaml, ZeroStiffnessWrongTypeAndMissingSectionAreRefused) {
  EXPECT_THROW(LoadBirotorParams(WriteTemp("vehicle:\n  arm_stiffness_n_m_rad: 0\n")), ParamError);
  EXPECT_THROW(LoadBirotorParams(WriteTemp("vehicle:\n  arm_length_m: long\n")), ParamError);
  EXPECT_THROW(LoadBirotorParams(WriteTemp("other: 1\n")), ParamError);
}

TEST(BirotorParamsYaml, GaugeKeysDefaultToTheIdealGaugeAndRoundTrip) {
  const BirotorParams reference = LoadBirotorParams("config/reference_vehicle.yaml");
  EXPECT_EQ(reference.gauge_scale[0], 1.0);  // shared/spec/gauges.md "Parameter keys"
  EXPECT_EQ(reference.gauge_offset_rad[1], 0.0);
  EXPECT_EQ(reference.gauge_offset_std_rad, 5.0e-5);
  EXPECT_EQ(reference.gauge_drift_psd_rad2_s, 1.0e-10);
  BirotorParams p;
  p.gauge_scale[0] = 1.03;
  p.gauge_scale[1] = 0.98;
  p.gauge_offset_rad[0] = 1.5e-5;
  p.gauge_offset_std_rad = 2e-6;
  const BirotorParams q = LoadBirotorParams(WriteTemp(BirotorParamsYaml(p)));
  EXPECT_EQ(q.gauge_scale[0], 1.03);
  EXPECT_EQ(q.gauge_scale[1], 0.98);
  EXPECT_EQ(q.gauge_offset_rad[0], 1.5e-5);
  EXPECT_EQ(q.gauge_offset_std_rad, 2e-6);
}

TEST(BirotorParamsYaml, GaugeKeysOutOfRangeNameTheKeyAndRange) {
  ExpectRefusedNaming("vehicle:\n  gauge_scale: [1.03, 3.0]\n", "vehicle.gauge_scale", "[0.5, 2]");
  EXPECT_THROW(LoadBirotorParams(WriteTemp("vehicle:\n  gauge_offset_rad: [0.0]\n")), ParamError);
  EXPECT_THROW(LoadBirotorParams(WriteTemp("vehicle:\n  gauge_offset_std_rad: 0\n")), ParamError);
  EXPECT_THROW(LoadBirotorParams(WriteTemp("vehicle:\n  gauge_drift_psd_rad2_s: -1e-10\n")), ParamError);
}

}  // namespace
}  // namespace birotor
