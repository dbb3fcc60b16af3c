// MismatchChangeRule and its use by EfficiencyConditioner: under a model
// mismatch (FORCE not VALID by MODEL_MISMATCH alone) a rotor the estimate
// flags is flown at its change relative to the unflagged rotors, once
// confirmed (fault held mismatch_confirm_s 0.03 s, a loss beyond
// mismatch_min_change 0.2, the change and the common factor steady within
// mismatch_max_spread 0.1), handed over with mismatch_handover_factor (2) x
// the time the fault was held; and nothing when the flags disagree. Reports
// at 1 kHz, the reference vehicle's weight (44.89 N), defaults of
// controller/controller_params.h. The figures are a payload's: mu 1.02 on
// both rotors before, rotor 1 at 60 % after (mu 0.53 / 0.88 as the mismatched
// EKF reports it, birotor-eval's payload_+15_loss_40).
#include "controller/mismatch_change_rule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "controller/efficiency_conditioner.h"

namespace birotor {
namespace {

constexpr double kWeightN = 4.57624 * 9.81;
constexpr int64_t kPeriodUs = 1000;

RotorEfficiencyEstimate Report(int64_t utime, const std::array<double, 3>& mu, int n_rotors, int32_t fault_bits,
                               int32_t status = kStatusModelMismatch) {
  RotorEfficiencyEstimate e;
  e.utime = utime;
  e.n_rotors = n_rotors;
  e.status = status;
  e.valid = (status & kStatusValid) != 0;
  e.rotor_fault_bits = fault_bits;
  for (int i = 0; i < n_rotors; ++i) {
    const size_t r = static_cast<size_t>(i);
    e.thrust_scale[r] = mu[r];
    e.force_n[r] = kWeightN / n_rotors;
    e.force_std_n[r] = 0.02 * e.force_n[r];
  }
  return e;
}

class RuleFeed {
 public:
  explicit RuleFeed(int n_rotors = 2, const EfficiencyParams& params = EfficiencyParams())
      : rule_(params, kWeightN, n_rotors), n_rotors_(n_rotors) {}
  void Fly(double seconds, const std::array<double, 3>& mu, int32_t fault_bits = 0) {
    const int samples = static_cast<int>(std::lround(seconds * 1e6 / kPeriodUs));
    for (int k = 0; k < samples; ++k) {
      rule_.OnMismatchedReport(Report(utime_us_, mu, n_rotors_, fault_bits));
      utime_us_ += kPeriodUs;
    }
  }
  MismatchChangeRule& rule() { return rule_; }

