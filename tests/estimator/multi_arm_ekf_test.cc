// The N-arm EKF (estimator/multi_arm_ekf.h) on short runs of the N-arm
// simulator (evaluation/multi_arm_accuracy.h): accuracy and consistency on the
// trirotor, a thrust step on rotor 3, N = 2 on the birotor description next
// to the birotor EKF, garbage input, and the N-rotor status bits. (The
// birotor's RotorFaultMonitor is the N-rotor monitor at N = 2: its rules are
// tested in rotor_fault_monitor_test.cc.) Figures measured on this commit
// (margins <= 1.5x).
#include "estimator/multi_arm_ekf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "evaluation/eval_runner.h"
#include "evaluation/multi_arm_accuracy.h"
#include "multi_arm_source_files.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "samples/sample_sink.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

// 4 s of the gentle flight on the trirotor. Measured: MAE 0.0770 / 0.0483 /
// 0.0515 N (rotor 1 carries 27.5 N at hover, rotors 2 and 3 14.3 N), 2-sigma
// share 0.951 / 0.980 / 0.970, VALID share 1.000, no false alarm. Asserted:
// MAE below 1.3x, the 2-sigma share in [0.93, 0.99].
TEST(MultiArmEkfTest, TrirotorGentleAccuracy) {
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("trirotor"), ScenarioFor("gentle", {"scenario.duration_s=4"}, 3), Config(), EvalOptions());
  ASSERT_EQ(r.n_rotors, 3);
  EXPECT_EQ(r.nonfinite, 0);
  const double measured_mae_n[3] = {0.0770, 0.0483, 0.0515};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_LT(r.rotor[i].mae_n, 1.3 * measured_mae_n[i]) << "rotor " << i + 1;
    EXPECT_GT(r.rotor[i].share_within_2sigma, 0.93) << "rotor " << i + 1;
    EXPECT_LT(r.rotor[i].share_within_2sigma, 0.99) << "rotor " << i + 1;
  }
  EXPECT_GT(r.valid_share, 0.99);
  EXPECT_EQ(r.false_alarms, 0);
}

// A 25 % loss on rotor 3 at 2 s of a 4 s hover. Measured: flagged 10 ms
// after the step, no false alarm; asserted within 15 ms (1.5x) and not before
// the 2 ms persistence (fault_persistence_s).
TEST(MultiArmEkfTest, TrirotorLossOnRotor3IsFlagged) {
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("trirotor"),
      ScenarioFor("thrust_loss",
                  {"scenario.duration_s=4", "faults.thrust_steps=[{time_s: 2.0, rotor: 3, scale: 0.75}]"}, 3),
      Config(), EvalOptions());
  EXPECT_EQ(r.step_rotor, 3);
  EXPECT_LE(r.detection_delay_s, 0.015);
  EXPECT_GE(r.detection_delay_s, 0.002);
  EXPECT_EQ(r.false_alarms, 0);
}

// N = 2 on the birotor description next to the birotor's EKF (its whole
// pipeline, birotor-eval's path) on 4 s of hover. Measured: MAE 0.0668 /
// 0.0666 N against the birotor's 0.0670 / 0.0666 N (differences 0.0002 and
// 0.0000 N); 2-sigma share 0.962 / 0.961. Asserted: within 0.0003 N (1.5x).
TEST(MultiArmEkfTest, BirotorDescriptionIsCloseToTheBirotorEkf) {
  const EstimatorConfig config = Config();
  const MultiArmAccuracy multi = RunMultiArmAccuracy(
      Vehicle("birotor"), ScenarioFor("hover", {"scenario.duration_s=4"}, 2), config, EvalOptions());
  const EvalRun run = RunSimulatedScenario(ScenarioFor("hover", {"scenario.duration_s=4"}, 2), config);
  const EvalResult birotor = Evaluate(run.forces, run.truth, run.stats.strain_fault_utimes, EvalOptions());
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(multi.rotor[i].mae_n, birotor.rotor[i].mae_n, 0.0003) << "rotor " << i + 1;
    EXPECT_GT(multi.rotor[i].share_within_2sigma, 0.93) << "rotor " << i + 1;
  }
}

