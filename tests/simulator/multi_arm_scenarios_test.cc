// The trirotor of config/vehicles/trirotor.yaml in every scenario kind of
// the birotor's scenario files (read for three arms): hover with every noise,
// a thrust step on rotor 3 (TRUTH_N), the ground phase (rest, spool-up,
// lift-off, landing), the bench (LOADCELL_N against c_T mu omega^2), real
// gauges (STRAIN_N against s b + o) and the strain faults on three arms.
// Bounds: the measured figure (seed 1, in the comment) times at most 1.5,
// or the model's own equation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "simulator/multi_arm_simulator.h"
#include "tests/simulator/test_support.h"

namespace birotor {
namespace {

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

Scenario ForTrirotor(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return LoadScenario(ScenarioPath(name), overrides, 3);
}

// Every N-arm sample of a run.
struct MultiArmCollector : SampleSink {
  std::vector<MultiArmStrainSample> strain;
  std::vector<MultiArmMotorSample> motor;
  std::vector<MultiArmLoadCellSample> loadcell;
  std::vector<MultiArmTruthSample> truth;
  void OnStrainN(const MultiArmStrainSample& s) override { strain.push_back(s); }
  void OnMotorN(const MultiArmMotorSample& s) override { motor.push_back(s); }
  void OnLoadCellN(const MultiArmLoadCellSample& s) override { loadcell.push_back(s); }
  void OnTruthN(const MultiArmTruthSample& s) override { truth.push_back(s); }
};

double Mean(const std::vector<double>& x) {
  double sum = 0.0;
  for (double v : x) sum += v;
  return x.empty() ? 0.0 : sum / static_cast<double>(x.size());
}

double StdDev(const std::vector<double>& x) {
  const double m = Mean(x);
  double sum = 0.0;
  for (double v : x) sum += (v - m) * (v - m);
  return x.size() < 2 ? 0.0 : std::sqrt(sum / static_cast<double>(x.size() - 1));
}

TEST(MultiArmScenariosTest, TrirotorHoversOnTheHoverScenarioWithEveryNoise) {
  MultiArmSimulator sim(Trirotor(), ForTrirotor("hover", {"scenario.duration_s=10"}));
  MultiArmCollector sink;
  sim.Run(&sink);
  double max_position_error_m = 0.0, max_tilt_rad = 0.0;
  for (const MultiArmTruthSample& t : sink.truth) {
    max_position_error_m = std::max(max_position_error_m, std::hypot(t.x_m, t.z_m));
    max_tilt_rad = std::max(max_tilt_rad, std::abs(t.phi_rad));
  }
  std::printf("trirotor hover.yaml: |p - p_ref| <= %.3g m, |phi| <= %.3g rad\n", max_position_error_m, max_tilt_rad);
  // Measured 0.00676 m, 0.00829 rad.
  EXPECT_LT(max_position_error_m, 0.010);
  EXPECT_LT(max_tilt_rad, 0.012);
  EXPECT_EQ(sink.truth.size(), 10000u);
}

// faults.thrust_steps on rotor 3 (the birotor's file names rotor 1; --set
// moves it): mu_3 drops to the new s_3 at the step, so TRUTH_N's force of
// rotor 3 drops by the same factor at once, then the autopilot spins it up
// back to its hover share.
TEST(MultiArmScenariosTest, ThrustStepOnRotor3ShowsInTruthForceOfRotor3) {
  MultiArmSimulator sim(
      Trirotor(), ForTrirotor("thrust_loss",
                              {"scenario.duration_s=10", "faults.thrust_steps=[{time_s: 5.0, rotor: 3, scale: 0.8}]"}));
  MultiArmCollector sink;
  sim.Run(&sink);
  ASSERT_EQ(sim.fault_events().size(), 1u);
  EXPECT_EQ(sim.fault_events()[0].rotor, 3);
  EXPECT_EQ(sim.fault_events()[0].utime, 5000000);
  const MultiArmTruthSample& before = sink.truth[4999];  // 4.999 s
  const MultiArmTruthSample& after = sink.truth[5000];   // 5.000 s: the step's sample
  ASSERT_EQ(after.utime, 5000000);
  // f_3 = mu_3 c_T omega_3^2 with omega_3 continuous across the step: the
  // ratio is s_3 (1 + eta(t+)) / (1 + eta(t-)), eta's 1 ms change ~1e-3.
  const double ratio = after.force_n[2] / before.force_n[2];
  const double rotor1_ratio = after.force_n[0] / before.force_n[0];
  std::vector<double> scale_after, force_late, force_hover;
  for (const MultiArmTruthSample& t : sink.truth) {
    if (t.utime >= 5000000 && t.utime < 6000000) scale_after.push_back(t.thrust_scale[2]);
    if (t.utime >= 8000000) force_late.push_back(t.force_n[2]);
    if (t.utime >= 3000000 && t.utime < 5000000) force_hover.push_back(t.force_n[2]);
  }
  std::printf(
      "rotor 3 step to 0.8 at 5 s: f3(t+)/f3(t-) = %.4f, f1 ratio %.4f, mean mu_3 over 1 s %.4f, f3 hover %.3f N, f3 "
      "from 8 s %.3f N\n",
      ratio, rotor1_ratio, Mean(scale_after), Mean(force_hover), Mean(force_late));
  EXPECT_NEAR(ratio, 0.8, 0.8 * 3e-3);
  EXPECT_NEAR(rotor1_ratio, 1.0, 3e-3);
  EXPECT_NEAR(Mean(scale_after), 0.8, 0.8 * 0.02);
  // Measured: back to 14.325 N against 14.341 N in hover (0.11 %).
  EXPECT_NEAR(Mean(force_late), Mean(force_hover), 0.0017 * Mean(force_hover));
}

// hover.yaml with ground.enabled and land: at rest on the support with the
// motors stopped and every arm at its static deflection under its tip
// weight; lift-off after the spool-up; landed and level at the end.
TEST(MultiArmScenariosTest, TrirotorGroundPhaseRestsLiftsOffAndLands) {
  const VehicleDescription vehicle = Trirotor();
  MultiArmSimulator sim(vehicle, ForTrirotor("hover", {"scenario.duration_s=14", "ground.enabled=true",
                                                       "ground.land=true", "sensors.strain.noise_rad=0"}));
  const GroundParams& ground = sim.scenario().ground;
  MultiArmCollector sink;
  sim.Run(&sink);
  const MultiArmTruthSample& resting = sink.truth[2000];  // 2 s: motors stopped
  double max_rest_height_m = 0.0;
  for (const MultiArmTruthSample& t : sink.truth)
    if (t.utime < sim.scenario().ground.rest_s * 1e6) max_rest_height_m = std::max(max_rest_height_m, std::abs(t.z_m));
  const double liftoff_s = static_cast<double>(sim.liftoff_utime()) * 1e-6;
  double max_height_m = 0.0;
  for (const MultiArmTruthSample& t : sink.truth) max_height_m = std::max(max_height_m, t.z_m);
  const MultiArmTruthSample& last = sink.truth.back();
  std::printf("trirotor ground phase: lift-off at %.4f s (flight from %.1f s), max height %.4g m, end z %.3g m\n",
              liftoff_s, ground.FlightStartS(), max_height_m, last.z_m);
  EXPECT_EQ(max_rest_height_m, 0.0);  // the support holds it exactly
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(resting.omega_rad_s[static_cast<size_t>(i)], 0.0);
    EXPECT_NEAR(resting.deflection_rad[static_cast<size_t>(i)], MultiArmStaticDeflectionRad(vehicle, i, 0.0), 1e-9);
  }
  // Measured: lift-off at 4.1932 s, 193 ms after the flight starts (the
  // spool-up ends at idle, below the hover speeds); the climb overshoots
  // the start height by 4.98 mm before the hold.
  EXPECT_GT(liftoff_s, ground.FlightStartS());
  EXPECT_LT(liftoff_s, ground.FlightStartS() + 0.285);
  EXPECT_GT(max_height_m, 0.0033);
  EXPECT_LT(max_height_m, 0.0075);
  EXPECT_TRUE(sim.on_ground());
  EXPECT_EQ(last.z_m, 0.0);
  EXPECT_EQ(last.phi_rad, 0.0);
}

// bench.yaml: the body clamped, the three rotors on the open-loop profile,
// each load cell reading f_i = mu_i c_T,i omega_i^2 plus its noise.
TEST(MultiArmScenariosTest, TrirotorBenchLoadCellsReadCtOmegaSquared) {
  const VehicleDescription vehicle = Trirotor();
  MultiArmSimulator sim(vehicle, ForTrirotor("bench", {"scenario.duration_s=12"}));
  MultiArmCollector sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.loadcell.size(), sink.truth.size());
  ASSERT_EQ(sink.loadcell.size(), 12000u);
  std::vector<double> residual_n[3];
  double max_body_motion = 0.0, min_speed = 1e9, max_speed = 0.0;
  for (size_t k = 0; k < sink.truth.size(); ++k) {
    const MultiArmTruthSample& t = sink.truth[k];
    max_body_motion = std::max({max_body_motion, std::abs(t.x_m), std::abs(t.z_m), std::abs(t.phi_rad)});
    for (size_t i = 0; i < 3; ++i) {
      const double c_t = vehicle.arms[i].thrust_coeff_n_s2_rad2;
      residual_n[i].push_back(sink.loadcell[k].force_n[i] -
                              t.thrust_scale[i] * c_t * t.omega_rad_s[i] * t.omega_rad_s[i]);
      min_speed = std::min(min_speed, t.omega_rad_s[i]);
      max_speed = std::max(max_speed, t.omega_rad_s[i]);
    }
  }
  EXPECT_EQ(max_body_motion, 0.0);
  const double sigma_n = sim.scenario().sensors.loadcell_noise_n;
  for (int i = 0; i < 3; ++i) {
    std::printf("bench rotor %d: load cell - mu c_T omega^2: mean %.2g N, std %.4g N (noise %.3g N)\n", i + 1,
                Mean(residual_n[i]), StdDev(residual_n[i]), sigma_n);
    EXPECT_NEAR(Mean(residual_n[i]), 0.0, 4.0 * sigma_n / std::sqrt(12000.0));
    // 4 sigma of a standard deviation from 12000 samples: 4 / sqrt(2 x 12000) = 2.6 %.
    EXPECT_NEAR(StdDev(residual_n[i]), sigma_n, 0.026 * sigma_n);
  }
  // The profile spans [omega_low, omega_high] = [300, 1100] rad/s (bench.yaml).
  std::printf("bench speeds %.1f .. %.1f rad/s\n", min_speed, max_speed);
  EXPECT_GT(min_speed, 290.0);
  EXPECT_LT(max_speed, 1110.0);
}

