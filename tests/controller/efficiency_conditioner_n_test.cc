// EfficiencyConditioner on three rotors (issue 38: one class for any rotor
// count, input the N-rotor report RotorEfficiencyEstimate): a loss on rotor
// 3 followed with fault_tau_s, a ringing scale not passed to the rotors
// (max_rate_1_s), the absolute rule on every rotor, reports of another count
// or not VALID ignored, and on two rotors the birotor's FORCE and its report
// (RotorEfficiencyReportOf) answering alike. Reports at 1 kHz, one Advance
// per report (dt 1 ms), the defaults of controller/controller_params.h. The
// rotors' forces are the trirotor's hover thrusts (27.47, 14.32, 14.32 N,
// config/vehicles/trirotor.yaml) times the scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "controller/efficiency_conditioner.h"

namespace birotor {
namespace {

constexpr double kDtS = 0.001;
constexpr std::array<double, 3> kHoverN = {27.47, 14.32, 14.32};
constexpr double kHoverSumN = 27.47 + 14.32 + 14.32;
// airborne_s (0.05 s) to airborne, then baseline_tau_s (1 s) until a change
// counts; the first following after the unusable ground phase is a blend
// (blend_s 1.5 s, time constant blend_s / 3): over by 0.05 + 1.5 s (0.3 s
// of margin).
constexpr double kSettledS = 0.3 + 1.5 + 0.05;

class ThreeRotorFeed {
 public:
  explicit ThreeRotorFeed(const EfficiencyParams& params = EfficiencyParams()) : conditioner_(params, kHoverSumN, 3) {}

  // One report of these scales, fault bits and status, then one period.
  void Step(const std::array<double, 3>& scale, int32_t fault_bits = 0, int32_t status = kStatusValid) {
    Send(Report(scale, fault_bits, status));
  }
  // One report as it is, then one period.
  void Send(const RotorEfficiencyEstimate& report) {
    conditioner_.OnForce(report);
    conditioner_.Advance(kDtS, true);
    utime_us_ += 1000;
  }
  void Fly(double seconds, const std::array<double, 3>& scale, int32_t fault_bits = 0) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / kDtS)); ++k) Step(scale, fault_bits);
  }
  RotorEfficiencyEstimate Report(const std::array<double, 3>& scale, int32_t fault_bits, int32_t status) const {
    RotorEfficiencyEstimate report;
    report.utime = utime_us_;
    report.n_rotors = 3;
    report.valid = (status & kStatusValid) != 0;
    report.status = status;
    report.rotor_fault_bits = fault_bits;
    for (size_t i = 0; i < 3; ++i) {
      report.thrust_scale[i] = scale[i];
      report.force_n[i] = scale[i] * kHoverN[i];
      report.force_std_n[i] = 0.01 * report.force_n[i];  // 1 %: precise
    }
    return report;
  }
  EfficiencyConditioner& conditioner() { return conditioner_; }

 private:
  EfficiencyConditioner conditioner_;
  int64_t utime_us_ = 0;
};

TEST(EfficiencyConditionerNTest, ALossOnRotorThreeIsFollowed) {
  ThreeRotorFeed feed;
  feed.Fly(kSettledS, {1.0, 1.0, 1.0});
  ASSERT_TRUE(feed.conditioner().airborne());
  EXPECT_EQ(feed.conditioner().efficiency(2), 1.0);
  // Rotor 3 loses 40 %, flagged (bit 2): mu / mu0 = 0.6, fault_tau_s 0.01 s.
  feed.Fly(0.1, {1.0, 1.0, 0.6}, 1 << 2);
  EXPECT_NEAR(feed.conditioner().efficiency(2), 0.6, 1e-3);
  EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  EXPECT_EQ(feed.conditioner().efficiency(1), 1.0);
  EXPECT_EQ(feed.conditioner().baseline(2), 1.0);  // the baseline holds while flagged
}

