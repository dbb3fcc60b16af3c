// The N-arm flight identification (issue 38 item 2): a flight of the
// three-rotor vehicle whose every arm and rotor parameter differs 5-30 % from
// config/vehicles/trirotor.yaml (tests/data/trirotor_modified.yaml), simulated
// by the project's N-arm simulator (20 s of config/scenarios/flight_id.yaml,
// shortened from 60 s, 12 windows instead of 40 to keep the test short),
// identified against the file with the tip masses and damping a bench gives
// (the flight holds them: docs/identification.md "Vehicles with N arms").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "identification/multi_arm_flight_fit.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

class FlightLogSink : public SampleSink {
 public:
  explicit FlightLogSink(MultiArmBenchLog* log) : log_(log) {}
  void OnStrainN(const MultiArmStrainSample& s) override { log_->strain.push_back(s); }
  void OnMotorN(const MultiArmMotorSample& s) override { log_->motor.push_back(s); }
  void OnImu(const ImuSample& s) override { log_->imu.push_back(s); }

 private:
  MultiArmBenchLog* log_;
};

std::string SourcePath(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }

MultiArmBenchLog SimulateFlight(const VehicleDescription& truth, double duration_s,
                                const std::vector<std::string>& extra = {}) {
  std::vector<std::string> overrides = {"scenario.duration_s=" + std::to_string(duration_s)};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  const Scenario scenario = LoadScenario(SourcePath("config/scenarios/flight_id.yaml"), overrides, truth.arm_count);
  MultiArmBenchLog log;
  log.source = "simulated trirotor flight";
  log.has_vehicle = true;
  log.vehicle = truth;
  FlightLogSink sink(&log);
  MultiArmSimulator simulator(truth, scenario);
  simulator.Run(&sink);
  return log;
}

// The file with the truth's m_p,i and d_i: what the N-arm bench gives
// (within 0.15 % and 2.7 %, docs/identification.md) before the flight.
VehicleDescription FileAfterBench(const VehicleDescription& file, const VehicleDescription& truth) {
  VehicleDescription base = file;
  for (size_t i = 0; i < 3; ++i) {
    base.arms[i].tip_mass_kg = truth.arms[i].tip_mass_kg;
    base.arms[i].damping_n_m_s_rad = truth.arms[i].damping_n_m_s_rad;
  }
  return base;
}

IdentificationOptions ShortFlightOptions() {
  IdentificationOptions options;
  options.flight_max_windows = 12;
  return options;
}

struct Check {
  const char* name;
  const ParameterEstimate* estimate;
  double truth;
  double max_relative_error;  // the measured worst of the three arms x 1.5 (below) [1]
};

