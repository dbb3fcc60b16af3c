// Filter consistency on simulated flights (the simulator in-process, each
// reference scenario in full): the force errors must fall within the
// filter's own one-sigma at the Gaussian rate (share inside 2 sigma within
// 0.93-0.98, issue 13) and the strain NIS must average its 2 degrees of
// freedom (within 10 %). Also the fault semantics per scenario (issue 13
// item 5) and the accuracy figures of the README table.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

using testing_support::ReferenceConfig;
using testing_support::RunScenario;
using testing_support::ScenarioFile;
using testing_support::ScenarioRun;

constexpr int64_t kWarmupUs = 500000;  // not scored, as birotor-eval (EvalOptions::warmup_s)

struct Consistency {
  double share_inside_2sigma[2] = {0, 0};
  double strain_nis_mean = 0;
  double mae_n[2] = {0, 0};
  int64_t fault_flags[2] = {0, 0};  // estimates with ROTOR1 / ROTOR2_FAULT
  int64_t deficit_flags = 0;
  int64_t first_fault_utime[2] = {-1, -1};
};

Consistency Measure(const ScenarioRun& run) {
  Consistency c;
  int64_t scored = 0;
  for (const auto& p : run.pairs) {
    for (int i = 0; i < 2; ++i) {
      const int32_t bit = i == 0 ? kStatusRotor1Fault : kStatusRotor2Fault;
      if (p.status & bit) {
        ++c.fault_flags[i];
        if (c.first_fault_utime[i] < 0) c.first_fault_utime[i] = p.utime;
      }
    }
    if (p.status & kStatusThrustDeficit) ++c.deficit_flags;
    if (p.utime < kWarmupUs) continue;
    ++scored;
    for (int i = 0; i < 2; ++i) {
      if (std::abs(p.force_error_n[i]) <= 2.0 * p.force_std_n[i]) c.share_inside_2sigma[i] += 1.0;
      c.mae_n[i] += std::abs(p.force_error_n[i]);
    }
  }
  for (int i = 0; i < 2; ++i) {
    c.share_inside_2sigma[i] /= static_cast<double>(scored);
    c.mae_n[i] /= static_cast<double>(scored);
  }
  const InputCounters& strain = run.health.inputs[static_cast<int>(InputChannel::kStrain)];
  c.strain_nis_mean = strain.nis_sum / static_cast<double>(strain.nis_count);
  return c;
}

Consistency RunAndMeasure(const std::string& name, const std::vector<std::string>& overrides = {}) {
  const Consistency c = Measure(RunScenario(LoadScenario(ScenarioFile(name), overrides), ReferenceConfig("ekf")));
  std::printf(
      "%s: inside 2 sigma %.4f / %.4f, strain NIS mean %.3f, MAE %.4f / %.4f N, fault flags %lld / %lld, "
      "deficit flags %lld\n",
      name.c_str(), c.share_inside_2sigma[0], c.share_inside_2sigma[1], c.strain_nis_mean, c.mae_n[0], c.mae_n[1],
      static_cast<long long>(c.fault_flags[0]), static_cast<long long>(c.fault_flags[1]),
      static_cast<long long>(c.deficit_flags));
  return c;
}

// The README accuracy table's EKF MAE, asserted within 5 % (issue 13).
void ExpectReadmeMae(const Consistency& c, double rotor1_n, double rotor2_n) {
  EXPECT_NEAR(c.mae_n[0], rotor1_n, 0.05 * rotor1_n);
  EXPECT_NEAR(c.mae_n[1], rotor2_n, 0.05 * rotor2_n);
}

void ExpectConsistent(const Consistency& c) {
  for (int i = 0; i < 2; ++i) {
    EXPECT_GE(c.share_inside_2sigma[i], 0.93) << "rotor " << i + 1;
    EXPECT_LE(c.share_inside_2sigma[i], 0.98) << "rotor " << i + 1;
  }
  EXPECT_NEAR(c.strain_nis_mean, 2.0, 0.2);
}

// A healthy flight: consistent, the README's MAE, and no flag at all.
void ExpectHealthyFlight(const std::string& scenario, double rotor1_mae_n, double rotor2_mae_n) {
  const Consistency c = RunAndMeasure(scenario);
  ExpectConsistent(c);
  ExpectReadmeMae(c, rotor1_mae_n, rotor2_mae_n);
  EXPECT_EQ(c.fault_flags[0] + c.fault_flags[1] + c.deficit_flags, 0);
}

