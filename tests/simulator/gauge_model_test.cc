// Tests of the real strain-gauge model of the simulator (scenario.h
// GaugeParams, shared/spec/gauges.md): b_meas = s b + o(t) + v(t) + n.
#include <gtest/gtest.h>

#include <cmath>

#include "params/scenario_yaml.h"
#include "simulator/simulator.h"
#include "test_support.h"

namespace birotor {
namespace {

// Noise-free, turbulence-free hover: the reading minus the truth is the gauge model alone.
const std::vector<std::string> kQuietHover = {"vehicle.turbulence_std=0",        "scenario.duration_s=2",
                                              "sensors.strain.noise_rad=0",      "sensors.motor.speed_noise_rad_s=0",
                                              "sensors.imu.gyro_noise_rad_s=0",  "sensors.imu.accel_noise_m_s2=0",
                                              "sensors.pose.position_noise_m=0", "sensors.pose.angle_noise_rad=0"};

std::vector<std::string> With(std::vector<std::string> base, const std::vector<std::string>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

TEST(GaugeModelTest, ScaleAndOffsetGiveSTimesBPlusO) {
  Simulator sim(LoadScenario(ScenarioPath("hover"),
                             With(kQuietHover, {"gauge.scale=[1.03, 0.98]", "gauge.offset_rad=[1.5e-5, -1.0e-5]"})));
  CollectingSink sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.strain.size(), sink.truth.size());
  for (size_t k = 0; k < sink.strain.size(); k += 97) {
    ASSERT_EQ(sink.strain[k].utime, sink.truth[k].utime);
    EXPECT_NEAR(sink.strain[k].deflection_rad[0], 1.03 * sink.truth[k].deflection_rad[0] + 1.5e-5, 1e-15);
    EXPECT_NEAR(sink.strain[k].deflection_rad[1], 0.98 * sink.truth[k].deflection_rad[1] - 1.0e-5, 1e-15);
  }
}

TEST(GaugeModelTest, DriftRunsOnlyInsideItsWindow) {
  Simulator sim(LoadScenario(ScenarioPath("hover"),
                             With(kQuietHover, {"gauge.drift_rad_s=[3.0e-6, -2.0e-6]", "gauge.drift_window.start_s=0.5",
                                                "gauge.drift_window.duration_s=1.0"})));
  CollectingSink sink;
  sim.Run(&sink);
  // o(t) = 3e-6 * clamp(t - 0.5, 0, 1.0): 0 before 0.5 s, 1.5e-6 at 1 s, 3e-6 from 1.5 s on.
  const double expected[4][2] = {{0.25, 0.0}, {1.0, 1.5e-6}, {1.5, 3.0e-6}, {1.999, 3.0e-6}};
  for (const auto& [t_s, offset] : expected) {
    const size_t k = static_cast<size_t>(std::llround(t_s * 1000));
    EXPECT_NEAR(sink.strain[k].deflection_rad[0] - sink.truth[k].deflection_rad[0], offset, 1e-15) << t_s;
    EXPECT_NEAR(sink.strain[k].deflection_rad[1] - sink.truth[k].deflection_rad[1], -2.0 / 3.0 * offset, 1e-15);
  }
}

// Amplitude of the component of x(t) at angular frequency w (least squares over a whole-ish window).
double Amplitude(const std::vector<double>& x, const std::vector<double>& t_s, double w) {
  double c = 0, s = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    c += x[k] * std::cos(w * t_s[k]);
    s += x[k] * std::sin(w * t_s[k]);
  }
  return 2.0 * std::hypot(c, s) / static_cast<double>(x.size());
}

TEST(GaugeModelTest, HarmonicPickupIsAtOnceAndTwiceTheArmsOwnRotorSpeed) {
  // Calm hover at 698.55 rad/s; each gauge with its own amplitudes.
  Simulator sim(LoadScenario(ScenarioPath("hover"), With(kQuietHover, {"gauge.harmonic_1x_rad=[3.0e-5, 1.0e-5]",
                                                                       "gauge.harmonic_2x_rad=[2.0e-5, 0.5e-5]",
                                                                       "gauge.harmonic_2x_phase_rad=[0.7, -1.1]"})));
  CollectingSink sink;
  sim.Run(&sink);
  std::vector<double> pickup[2], t_s;
  double omega[2] = {0, 0};
  for (size_t k = 1000; k < sink.strain.size(); ++k) {  // the last second
    t_s.push_back(sink.strain[k].utime * 1e-6);
    for (int i = 0; i < 2; ++i) {
      pickup[i].push_back(sink.strain[k].deflection_rad[i] - sink.truth[k].deflection_rad[i]);
      omega[i] += sink.truth[k].omega_rad_s[i] / 1000.0;
    }
  }
  EXPECT_NEAR(omega[0], 698.55, 0.5);  // hover speed, reference-vehicle.md
  // Amplitudes as configured (window of 111 periods: leakage below 1 %).
  EXPECT_NEAR(Amplitude(pickup[0], t_s, omega[0]), 3.0e-5, 0.3e-6);
  EXPECT_NEAR(Amplitude(pickup[0], t_s, 2 * omega[0]), 2.0e-5, 0.2e-6);
  EXPECT_NEAR(Amplitude(pickup[1], t_s, omega[1]), 1.0e-5, 0.1e-6);
  EXPECT_NEAR(Amplitude(pickup[1], t_s, 2 * omega[1]), 0.5e-5, 0.05e-6);
  // Nothing at an unrelated frequency (1.5x).
  EXPECT_LT(Amplitude(pickup[0], t_s, 1.5 * omega[0]), 0.5e-6);
}

TEST(GaugeModelTest, IdealGaugeDefaultsLeaveTheSamplesBitForBit) {
  // The defaults are the ideal gauge: explicit ideal values change nothing.
  CollectingSink a, b;
  Simulator(LoadScenario(ScenarioPath("hover"), {"scenario.duration_s=0.5"})).Run(&a);
  Simulator(LoadScenario(ScenarioPath("hover"), {"scenario.duration_s=0.5", "gauge.scale=[1.0, 1.0]",
                                                 "gauge.offset_rad=[0.0, 0.0]", "ground.enabled=false"}))
      .Run(&b);
  ASSERT_EQ(a.strain.size(), b.strain.size());
  for (size_t k = 0; k < a.strain.size(); ++k) {
    ASSERT_EQ(a.strain[k].deflection_rad[0], b.strain[k].deflection_rad[0]);
    ASSERT_EQ(a.strain[k].deflection_rad[1], b.strain[k].deflection_rad[1]);
  }
}

TEST(GaugeModelTest, ScenarioKeysAreValidated) {
  EXPECT_THROW(LoadScenario(ScenarioPath("hover"), {"gauge.scale=[1.03]"}), ParamError);
  EXPECT_THROW(LoadScenario(ScenarioPath("hover"), {"gauge.scale=[3.0, 1.0]"}), ParamError);
  EXPECT_THROW(LoadScenario(ScenarioPath("hover"), {"gauge.typo=1"}), ParamError);
  // The vehicle's gauge keys are the estimator's belief, not the simulated gauge.
  try {
    LoadScenario(ScenarioPath("hover"), {"vehicle.gauge_scale=[1.03, 1.0]"});
    ADD_FAILURE() << "accepted";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("gauge: section"), std::string::npos) << e.what();
  }
}