TEST(MultiArmFlightTest, ModifiedTrirotorKcTtauWithinMeasuredErrorsAndThreeSigma) {
  const VehicleDescription file = LoadVehicleDescription(SourcePath("config/vehicles/trirotor.yaml"));
  const VehicleDescription truth = LoadVehicleDescription(SourcePath("tests/data/trirotor_modified.yaml"));
  const VehicleDescription base = FileAfterBench(file, truth);
  const MultiArmBenchLog log = SimulateFlight(truth, 20.0);
  const MultiArmIdentificationResult result = IdentifyMultiArmFlight({log}, base, ShortFlightOptions());
  for (const std::string& e : result.errors) ADD_FAILURE() << e;
  ASSERT_TRUE(result.ok);
  ASSERT_EQ(result.arms.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    const ArmDescription& t = truth.arms[i];
    const ArmEstimates& e = result.arms[i];
    // Measured (this test): worst |error| k 0.063 % (arm 1), c_T 0.174 %
    // (arm 2), tau_m 0.472 % (arm 1), each within 0.6 sigma; the bounds are
    // 1.5 x those, all within issue 38's 1 %.
    const Check checks[] = {{"k", &e.stiffness, t.stiffness_n_m_rad, 0.00095},
                            {"c_T", &e.thrust_coeff, t.thrust_coeff_n_s2_rad2, 0.0026},
                            {"tau_m", &e.motor_time_constant, t.motor_time_constant_s, 0.0071}};
    for (const Check& c : checks) {
      const double error = c.estimate->value - c.truth;
      std::printf("arm %zu %-5s truth %.6g identified %.6g sigma %.3g error %+.3f %% (%.2f sigma)\n", i + 1, c.name,
                  c.truth, c.estimate->value, c.estimate->sigma, 100.0 * error / c.truth, error / c.estimate->sigma);
      EXPECT_TRUE(c.estimate->determined) << "arm " << i + 1 << " " << c.name;
      EXPECT_LT(std::abs(error), c.max_relative_error * c.truth) << "arm " << i + 1 << " " << c.name;
      EXPECT_LT(std::abs(error), 3.0 * c.estimate->sigma) << "arm " << i + 1 << " " << c.name;
    }
    // The vehicle has rotor turbulence: m_p held (the birotor's rule), as
    // are d and the gauge offset; the description keeps the base values.
    EXPECT_FALSE(e.tip_mass.determined);
    EXPECT_FALSE(e.damping.determined);
    EXPECT_FALSE(e.gauge_offset.determined);
    EXPECT_EQ(result.vehicle.arms[i].tip_mass_kg, base.arms[i].tip_mass_kg);
    EXPECT_EQ(result.vehicle.arms[i].damping_n_m_s_rad, base.arms[i].damping_n_m_s_rad);
    EXPECT_EQ(result.vehicle.arms[i].stiffness_n_m_rad, e.stiffness.value);
    EXPECT_EQ(result.vehicle.arms[i].thrust_coeff_n_s2_rad2, e.thrust_coeff.value);
  }
  // The advice: per arm, d and o (bench), m_p (bench first).
  ASSERT_EQ(result.advice.size(), 6u);
  EXPECT_NE(result.advice[1].find("arm 1: m_p NOT DETERMINED by a flight"), std::string::npos) << result.advice[1];
}

TEST(MultiArmFlightTest, RefusesAnotherArmCountAndAFlightWithoutTelemetry) {
  const VehicleDescription trirotor = LoadVehicleDescription(SourcePath("config/vehicles/trirotor.yaml"));
  const MultiArmBenchLog log = SimulateFlight(trirotor, 1.0);
  const VehicleDescription birotor = LoadVehicleDescription(SourcePath("config/reference_vehicle.yaml"));
  const MultiArmIdentificationResult wrong_count = IdentifyMultiArmFlight({log}, birotor, ShortFlightOptions());
  EXPECT_FALSE(wrong_count.ok);
  ASSERT_EQ(wrong_count.errors.size(), 1u);
  EXPECT_EQ(wrong_count.errors[0], "simulated trirotor flight: VEHICLE has 3 arms, the description 2");
  // No ESC telemetry: tau_m cannot be fitted on any rotor, nothing is ok.
  const MultiArmBenchLog silent = SimulateFlight(trirotor, 3.0, {"sensors.motor.telemetry=false"});
  IdentificationOptions few_windows = ShortFlightOptions();
  few_windows.flight_max_windows = 3;  // what is refused is tau_m; k and c_T only take time here
  const MultiArmIdentificationResult no_telemetry = IdentifyMultiArmFlight({silent}, trirotor, few_windows);
  EXPECT_FALSE(no_telemetry.ok);
  for (const std::string& e : no_telemetry.errors) std::printf("no telemetry: %s\n", e.c_str());
  ASSERT_GE(no_telemetry.errors.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(no_telemetry.errors[i].rfind("rotor " + std::to_string(i + 1) + ": ", 0), 0u) << no_telemetry.errors[i];
    EXPECT_FALSE(no_telemetry.arms[i].motor_time_constant.determined);
  }
}

}  // namespace
}  // namespace birotor