// Real gauges (gauge_model.h) per arm: with the strain noise off, STRAIN_N
// is s_i b_i + o_i exactly, b_i the TRUTH_N deflection of the same step.
TEST(MultiArmScenariosTest, TrirotorRealGaugeScaleAndOffsetShowInStrain) {
  MultiArmSimulator sim(Trirotor(), ForTrirotor("hover", {"scenario.duration_s=2", "sensors.strain.noise_rad=0",
                                                          "gauge.scale=[1.03, 1.0, 0.98]",
                                                          "gauge.offset_rad=[1.0e-4, -5.0e-5, 2.0e-5]"}));
  MultiArmCollector sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.strain.size(), sink.truth.size());
  const GaugeParams& gauge = sim.scenario().gauge;
  double max_error_rad = 0.0;
  for (size_t k = 0; k < sink.strain.size(); ++k) {
    for (size_t i = 0; i < 3; ++i) {
      const double expected = gauge.scale[i] * sink.truth[k].deflection_rad[i] + gauge.offset_rad[i];
      max_error_rad = std::max(max_error_rad, std::abs(sink.strain[k].deflection_rad[i] - expected));
    }
  }
  EXPECT_LT(max_error_rad, 1e-15);
  EXPECT_NEAR(sink.strain[0].deflection_rad[2] - sink.truth[0].deflection_rad[2] * 0.98, 2.0e-5, 1e-15);
}

