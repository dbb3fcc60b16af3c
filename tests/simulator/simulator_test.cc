// Tests of simulator/simulator.h: hover equilibrium, sample rates and times,
// noise levels, fault injection, determinism and the clamped test bench.
#include "simulator/simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "params/scenario_yaml.h"
#include "tests/simulator/test_support.h"

namespace birotor {
namespace {

// Sample standard deviation of a list.
double StdDev(const std::vector<double>& values) {
  double mean = 0;
  for (double v : values) mean += v;
  mean /= values.size();
  double sum = 0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / (values.size() - 1));
}

const std::vector<std::string> kCalmHover = {"vehicle.turbulence_std=0", "scenario.duration_s=5"};

TEST(SimulatorTest, HoverTruthStaysAtTheEquilibriumDeflection) {
  Simulator sim(LoadScenario(ScenarioPath("hover"), kCalmHover));
  const Equilibrium& eq = sim.hover_equilibrium();
  ASSERT_TRUE(eq.converged);
  EXPECT_NEAR(eq.deflection_rad[0], -0.0018664, 1e-7);  // reference-vehicle.md
  EXPECT_NEAR(eq.deflection_rad[1], 0.0018664, 1e-7);
  TruthSink sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.truth.size(), 5000u);
  double worst = 0;
  for (const TruthSample& t : sink.truth) {
    worst = std::max({worst, std::fabs(t.deflection_rad[0] - eq.deflection_rad[0]),
                      std::fabs(t.deflection_rad[1] - eq.deflection_rad[1])});
    EXPECT_NEAR(t.force_n[0], 22.4465, 1e-3);
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(SimulatorTest, ChannelRatesMatchTheReference) {
  Simulator sim(LoadScenario(ScenarioPath("hover"), {"scenario.duration_s=2", "sensors.loadcell.enabled=true"}));
  CollectingSink sink;
  sim.Run(&sink);
  const double duration_s = 2.0;
  const std::map<std::string, std::pair<size_t, double>> rates = {
      {"strain", {sink.strain.size(), 1000.0}},     {"motor", {sink.motor.size(), 500.0}},
      {"imu", {sink.imu.size(), 1000.0}},           {"pose", {sink.pose.size(), 100.0}},
      {"loadcell", {sink.loadcell.size(), 1000.0}}, {"truth", {sink.truth.size(), 1000.0}}};
  for (const auto& [name, count_and_rate] : rates) {
    const double rate_hz = count_and_rate.first / duration_s;
    EXPECT_NEAR(rate_hz, count_and_rate.second, 0.01 * count_and_rate.second) << name;
  }
  // Exact spacing, utime from 0, seq from 0, and TRUTH k paired with STRAIN k.
  for (size_t k = 0; k < sink.strain.size(); ++k) {
    ASSERT_EQ(sink.strain[k].utime, static_cast<int64_t>(k) * 1000);
    ASSERT_EQ(sink.strain[k].seq, static_cast<int32_t>(k));
    ASSERT_EQ(sink.truth[k].utime, sink.strain[k].utime);
  }
  for (size_t k = 0; k < sink.motor.size(); ++k) ASSERT_EQ(sink.motor[k].utime, static_cast<int64_t>(k) * 2000);
  for (size_t k = 0; k < sink.pose.size(); ++k) ASSERT_EQ(sink.pose[k].utime, static_cast<int64_t>(k) * 10000);
  EXPECT_EQ(sim.emitted().strain, static_cast<int64_t>(sink.strain.size()));
}

TEST(SimulatorTest, OptionalSensorsCanBeSwitchedOff) {
  Simulator sim(LoadScenario(ScenarioPath("hover"), {"scenario.duration_s=0.5", "sensors.imu.enabled=false",
                                                     "sensors.pose.enabled=false", "sensors.motor.telemetry=false"}));
  CollectingSink sink;
  sim.Run(&sink);
  EXPECT_TRUE(sink.imu.empty());
  EXPECT_TRUE(sink.pose.empty());
  ASSERT_FALSE(sink.motor.empty());
  for (const MotorSample& m : sink.motor) {
    EXPECT_TRUE(std::isnan(m.omega_meas_rad_s[0]) && std::isnan(m.omega_meas_rad_s[1]));
    EXPECT_TRUE(std::isfinite(m.omega_cmd_rad_s[0]));
  }
}

TEST(SimulatorTest, MeasuredNoiseMatchesTheConfiguredStandardDeviation) {
  // Calm hover: the true specific force is exactly (0, g) in body axes.
  const Scenario scenario = LoadScenario(ScenarioPath("hover"), kCalmHover);
  Simulator sim(scenario);
  CollectingSink sink;
  sim.Run(&sink);
  std::map<int64_t, const TruthSample*> truth;
  for (const TruthSample& t : sink.truth) truth[t.utime] = &t;

  std::vector<double> strain, motor, gyro, accel_x, accel_z;
  for (const StrainSample& s : sink.strain)
    for (int i = 0; i < 2; ++i) strain.push_back(s.deflection_rad[i] - truth.at(s.utime)->deflection_rad[i]);
  for (const MotorSample& m : sink.motor)
    for (int i = 0; i < 2; ++i) motor.push_back(m.omega_meas_rad_s[i] - truth.at(m.utime)->omega_rad_s[i]);
  for (const ImuSample& s : sink.imu) {
    gyro.push_back(s.gyro_y_rad_s - truth.at(s.utime)->phi_dot_rad_s);
    accel_x.push_back(s.accel_x_m_s2);
    accel_z.push_back(s.accel_z_m_s2 - scenario.vehicle.gravity_m_s2);
  }
  const SensorParams& s = scenario.sensors;
  EXPECT_NEAR(StdDev(strain), s.strain_noise_rad, 0.05 * s.strain_noise_rad);
  EXPECT_NEAR(StdDev(motor), s.motor_speed_noise_rad_s, 0.05 * s.motor_speed_noise_rad_s);
  EXPECT_NEAR(StdDev(gyro), s.gyro_noise_rad_s, 0.05 * s.gyro_noise_rad_s);
  EXPECT_NEAR(StdDev(accel_x), s.accel_noise_m_s2, 0.05 * s.accel_noise_m_s2);
  EXPECT_NEAR(StdDev(accel_z), s.accel_noise_m_s2, 0.05 * s.accel_noise_m_s2);
}

TEST(SimulatorTest, MotionCaptureNoiseMatchesTheConfiguredStandardDeviation) {
  // 100 Hz: 30 s give 3000 samples, so 5 % is ~4 standard errors.
  const Scenario scenario = LoadScenario(
      ScenarioPath("hover"), {"vehicle.turbulence_std=0", "scenario.duration_s=30", "sensors.strain.enabled=false",
                              "sensors.imu.enabled=false", "sensors.motor.enabled=false"});
  Simulator sim(scenario);
  CollectingSink sink;
  sim.Run(&sink);
  std::map<int64_t, const TruthSample*> truth;
  for (const TruthSample& t : sink.truth) truth[t.utime] = &t;
  std::vector<double> x, z, phi;
  for (const PoseSample& p : sink.pose) {
    x.push_back(p.x_m - truth.at(p.utime)->x_m);
    z.push_back(p.z_m - truth.at(p.utime)->z_m);
    phi.push_back(p.phi_rad - truth.at(p.utime)->phi_rad);
  }
  ASSERT_EQ(phi.size(), 3000u);
  const SensorParams& s = scenario.sensors;
  EXPECT_NEAR(StdDev(x), s.pose_position_noise_m, 0.05 * s.pose_position_noise_m);
  EXPECT_NEAR(StdDev(z), s.pose_position_noise_m, 0.05 * s.pose_position_noise_m);
  EXPECT_NEAR(StdDev(phi), s.pose_angle_noise_rad, 0.05 * s.pose_angle_noise_rad);
}

TEST(SimulatorTest, NoiseFreeRunMeasuresTheTruth) {
  Simulator sim(LoadScenario(ScenarioPath("gentle"), {"scenario.duration_s=1", "sensors.strain.noise_rad=0"}));
  CollectingSink sink;
  sim.Run(&sink);
  for (size_t k = 0; k < sink.strain.size(); ++k)
    for (int i = 0; i < 2; ++i) ASSERT_EQ(sink.strain[k].deflection_rad[i], sink.truth[k].deflection_rad[i]);
}

TEST(SimulatorTest, TurbulenceHasTheConfiguredStandardDeviation) {
  // mu = 1 + eta with eta Gauss-Markov, std 0.01, 0.1 s: 60 s give ~300
  // correlation times per rotor, so the sample std is within ~6 %.
  Simulator sim(LoadScenario(ScenarioPath("hover"),
                             {"scenario.duration_s=60", "sensors.strain.enabled=false", "sensors.imu.enabled=false",
                              "sensors.pose.enabled=false", "sensors.motor.enabled=false"}));
  TruthSink sink;
  sim.Run(&sink);
  std::vector<double> eta;
  for (const TruthSample& t : sink.truth)
    for (int i = 0; i < 2; ++i) eta.push_back(t.thrust_scale[i] - 1.0);
  EXPECT_NEAR(StdDev(eta), 0.01, 0.0015);
}

TEST(SimulatorTest, SensorFaultsHappenExactlyWhereConfigured) {
  const Scenario scenario = LoadScenario(ScenarioPath("sensor_faults"));
  Simulator sim(scenario);
  CollectingSink sink;
  sim.Run(&sink);
  const double sigma = scenario.sensors.strain_noise_rad;
  std::map<int64_t, const TruthSample*> truth;
  for (const TruthSample& t : sink.truth) truth[t.utime] = &t;

  // Gap: seq 6000..6149 (t = 6.000 .. 6.149 s) missing, nothing else.
  std::vector<bool> seen(20000, false);
  for (const StrainSample& s : sink.strain) seen[s.seq] = true;
  for (int seq = 0; seq < 20000; ++seq) EXPECT_EQ(seen[seq], seq < 6000 || seq >= 6150) << seq;
  EXPECT_EQ(sink.strain.size(), 20000u - 150u);

  // Out of order: exactly one inversion, 10001 right before 10000.
  int inversions = 0;
  for (size_t k = 1; k < sink.strain.size(); ++k) {
    if (sink.strain[k].seq < sink.strain[k - 1].seq) {
      ++inversions;
      EXPECT_EQ(sink.strain[k].seq, 10000);
      EXPECT_EQ(sink.strain[k - 1].seq, 10001);
      EXPECT_EQ(sink.strain[k].utime, 10000000);
    }
  }
  EXPECT_EQ(inversions, 1);

  // NaN: only the sample at t = 8 s. Spikes: exactly the recorded ones are beyond 10 sigma.
  std::map<int32_t, double> spikes;
  int gaps = 0, nans = 0, swaps = 0;
  for (const FaultEvent& e : sim.fault_events()) {
    if (e.kind == FaultKind::kStrainSpike) spikes[e.seq] = e.value;
    gaps += e.kind == FaultKind::kStrainGap;
    nans += e.kind == FaultKind::kStrainNan;
    swaps += e.kind == FaultKind::kStrainOutOfOrder;
  }
  EXPECT_EQ(gaps, 150);
  EXPECT_EQ(nans, 1);
  EXPECT_EQ(swaps, 1);
  for (const StrainSample& s : sink.strain) {
    const bool is_nan = std::isnan(s.deflection_rad[0]);
    EXPECT_EQ(is_nan, s.utime == 8000000) << s.seq;
    if (is_nan) {
      EXPECT_TRUE(std::isnan(s.deflection_rad[1]));
      continue;
    }
    double worst = 0;
    for (int i = 0; i < 2; ++i)
      worst = std::max(worst, std::fabs(s.deflection_rad[i] - truth.at(s.utime)->deflection_rad[i]));
    EXPECT_EQ(worst > 10 * sigma, spikes.count(s.seq) == 1) << s.seq;
    if (spikes.count(s.seq) == 1) {
      EXPECT_NEAR(std::fabs(spikes[s.seq]), 50 * sigma, 1e-12);
    }
  }
  // 0.5 % of ~19850 samples: ~99 expected; 60..140 is four standard deviations.
  EXPECT_GT(spikes.size(), 60u);
  EXPECT_LT(spikes.size(), 140u);

  // Motor telemetry: NaN for t in [12, 13) s (500 samples), commands continue.
  int telemetry_nan = 0;
  for (const MotorSample& m : sink.motor) {
    const bool in_gap = m.utime >= 12000000 && m.utime < 13000000;
    EXPECT_EQ(std::isnan(m.omega_meas_rad_s[0]), in_gap) << m.utime;
    EXPECT_EQ(std::isnan(m.omega_meas_rad_s[1]), in_gap) << m.utime;
    EXPECT_TRUE(std::isfinite(m.omega_cmd_rad_s[0]) && std::isfinite(m.omega_cmd_rad_s[1]));
    telemetry_nan += in_gap;
  }
  EXPECT_EQ(telemetry_nan, 500);
}

TEST(SimulatorTest, SameSeedSameSamplesOtherSeedOtherSamples) {
  auto run = [](const std::string& seed) {
    Simulator sim(LoadScenario(ScenarioPath("hover"), {"scenario.duration_s=1", "scenario.seed=" + seed,
                                                       "faults.strain_spike_probability=0.05"}));
    CollectingSink sink;
    sim.Run(&sink);
    return sink;
  };
  const CollectingSink a = run("11"), b = run("11"), c = run("12");
  ASSERT_EQ(a.strain.size(), b.strain.size());
  bool all_equal = true, any_differs = false;
  for (size_t k = 0; k < a.strain.size(); ++k) {
    all_equal &= std::memcmp(&a.strain[k], &b.strain[k], sizeof(StrainSample)) == 0;
    any_differs |= a.strain[k].deflection_rad[0] != c.strain[k].deflection_rad[0];
  }
  for (size_t k = 0; k < a.truth.size(); ++k)
    all_equal &= std::memcmp(&a.truth[k], &b.truth[k], sizeof(TruthSample)) == 0;
  EXPECT_TRUE(all_equal);
  EXPECT_TRUE(any_differs);
}

TEST(SimulatorTest, BenchHoldsTheBodyStillAndLoadCellsReadTheTrueForce) {
  const Scenario scenario = LoadScenario(ScenarioPath("bench"), {"scenario.duration_s=25"});
  Simulator sim(scenario);
  CollectingSink sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.loadcell.size(), sink.truth.size());
  std::vector<double> error;
  double force_min = 1e9, force_max = 0, deflection_max = 0;
  for (size_t k = 0; k < sink.truth.size(); ++k) {
    const TruthSample& t = sink.truth[k];
    ASSERT_EQ(t.x_m, 0.0);
    ASSERT_EQ(t.z_m, 0.0);
    ASSERT_EQ(t.phi_rad, 0.0);
    ASSERT_EQ(t.x_dot_m_s, 0.0);
    ASSERT_EQ(t.phi_dot_rad_s, 0.0);
    ASSERT_EQ(sink.loadcell[k].utime, t.utime);
    for (int i = 0; i < 2; ++i) {
      error.push_back(sink.loadcell[k].force_n[i] - t.force_n[i]);
      force_min = std::min(force_min, t.force_n[i]);
      force_max = std::max(force_max, t.force_n[i]);
      deflection_max = std::max(deflection_max, std::fabs(t.deflection_rad[i]));
    }
  }
  double mean = 0;
  for (double e : error) mean += e / error.size();
  EXPECT_NEAR(mean, 0.0, 1e-3);
  EXPECT_NEAR(StdDev(error), scenario.sensors.loadcell_noise_n, 0.05 * scenario.sensors.loadcell_noise_n);
  // The profile spans 300..1100 rad/s: c_T omega^2 from ~4 N to ~56 N.
  EXPECT_LT(force_min, 8.0);
  EXPECT_GT(force_max, 45.0);
  EXPECT_GT(deflection_max, 0.004);
}

}  // namespace
}  // namespace birotor