TEST(FilterConsistencyTest, Hover) { ExpectHealthyFlight("hover", 0.0674, 0.0660); }
TEST(FilterConsistencyTest, Gentle) { ExpectHealthyFlight("gentle", 0.0667, 0.0670); }
TEST(FilterConsistencyTest, Aggressive) { ExpectHealthyFlight("aggressive", 0.0661, 0.0684); }

// Both rotors at 0.9 of the nominal map (thin air): a shared deficit, not a
// rotor fault.
TEST(FilterConsistencyTest, Density) {
  const Consistency c = RunAndMeasure("density");
  ExpectConsistent(c);
  ExpectReadmeMae(c, 0.0683, 0.0671);
  EXPECT_EQ(c.fault_flags[0] + c.fault_flags[1], 0);
  // Of 15000 estimates: from the model's confirmation on (two consistent
  // 0.25 s windows, docs/mismatch.md); measured 14500.
  EXPECT_GE(c.deficit_flags, 14500);
}

TEST(FilterConsistencyTest, DensityAt085FlagsNoRotor) {
  const Consistency c = RunAndMeasure("density", {"faults.initial_thrust_scale=[0.85, 0.85]"});
  ExpectConsistent(c);
  EXPECT_EQ(c.fault_flags[0] + c.fault_flags[1], 0);
}

// Rotor 2 loses 25 % of its thrust at the step.
TEST(FilterConsistencyTest, ThrustLoss) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("thrust_loss")), ReferenceConfig("ekf"));
  const Consistency c = Measure(run);
  int64_t step_utime = -1;
  for (const FaultEvent& f : run.faults) {
    if (f.kind == FaultKind::kThrustStep) step_utime = f.utime;
  }
  ASSERT_GE(step_utime, 0);
  std::printf(
      "thrust_loss: inside 2 sigma %.4f / %.4f, strain NIS mean %.3f, MAE %.4f / %.4f N, rotor 2 flagged "
      "%.1f ms after the step, rotor 1 flags %lld\n",
      c.share_inside_2sigma[0], c.share_inside_2sigma[1], c.strain_nis_mean, c.mae_n[0], c.mae_n[1],
      (c.first_fault_utime[1] - step_utime) * 1e-3, static_cast<long long>(c.fault_flags[0]));
  ExpectConsistent(c);
  ExpectReadmeMae(c, 0.0693, 0.0788);
  EXPECT_EQ(c.fault_flags[0], 0);
  EXPECT_EQ(c.deficit_flags, 0);  // rotor 1 is at full thrust: not a shared deficit
  ASSERT_GE(c.first_fault_utime[1], step_utime);
  EXPECT_LE(c.first_fault_utime[1] - step_utime, 20000);  // issue 27 target: within 20 ms (measured 15 ms)
}

// The same without motor telemetry (neither sent nor fused): still within
// 20 ms (measured 15 ms), and no false flag.
TEST(FilterConsistencyTest, ThrustLossWithoutMotorTelemetry) {
  EstimatorConfig config = ReferenceConfig("ekf");
  config.ekf.use_motor_telemetry = false;
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("thrust_loss"), {"sensors.motor.telemetry=false"}), config);
  const Consistency c = Measure(run);
  int64_t step_utime = -1;
  for (const FaultEvent& f : run.faults) {
    if (f.kind == FaultKind::kThrustStep) step_utime = f.utime;
  }
  ASSERT_GE(step_utime, 0);
  std::printf("thrust_loss without telemetry: rotor 2 flagged %.1f ms after the step, rotor 1 flags %lld\n",
              (c.first_fault_utime[1] - step_utime) * 1e-3, static_cast<long long>(c.fault_flags[0]));
  EXPECT_EQ(c.fault_flags[0], 0);
  EXPECT_EQ(c.deficit_flags, 0);
  ASSERT_GE(c.first_fault_utime[1], step_utime);
  EXPECT_LE(c.first_fault_utime[1] - step_utime, 20000);
}

}  // namespace
}  // namespace birotor