// sensors.strain.stamp_jitter_s: the gauges read b(t + e) = b(t) + e b_dot(t)
// with e ~ N(0, 50 us^2) per sample, one e for both arms. Without noise
// the truth gives e back exactly: (reading - b) / b_dot, the same for both
// arms; over the samples with |b_dot| > 1e-4 rad/s (the gentle move with
// turbulence) its standard deviation is 50 us within 10 % (sampling error
// of 1-2k samples: 2 %) and its mean within 5 us.
TEST(GaugeModelTest, StampJitterReadsTheGaugeAtAJitteredInstant) {
  Simulator sim(LoadScenario(ScenarioPath("gentle"), {"scenario.duration_s=3", "sensors.strain.noise_rad=0",
                                                      "sensors.strain.stamp_jitter_s=5.0e-5"}));
  CollectingSink sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.strain.size(), sink.truth.size());
  double sum = 0, sum_sq = 0;
  int n = 0;
  for (size_t k = 0; k < sink.strain.size(); ++k) {
    const TruthSample& t = sink.truth[k];
    ASSERT_EQ(sink.strain[k].utime, t.utime);
    if (std::fabs(t.deflection_dot_rad_s[0]) < 1e-4 || std::fabs(t.deflection_dot_rad_s[1]) < 1e-4) continue;
    const double e0 = (sink.strain[k].deflection_rad[0] - t.deflection_rad[0]) / t.deflection_dot_rad_s[0];
    const double e1 = (sink.strain[k].deflection_rad[1] - t.deflection_rad[1]) / t.deflection_dot_rad_s[1];
    EXPECT_NEAR(e0, e1, 1e-9);
    sum += e0;
    sum_sq += e0 * e0;
    ++n;
  }
  ASSERT_GT(n, 1000);
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 5e-6);
  EXPECT_NEAR(std::sqrt(sum_sq / n - mean * mean), 5e-5, 5e-6);
}

}  // namespace
}  // namespace birotor