// P stays exactly symmetric on a flight of the simulator, though the filter
// does not symmetrise it (every step writes each pair once): after every
// strain sample of 2 s of the gentle flight, P == P^T to the bit.
TEST(MultiArmEkfTest, CovarianceStaysExactlySymmetric) {
  struct Feed : SampleSink {
    explicit Feed(MultiArmEkf<3>* f) : filter(f) {}
    void OnMotorN(const MultiArmMotorSample& s) override { filter->AddMotor(s); }
    void OnImu(const ImuSample& s) override { filter->AddImu(s); }
    void OnStrainN(const MultiArmStrainSample& s) override {
      MultiArmForceEstimate estimate;
      filter->AddStrain(s, &estimate);
      ++strain_samples;
      if (!(filter->covariance() == filter->covariance().transpose())) ++asymmetric;
    }
    MultiArmEkf<3>* filter;
    int strain_samples = 0, asymmetric = 0;
  };
  const VehicleDescription vehicle = Vehicle("trirotor");
  MultiArmEkf<3> filter(vehicle, Config().ekf);
  Feed feed(&filter);
  MultiArmSimulator simulator(vehicle, ScenarioFor("gentle", {"scenario.duration_s=2"}, 3));
  simulator.Run(&feed);
  EXPECT_GT(feed.strain_samples, 1900);
  EXPECT_EQ(feed.asymmetric, 0);
}

// NaN, infinite and absurd readings, a wrong arm count, and time going
// backwards: every estimate stays finite.
TEST(MultiArmEkfTest, GarbageInputGivesFiniteEstimates) {
  const VehicleDescription vehicle = Vehicle("trirotor");
  const std::unique_ptr<MultiArmForceEstimator> filter = MakeMultiArmEkf(vehicle, Config().ekf);
  ASSERT_NE(filter, nullptr);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double garbage[] = {nan, inf, -inf, 1e300, -1e300, 0.0, 1e-3};
  MultiArmForceEstimate estimate;
  for (int k = 0; k < 3000; ++k) {
    const int64_t utime = (k % 97 == 0 ? k - 50 : k) * 1000;
    MultiArmMotorSample motor;
    motor.utime = utime;
    motor.n_rotors = k % 50 == 0 ? 5 : 3;
    MultiArmStrainSample strain;
    strain.utime = utime;
    strain.n_arms = k % 40 == 0 ? 2 : 3;
    for (size_t i = 0; i < 3; ++i) {
      motor.omega_cmd_rad_s[i] = k % 7 == 0 ? garbage[k % 7] : 600.0 + 100.0 * u(rng);
      motor.omega_meas_rad_s[i] = garbage[(k + i) % 7];
      strain.deflection_rad[i] = k % 3 == 0 ? garbage[(k / 3 + i) % 7] : 1.4e-3 + 1e-4 * u(rng);
    }
    ImuSample imu;
    imu.utime = utime;
    imu.gyro_y_rad_s = garbage[k % 7];
    imu.accel_x_m_s2 = garbage[(k + 3) % 7];
    imu.accel_z_m_s2 = 9.8;
    filter->AddMotor(motor);
    filter->AddImu(imu);
    filter->AddStrain(strain, &estimate);
    ASSERT_EQ(estimate.n_rotors, 3);
    for (size_t i = 0; i < 3; ++i) {
      ASSERT_TRUE(std::isfinite(estimate.force_n[i])) << k;
      ASSERT_TRUE(std::isfinite(estimate.force_std_n[i])) << k;
      ASSERT_TRUE(std::isfinite(estimate.thrust_scale[i])) << k;
    }
  }
}

// The N-rotor status: the birotor's bits for the method's facts
// (FilterStatusBits), the rotor faults in rotor_fault_bits, bit i for rotor i + 1.
TEST(MultiArmStatusTest, ComposedWithTheBirotorRules) {
  MultiArmFilterFacts facts;
  facts.convergence = FilterConvergence::kConverged;
  facts.measurement_rejected = true;
  facts.rotor_fault[2] = true;
  facts.rotor_fault[4] = true;  // beyond n_rotors = 3: not published
  MultiArmStatusBits bits = ComposeMultiArmFilterStatus(facts, 3);
  EXPECT_EQ(bits.status, kStatusValid | kStatusMeasurementRejected);
  EXPECT_EQ(bits.rotor_fault_bits, 0b100);
  facts = MultiArmFilterFacts();
  facts.convergence = FilterConvergence::kConverging;
  facts.thrust_deficit = true;
  bits = ComposeMultiArmFilterStatus(facts, 6);
  EXPECT_EQ(bits.status, kStatusConverging | kStatusThrustDeficit);
  EXPECT_EQ(bits.rotor_fault_bits, 0);
}

}  // namespace
}  // namespace birotor
