// EfficiencyConditioner's absolute rule (issue 36 item 5): a trusted mu0 is
// flown itself, e_i = a_i c_i with a_i first order towards mu0_i
// (absolute_tau_s), and only while FORCE is VALID, neither MODEL_MISMATCH nor
// CONVERGING, precise and beyond absolute_threshold and absolute_min_sigmas
// of its own sigma. FORCE at 1 kHz, one
// Advance per sample (dt 1 ms). The reference vehicle's weight 4.57624 x
// 9.81 = 44.89 N, each rotor making half of it. Expected figures are the
// discrete first-order step a += (goal - a) dt / tau (tau 0.2 s: 0.995 per
// step; decay_s 3 s) from the defaults of controller/controller_params.h.
#include "controller/efficiency_conditioner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace birotor {
namespace {

constexpr double kWeightN = 4.57624 * 9.81;
constexpr double kDtS = 0.001;

class ConditionerFeed {
 public:
  explicit ConditionerFeed(const EfficiencyParams& params) : conditioner_(params, kWeightN) {}

  // seconds of FORCE with these scales and status, each sample followed by a period.
  void Fly(double seconds, double mu1, double mu2, int32_t status = kStatusValid, double relative_std = 0.005,
           bool usable = true) {
    const int samples = static_cast<int>(std::lround(seconds / kDtS));
    for (int k = 0; k < samples; ++k) {
      ForceEstimate e;
      e.utime = utime_us_;
      e.status = status;
      e.thrust_scale[0] = mu1;
      e.thrust_scale[1] = mu2;
      for (int i = 0; i < kBirotorRotors; ++i) {
        e.force_n[i] = 0.5 * kWeightN;
        e.force_std_n[i] = relative_std * e.force_n[i];
      }
      if (usable) conditioner_.OnForce(e);
      conditioner_.Advance(kDtS, usable);
      utime_us_ += 1000;
    }
  }
  const EfficiencyConditioner& conditioner() const { return conditioner_; }

 private:
  EfficiencyConditioner conditioner_;
  int64_t utime_us_ = 0;
};

// airborne_s (0.05 s) to airborne, then absolute_settle_s (0.02 s) to trust.
const double kTrustedFromS = EfficiencyParams().airborne_s + EfficiencyParams().absolute_settle_s;

TEST(EfficiencyConditionerTest, TrustedOffsetIsFollowedWithAbsoluteTau) {
  ConditionerFeed feed{EfficiencyParams()};
  feed.Fly(kTrustedFromS - 0.01, 0.85, 0.85);
  EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);  // not yet trusted: the integrators' job
  EXPECT_EQ(feed.conditioner().baseline(0), 0.85);   // mu0 starts on the first airborne sample
  feed.Fly(0.01 + 0.2, 0.85, 0.85);
  // 0.2 s = one tau: a = 0.85 + 0.15 x 0.995^200 = 0.9051 (+-1 step at the settle boundary: +-0.0008).
  EXPECT_NEAR(feed.conditioner().efficiency(0), 0.9051, 0.0008);
  EXPECT_NEAR(feed.conditioner().absolute(1), 0.9051, 0.0008);
  EXPECT_EQ(feed.conditioner().change(0), 1.0);  // nothing flagged: the change factor stays 1
  feed.Fly(0.8, 0.85, 0.85);
  // 1 s = 5 tau: 0.85 + 0.15 x 0.995^1000 = 0.8510.
  EXPECT_NEAR(feed.conditioner().efficiency(0), 0.8510, 1e-4);
}

TEST(EfficiencyConditionerTest, ALossOnTopMultipliesTheAbsoluteFactor) {
  ConditionerFeed feed{EfficiencyParams()};
  feed.Fly(kTrustedFromS + 1.5, 0.85, 0.85);
  ASSERT_NEAR(feed.conditioner().absolute(0), 0.85, 1e-4);
  // Rotor 1 loses 40 % of what it made: mu 0.51, |0.51 / 0.85 - 1| = 0.4 > change_threshold, flagged.
  feed.Fly(0.1, 0.51, 0.85, kStatusValid | kStatusRotor1Fault);
  EXPECT_NEAR(feed.conditioner().change(0), 0.6, 1e-3);       // mu / mu0 with fault_tau_s 0.01 s, 10 taus
  EXPECT_NEAR(feed.conditioner().efficiency(0), 0.51, 1e-3);  // a c = 0.85 x 0.6: what the rotor makes
  EXPECT_NEAR(feed.conditioner().absolute(0), 0.85, 1e-4);    // the baseline holds while flagged
  EXPECT_NEAR(feed.conditioner().efficiency(1), 0.85, 1e-4);
}