// A dead rotor: FORCE reports about 0 N with a sigma above it (the
// trirotor's rotor 3 at 0: 0.01-0.1 N, sigma 0.10-0.16 N), flown at the
// plausibility floor (MultiArmController::NoteReport sets the scale to
// 0.2). The sigma is judged against the rotors' mean hover thrust, not
// against the 0 N: followed. A sigma above that mean is not.
TEST(EfficiencyConditionerNTest, ADeadRotorsZeroIsFollowed) {
  const auto fly_dead = [](double sigma_n) {
    ThreeRotorFeed feed;
    feed.Fly(kSettledS, {1.0, 1.0, 1.0});
    for (int k = 0; k < 100; ++k) {
      RotorEfficiencyEstimate report = feed.Report({1.0, 1.0, 0.2}, 1 << 2, kStatusValid);
      report.force_n[2] = 0.02;
      report.force_std_n[2] = sigma_n;
      feed.Send(report);
    }
    return feed.conditioner().efficiency(2);
  };
  EXPECT_NEAR(fly_dead(0.12), 0.2, 1e-3);
  EXPECT_EQ(fly_dead(1.2 * kHoverSumN / 3.0), 1.0);
}

// Right after a loss the N-arm EKF rings (the trirotor: -0.93, 1.71, -0.99
// within 10 ms; the negative ones are refused before the conditioner,
// MultiArmController::OnEfficiency). The plausible 1.71 between reports of
// 0.6 moves e by at most max_rate_1_s x dt = 0.05 a period: at most 1.055
// (1.05, 1.005, 1.055, ...: the rate limit and fault_tau_s against the
// raw 1.71), and 0.6 within 1e-3 0.1 s after the ringing.
TEST(EfficiencyConditionerNTest, ARingingScaleIsNotPassedToTheRotors) {
  ThreeRotorFeed feed;
  feed.Fly(kSettledS, {1.0, 1.0, 1.0});
  const double ringing[8] = {1.71, 0.6, 1.71, 0.6, 0.6, 1.71, 0.6, 0.6};
  double last = feed.conditioner().efficiency(0);
  double highest = last;
  for (const double scale : ringing) {
    feed.Step({scale, 1.0, 1.0}, 1 << 0);
    const double e = feed.conditioner().efficiency(0);
    EXPECT_LE(std::abs(e - last), 0.05 + 1e-12);
    highest = std::max(highest, e);
    last = e;
  }
  EXPECT_LE(highest, 1.055 + 1e-9);
  feed.Fly(0.1, {0.6, 1.0, 1.0}, 1 << 0);
  EXPECT_NEAR(feed.conditioner().efficiency(0), 0.6, 1e-3);
}

// A rotor that reads stronger than its baseline is followed up to
// max_change_gain (1.2) and no further: a motor lag the file lacks swings a
// healthy rotor's scale to 2 and more beside another's loss. A loss is not
// bounded.
TEST(EfficiencyConditionerNTest, AGainIsFollowedUpToMaxChangeGain) {
  ThreeRotorFeed feed;
  feed.Fly(kSettledS, {1.0, 1.0, 1.0});
  feed.Fly(0.1, {2.3, 1.0, 0.5}, 1 << 2);
  EXPECT_NEAR(feed.conditioner().efficiency(0), 1.2, 1e-3);
  EXPECT_LE(feed.conditioner().efficiency(0), 1.2);
  EXPECT_NEAR(feed.conditioner().efficiency(2), 0.5, 1e-3);
  feed.Fly(0.1, {1.15, 1.0, 0.5}, 1 << 2);
  EXPECT_NEAR(feed.conditioner().efficiency(0), 1.15, 1e-3);
  EfficiencyParams unbounded;
  unbounded.max_change_gain = 10.0;
  ThreeRotorFeed free_feed(unbounded);
  free_feed.Fly(kSettledS, {1.0, 1.0, 1.0});
  free_feed.Fly(0.1, {2.3, 1.0, 0.5}, 1 << 2);
  EXPECT_NEAR(free_feed.conditioner().efficiency(0), 2.3, 1e-3);
}