// sensor_faults.yaml on three arms: the gap, the NaN sample on every arm,
// the out-of-order pair and the telemetry gap where configured; spikes on
// all three arms.
TEST(MultiArmScenariosTest, TrirotorSensorFaultsHappenWhereConfigured) {
  MultiArmSimulator sim(Trirotor(), ForTrirotor("sensor_faults", {"faults.strain_spike_probability=0.02"}));
  MultiArmCollector sink;
  sim.Run(&sink);
  int gap = 0, spikes[3] = {0, 0, 0}, nan_samples = 0, swapped = 0, telemetry = 0;
  for (const FaultEvent& e : sim.fault_events()) {
    if (e.kind == FaultKind::kStrainGap) ++gap;
    if (e.kind == FaultKind::kStrainSpike) ++spikes[e.rotor - 1];
    if (e.kind == FaultKind::kStrainOutOfOrder) ++swapped;
    if (e.kind == FaultKind::kMotorTelemetryGap) ++telemetry;
  }
  for (const MultiArmStrainSample& s : sink.strain) {
    if (std::isnan(s.deflection_rad[0]) && std::isnan(s.deflection_rad[1]) && std::isnan(s.deflection_rad[2])) {
      ++nan_samples;
      EXPECT_EQ(s.utime, 8000000);
    }
  }
  const double duration_s = sim.scenario().duration_s;
  std::printf("trirotor sensor faults: gap %d, spikes %d %d %d, NaN %d, swapped %d, telemetry gap %d\n", gap, spikes[0],
              spikes[1], spikes[2], nan_samples, swapped, telemetry);
  EXPECT_EQ(gap, 150);        // 0.15 s at 1 kHz
  EXPECT_EQ(telemetry, 500);  // 1 s at 500 Hz
  EXPECT_EQ(nan_samples, 1);
  EXPECT_EQ(swapped, 1);
  EXPECT_EQ(static_cast<double>(sink.strain.size()), duration_s * 1000 - 150);
  // Each arm's count is binomial, p = 0.02 / 3 over the 19850 samples:
  // mean 132, sd 11.5; within 4 sd.
  for (int count : spikes) {
    EXPECT_GT(count, 86);
    EXPECT_LT(count, 178);
  }
  // The swapped pair: the sample at 10.000 s after the one at 10.001 s.
  for (size_t k = 1; k < sink.strain.size(); ++k) {
    if (sink.strain[k].utime == 10000000) EXPECT_EQ(sink.strain[k - 1].utime, 10001000);
  }
}

}  // namespace
}  // namespace birotor