TEST(EfficiencyConditionerTest, MismatchConvergingImpreciseOrMatchedAreNotFlownAbsolutely) {
  const EfficiencyParams params;
  {
    ConditionerFeed feed{params};
    feed.Fly(2.0, 0.85, 0.85, kStatusValid | kStatusModelMismatch);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  }
  {
    ConditionerFeed feed{params};
    feed.Fly(2.0, 0.85, 0.85, kStatusValid | kStatusConverging);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  }
  {
    // force_std / force 0.06 > absolute_max_relative_sigma 0.05.
    ConditionerFeed feed{params};
    feed.Fly(2.0, 0.85, 0.85, kStatusValid, 0.06);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  }
  {
    // |mu0 - 1| = 0.04 within absolute_threshold 0.05: a matched vehicle's wander.
    ConditionerFeed feed{params};
    feed.Fly(2.0, 0.96, 1.04);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
    EXPECT_EQ(feed.conditioner().efficiency(1), 1.0);
  }
  {
    EfficiencyParams off = params;
    off.absolute_tau_s = 0.0;  // the issue 25 rule
    ConditionerFeed feed{off};
    feed.Fly(2.0, 0.85, 0.85);
    EXPECT_EQ(feed.conditioner().efficiency(0), 1.0);
  }
}

// A filter still converging (a noisy accelerometer whose noise it is
// learning): mu from 0.93 to 1 over 1 s, its relative sigma from 3 % to
// 0.5 %. mu0 (baseline_tau_s 1 s) is off by 0.07 at first, beyond
// absolute_threshold, but within 4 of its own low-passed sigmas (0.12):
// nothing is flown. The lowest efficiency flown over the 3 s.
double LowestEfficiencyWhileConverging(const EfficiencyParams& params) {
  ConditionerFeed feed{params};
  double lowest = 1.0;
  for (int step = 0; step < 300; ++step) {
    const double t_s = 0.01 * step;
    const double progress = std::min(1.0, t_s);
    const double mu = 0.93 + 0.07 * progress;
    feed.Fly(0.01, mu, mu, kStatusValid, 0.03 - 0.025 * progress);
    lowest = std::min(lowest, feed.conditioner().efficiency(0));
  }
  return lowest;
}

TEST(EfficiencyConditionerTest, AConvergingFiltersEarlyOffsetIsNotFlown) {
  const EfficiencyParams params;
  EXPECT_EQ(LowestEfficiencyWhileConverging(params), 1.0);
  EfficiencyParams without = params;
  without.absolute_min_sigmas = 0.0;  // the threshold alone flies the early mu0
  EXPECT_LT(LowestEfficiencyWhileConverging(without), 0.98);
}

TEST(EfficiencyConditionerTest, AbsoluteFactorIsBoundedAndHysteretic) {
  const EfficiencyParams params;
  ConditionerFeed feed{params};
  feed.Fly(kTrustedFromS + 2.0, 0.6, 1.2);
  EXPECT_NEAR(feed.conditioner().efficiency(0), params.min_absolute_efficiency, 1e-4);  // 0.7
  EXPECT_NEAR(feed.conditioner().efficiency(1), 1.2, 1e-4);                             // within the 1.3 bound
  // mu0 drifting back to 0.97 (|0.03| between half the threshold and the threshold): still flown.
  ConditionerFeed drift{params};
  drift.Fly(kTrustedFromS + 2.0, 0.9, 0.9);
  drift.Fly(6.0, 0.97, 0.97);  // baseline_tau_s 1 s: mu0 at 0.97 within 0.07 e^-6
  EXPECT_NEAR(drift.conditioner().efficiency(0), 0.97, 1e-3);
  drift.Fly(6.0, 0.99, 0.99);  // |0.01| below half of it: back to 1
  EXPECT_NEAR(drift.conditioner().efficiency(0), 1.0, 1e-3);
}

TEST(EfficiencyConditionerTest, FallbackDecaysTheAbsoluteFactorContinuously) {
  const EfficiencyParams params;
  ConditionerFeed feed{params};
  feed.Fly(kTrustedFromS + 1.5, 0.85, 0.85);
  const double before = feed.conditioner().efficiency(0);
  ASSERT_NEAR(before, 0.85, 1e-4);
  feed.Fly(0.001, 0.85, 0.85, kStatusValid, 0.005, /*usable=*/false);
  // One period of fallback moves e by (1 - 0.85) x dt / decay_s = 5e-5: no jump.
  EXPECT_NEAR(feed.conditioner().efficiency(0) - before, 0.15 * kDtS / params.decay_s, 1e-6);
  feed.Fly(2.999, 0.85, 0.85, kStatusValid, 0.005, /*usable=*/false);
  // decay_s 3 s: 1 - 0.15 x (1 - 1/3000)^3000 = 1 - 0.15 e^-1 = 0.9448.
  EXPECT_NEAR(feed.conditioner().efficiency(0), 0.9448, 2e-4);
}

}  // namespace
}  // namespace birotor