// Every rotor at 0.85 of its map (c_T -15 %, thinner air) from take-off:
// no change (the baseline starts there), but mu0 = 0.85 is flown
// absolutely: a towards 0.85 with absolute_tau_s (0.2 s), 0.8510 after 1 s
// of trust (0.85 + 0.15 x 0.995^1000, as the birotor's test).
TEST(EfficiencyConditionerNTest, TheAbsoluteRuleFliesALearnedEfficiencyOnEveryRotor) {
  ThreeRotorFeed feed;
  feed.Fly(EfficiencyParams().airborne_s + EfficiencyParams().absolute_settle_s + 1.0, {0.85, 0.85, 0.85});
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(feed.conditioner().efficiency(i), 0.8510, 1e-4) << i;
    EXPECT_EQ(feed.conditioner().change(i), 1.0) << i;
  }
  feed.Fly(kSettledS - 1.4, {0.85, 0.85, 0.85});
  // A loss on top: rotor 2 at 0.51 = 0.85 x 0.6, flagged: e = a c = 0.51.
  feed.Fly(0.1, {0.85, 0.51, 0.85}, 1 << 1);
  EXPECT_NEAR(feed.conditioner().efficiency(1), 0.51, 2e-3);
}

TEST(EfficiencyConditionerNTest, AReportOfAnotherCountOrNotValidIsIgnored) {
  ThreeRotorFeed feed;
  RotorEfficiencyEstimate two = feed.Report({1.0, 1.0, 1.0}, 0, kStatusValid);
  two.n_rotors = 2;
  RotorEfficiencyEstimate invalid = feed.Report({1.0, 1.0, 1.0}, 0, 0);
  for (int k = 0; k < 1000; ++k) {
    two.utime = invalid.utime = 1000 * k;
    feed.conditioner().OnForce(two);
    feed.conditioner().OnForce(invalid);
  }
  EXPECT_FALSE(feed.conditioner().airborne());
  ForceEstimate birotor;  // a birotor FORCE to a three-rotor conditioner
  birotor.status = kStatusValid;
  feed.conditioner().OnForce(birotor);
  EXPECT_FALSE(feed.conditioner().airborne());
}

// Two rotors: the birotor's FORCE and its report through
// RotorEfficiencyReportOf give the same conditioner, bit for bit.
TEST(EfficiencyConditionerNTest, OnTwoRotorsTheForceAndItsReportAnswerAlike) {
  const double weight_n = 4.57624 * 9.81;
  EfficiencyConditioner from_force(EfficiencyParams(), weight_n);
  EfficiencyConditioner from_report(EfficiencyParams(), weight_n, 2);
  for (int k = 0; k < 3000; ++k) {
    ForceEstimate e;
    e.utime = 1000 * k;
    e.status = kStatusValid | (k >= 2000 ? kStatusRotor2Fault : 0);
    e.thrust_scale[0] = 0.9 + 0.001 * (k % 7);
    e.thrust_scale[1] = k >= 2000 ? (k % 3 == 0 ? 1.5 : 0.6) : 0.95;
    for (int i = 0; i < 2; ++i) {
      e.force_n[i] = 0.5 * weight_n * e.thrust_scale[i];
      e.force_std_n[i] = 0.02 * e.force_n[i];
    }
    from_force.OnForce(e);
    from_report.OnForce(RotorEfficiencyReportOf(e));
    from_force.Advance(kDtS, k % 500 != 0);
    from_report.Advance(kDtS, k % 500 != 0);
    for (int i = 0; i < 2; ++i) ASSERT_EQ(from_force.efficiency(i), from_report.efficiency(i)) << k;
  }
}

}  // namespace
}  // namespace birotor