 private:
  MismatchChangeRule rule_;
  int n_rotors_;
  int64_t utime_us_ = 0;
};

TEST(MismatchedOnlyTest, OnlyModelMismatchWithdrawsValid) {
  EXPECT_TRUE(MismatchedOnly(kStatusModelMismatch));
  EXPECT_TRUE(MismatchedOnly(kStatusModelMismatch | kStatusRotor1Fault | kStatusMeasurementRejected));
  EXPECT_FALSE(MismatchedOnly(kStatusValid | kStatusModelMismatch));
  EXPECT_FALSE(MismatchedOnly(0));
  for (const int32_t other :
       {kStatusConverging, kStatusInputStale, kStatusFilterReset, kStatusNoMotorInput, kStatusInputConflict})
    EXPECT_FALSE(MismatchedOnly(kStatusModelMismatch | other)) << other;
}

TEST(MismatchChangeRuleTest, ALossAgainstTheOthersIsConfirmedAndFlown) {
  RuleFeed feed;
  feed.Fly(2.0, {1.02, 1.02, 0.0});
  feed.Fly(0.025, {0.53, 0.88, 0.0}, 1);
  EXPECT_FALSE(feed.rule().flown(0));  // held 25 ms of mismatch_confirm_s 30 ms
  feed.Fly(0.01, {0.53, 0.88, 0.0}, 1);
  ASSERT_TRUE(feed.rule().flown(0));
  // (0.53 / 1.02) / (0.88 / 1.02): what rotor 1 makes against rotor 2.
  EXPECT_NEAR(feed.rule().target(0), 0.53 / 0.88, 1e-9);
  EXPECT_NEAR(feed.rule().handover_tau_s(0), 2.0 * 0.030, 0.0021);  // twice the 30-31 ms the fault was held
  EXPECT_FALSE(feed.rule().flown(1));
  EXPECT_EQ(feed.rule().target(1), 1.0);
  // The rotor is flown as long as the change lasts; back within
  // change_threshold (0.1) it is not.
  feed.Fly(1.0, {0.53, 0.88, 0.0}, 1);
  EXPECT_TRUE(feed.rule().flown(0));
  feed.Fly(0.01, {0.86, 0.88, 0.0}, 0);
  EXPECT_FALSE(feed.rule().flown(0));
}

TEST(MismatchChangeRuleTest, TheCommonFactorIsTheUnflaggedRotorsMean) {
  // Three rotors: rotor 2 at half of what rotors 1 and 3 make (0.9, 1.0 of their baselines).
  RuleFeed feed(3);
  feed.Fly(2.0, {1.0, 1.0, 1.0});
  feed.Fly(0.1, {0.9, 0.475, 1.0}, 2);
  ASSERT_TRUE(feed.rule().flown(1));
  EXPECT_NEAR(feed.rule().target(1), 0.475 / 0.95, 1e-9);
  EXPECT_FALSE(feed.rule().flown(0));
  EXPECT_FALSE(feed.rule().flown(2));
}

TEST(MismatchChangeRuleTest, WhatAMismatchDoesIsNotFlown) {
  {
    // A change within mismatch_min_change (a loss of 15 % against the other).
    RuleFeed feed;
    feed.Fly(2.0, {1.0, 1.0, 0.0});
    feed.Fly(0.5, {0.85, 1.0, 0.0}, 1);
    EXPECT_FALSE(feed.rule().flown(0));
  }
  {
    // A gain is not flown.
    RuleFeed feed;
    feed.Fly(2.0, {1.0, 1.0, 0.0});
    feed.Fly(0.5, {1.4, 1.0, 0.0}, 1);
    EXPECT_FALSE(feed.rule().flown(0));
  }
  {
    // Before the baselines settled (baseline_tau_s, 1 s): they may hold the fault already.
    RuleFeed feed;
    feed.Fly(0.5, {1.0, 1.0, 0.0});
    feed.Fly(0.01, {0.6, 1.0, 0.0}, 1);
    feed.Fly(2.0, {0.6, 1.0, 0.0}, 0);
    feed.Fly(0.5, {0.3, 1.0, 0.0}, 1);
    EXPECT_TRUE(feed.rule().distrusted());
    EXPECT_FALSE(feed.rule().flown(0));
  }
  {
    // The rotors flagged by turns (a motor lag the file lacks): distrusted
    // until VALID, a steady loss afterwards included.
    RuleFeed feed;
    feed.Fly(2.0, {1.0, 1.0, 0.0});
    feed.Fly(0.02, {0.6, 1.0, 0.0}, 1);
    feed.Fly(0.02, {1.0, 0.6, 0.0}, 2);
    feed.Fly(0.5, {0.6, 1.0, 0.0}, 1);
    EXPECT_TRUE(feed.rule().distrusted());
    EXPECT_FALSE(feed.rule().flown(0));
    feed.rule().Reset();  // a VALID report
    EXPECT_FALSE(feed.rule().distrusted());
  }
  {
    // Not steady: the change swings by 0.2 every 10 ms.
    RuleFeed feed;
    feed.Fly(2.0, {1.0, 1.0, 0.0});
    for (int k = 0; k < 20; ++k) {
      feed.Fly(0.01, {0.5, 1.0, 0.0}, 1);
      feed.Fly(0.01, {0.7, 1.0, 0.0}, 1);
    }
    EXPECT_FALSE(feed.rule().flown(0));
  }
  {
    // Every rotor flagged: nothing to compare with.
    RuleFeed feed;
    feed.Fly(2.0, {1.0, 1.0, 0.0});
    feed.Fly(0.5, {0.5, 0.5, 0.0}, 3);
    EXPECT_FALSE(feed.rule().flown(0));
    EXPECT_FALSE(feed.rule().flown(1));
  }
  {
    // Flown, then wandering beyond mismatch_max_spread from the confirmed change.
    RuleFeed feed;
    feed.Fly(2.0, {1.0, 1.0, 0.0});
    feed.Fly(0.05, {0.6, 1.0, 0.0}, 1);
    ASSERT_TRUE(feed.rule().flown(0));
    feed.Fly(0.01, {0.45, 1.0, 0.0}, 1);
    EXPECT_TRUE(feed.rule().distrusted());
    EXPECT_FALSE(feed.rule().flown(0));
  }
}

// The conditioner flies the confirmed change while the mismatched reports
// are on time (Advance's change_usable), and only then.
class ConditionerFeed {
 public:
  explicit ConditionerFeed(const EfficiencyParams& params = EfficiencyParams()) : conditioner_(params, kWeightN) {}
  void Fly(double seconds, double mu1, double mu2, int32_t fault_bits, bool change_usable = true) {
    const int samples = static_cast<int>(std::lround(seconds * 1e6 / kPeriodUs));
    for (int k = 0; k < samples; ++k) {
      conditioner_.OnMismatchedForce(Report(utime_us_, {mu1, mu2, 0.0}, 2, fault_bits));
      conditioner_.Advance(kPeriodUs * 1e-6, false, change_usable);
      utime_us_ += kPeriodUs;
    }
  }
  const EfficiencyConditioner& conditioner() const { return conditioner_; }

 private:
  EfficiencyConditioner conditioner_;
  int64_t utime_us_ = 0;
};

TEST(MismatchChangeRuleTest, TheConditionerFliesTheConfirmedLoss) {
  ConditionerFeed feed;
  feed.Fly(2.0, 1.02, 1.02, 0);
  EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  feed.Fly(0.5, 0.53, 0.88, 1);
  // 0.47 s after the hand-over began, tau 0.06 s (rate limited at first): at the target.
  EXPECT_NEAR(feed.conditioner().efficiency(0), 0.53 / 0.88, 1e-3);
  EXPECT_EQ(feed.conditioner().efficiency(1), 1.0);
  EXPECT_EQ(feed.conditioner().absolute(0), 1.0);  // nothing absolute is flown under a mismatch
}

TEST(MismatchChangeRuleTest, NotFlownUnlessAskedAndOnTime) {
  {
    EfficiencyParams off;
    off.mismatch_relative = false;
    ConditionerFeed feed(off);
    feed.Fly(2.0, 1.02, 1.02, 0);
    feed.Fly(0.5, 0.53, 0.88, 1);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  }
  {
    ConditionerFeed feed;
    feed.Fly(2.0, 1.02, 1.02, 0, false);
    feed.Fly(0.5, 0.53, 0.88, 1, false);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  }
}

}  // namespace
}  // namespace birotor
