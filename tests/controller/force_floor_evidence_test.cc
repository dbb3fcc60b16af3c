// ForceFloorEvidence (controller/force_floor_evidence.h) for three rotors
// (the trirotor's count, config/vehicles/trirotor.yaml) on the defaults of
// SupervisionParams (min_plausible_thrust_scale 0.2, max 2, at_floor_samples
// 5, clock windows 0.2 s past / 0.01 s future) and the low-pass of
// efficiency.infeasible_s (0.1 s): a flagged rotor below the floor flown at
// the floor, the low-pass, the reports it refuses; and the birotor's FORCE
// giving the answers of its converted report.
#include "controller/force_floor_evidence.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "samples/samples.h"

namespace birotor {
namespace {

constexpr int kRotors = 3;
constexpr double kLowPassS = 0.1;  // EfficiencyParams::infeasible_s

std::array<double, kMaxArms> Ones() {
  std::array<double, kMaxArms> ones;
  ones.fill(1.0);
  return ones;
}

// A VALID three-rotor report at utime, rotor 2 (index 1) at scale2, flagged or not.
RotorEfficiencyEstimate Report(int64_t utime, double scale2, bool flagged2) {
  RotorEfficiencyEstimate report;
  report.utime = utime;
  report.n_rotors = kRotors;
  report.valid = true;
  report.thrust_scale = {1.0, scale2, 1.0};
  report.rotor_fault_bits = flagged2 ? 2 : 0;
  return report;
}

TEST(ForceFloorEvidenceTest, FlaggedRotorBelowTheFloorIsFlownAtTheFloorAfterAtFloorSamples) {
  const SupervisionParams params;
  ForceFloorEvidence evidence(params, kLowPassS, kRotors);
  // The first at_floor_samples - 1 (4) reports keep their scale (the caller refuses them).
  for (int k = 1; k < params.at_floor_samples; ++k) {
    RotorEfficiencyEstimate report = Report(1000 * k, 0.15, true);
    EXPECT_EQ(evidence.FlyAtTheFloor(&report), 0) << k;
    EXPECT_EQ(report.thrust_scale[1], 0.15) << k;
  }
  // The 5th in a row and every later one: the floor, the other rotors untouched.
  for (int k = params.at_floor_samples; k < params.at_floor_samples + 3; ++k) {
    RotorEfficiencyEstimate report = Report(1000 * k, 0.15, true);
    EXPECT_EQ(evidence.FlyAtTheFloor(&report), 1) << k;
    EXPECT_EQ(report.thrust_scale[0], 1.0);
    EXPECT_EQ(report.thrust_scale[1], params.min_plausible_thrust_scale);
    EXPECT_EQ(report.thrust_scale[2], 1.0);
  }
  // One unflagged report ends the run: 4 more flagged ones are refused again.
  RotorEfficiencyEstimate unflagged = Report(9000, 0.15, false);
  EXPECT_EQ(evidence.FlyAtTheFloor(&unflagged), 0);
  EXPECT_EQ(unflagged.thrust_scale[1], 0.15);
  for (int k = 1; k < params.at_floor_samples; ++k) {
    RotorEfficiencyEstimate report = Report(9000 + 1000 * k, 0.15, true);
    EXPECT_EQ(evidence.FlyAtTheFloor(&report), 0) << k;
  }
  // Rotor 3 flagged below the floor has its own run; rotor 1 above the floor is never set.
  RotorEfficiencyEstimate both = Report(20000, 0.15, true);
  both.thrust_scale[2] = 0.1;
  both.rotor_fault_bits = 2 | 4;
  EXPECT_EQ(evidence.FlyAtTheFloor(&both), 1);  // rotor 2's 5th, rotor 3's 1st
  EXPECT_EQ(both.thrust_scale[2], 0.1);
}

// The mean of a run of flagged reports below the floor, negatives as they
// are (a dead rotor's scatter about 0): NaN until the run is
// at_floor_samples long, then the run's mean; one unflagged report, or one
// at the floor, ends it.
TEST(ForceFloorEvidenceTest, BelowTheFloorReportsAreAveragedOverTheirRun) {
  const SupervisionParams params;
  ForceFloorEvidence evidence(params, kLowPassS, kRotors);
  const double scales[6] = {0.04, -0.06, 0.02, -0.01, 0.06, 0.01};
  double sum = 0.0;
  for (int k = 0; k < 6; ++k) {
    RotorEfficiencyEstimate report = Report(1000 * (k + 1), scales[k], true);
    evidence.FlyAtTheFloor(&report);
    sum += scales[k];
    if (k + 1 < params.at_floor_samples) {
      EXPECT_TRUE(std::isnan(evidence.below_floor_mean(1))) << k;
    } else {
      EXPECT_NEAR(evidence.below_floor_mean(1), sum / (k + 1), 1e-15) << k;
    }
    EXPECT_TRUE(std::isnan(evidence.below_floor_mean(0))) << k;
  }
  RotorEfficiencyEstimate unflagged = Report(7000, 0.0, false);
  evidence.FlyAtTheFloor(&unflagged);
  EXPECT_TRUE(std::isnan(evidence.below_floor_mean(1)));
  for (int k = 0; k < params.at_floor_samples; ++k) {
    RotorEfficiencyEstimate report = Report(8000 + 1000 * k, 0.1, true);
    evidence.FlyAtTheFloor(&report);
  }
  EXPECT_NEAR(evidence.below_floor_mean(1), 0.1, 1e-15);
  RotorEfficiencyEstimate at_floor = Report(20000, params.min_plausible_thrust_scale, true);
  evidence.FlyAtTheFloor(&at_floor);
  EXPECT_TRUE(std::isnan(evidence.below_floor_mean(1)));
}

TEST(ForceFloorEvidenceTest, NotValidNegativeOrAtTheFloorIsNotFlownAtTheFloor) {
  const SupervisionParams params;
  ForceFloorEvidence invalid_evidence(params, kLowPassS, kRotors);
  ForceFloorEvidence negative_evidence(params, kLowPassS, kRotors);
  ForceFloorEvidence at_floor_evidence(params, kLowPassS, kRotors);
  for (int k = 0; k < 2 * params.at_floor_samples; ++k) {
    RotorEfficiencyEstimate invalid = Report(1000 * k, 0.15, true);
    invalid.valid = false;
    EXPECT_EQ(invalid_evidence.FlyAtTheFloor(&invalid), 0);
    RotorEfficiencyEstimate negative = Report(1000 * k, -0.1, true);  // below 0: not a scale
    EXPECT_EQ(negative_evidence.FlyAtTheFloor(&negative), 0);
    EXPECT_EQ(negative.thrust_scale[1], -0.1);
    RotorEfficiencyEstimate at_floor = Report(1000 * k, params.min_plausible_thrust_scale, true);  // plausible
    EXPECT_EQ(at_floor_evidence.FlyAtTheFloor(&at_floor), 0);
  }
}

// r_k = r_k-1 + min(1, dt / 0.1 s) (s_k / b - r_k-1), r_0 = 1: every VALID
// report, refused ones included (0.15 is below the floor), each rotor over
// its baseline b; a scale above max_plausible_thrust_scale leaves its
// rotor's value.
TEST(ForceFloorEvidenceTest, ReportsAreLowPassedOverTheInfeasibleTime) {
  const SupervisionParams params;
  ForceFloorEvidence evidence(params, kLowPassS, kRotors);
  std::array<double, kMaxArms> baseline = Ones();
  baseline[2] = 0.8;  // rotor 3 learnt at 0.8: a report of 0.8 is its 1
  for (int k = 0; k < kRotors; ++k) EXPECT_EQ(evidence.reported_scale(k), 1.0);
  double expected = 1.0;
  for (int k = 0; k < 100; ++k) {  // 1 kHz for 0.1 s
    const int64_t utime = 1000000 + 1000 * k;
    RotorEfficiencyEstimate report = Report(utime, 0.15, false);
    report.thrust_scale[2] = 0.8;
    evidence.Note(report, utime, baseline);
    const double gain = k == 0 ? 0.0 : 1e-3 / kLowPassS;  // the first report has no interval
    expected += gain * (0.15 - expected);
    EXPECT_NEAR(evidence.reported_scale(1), expected, 1e-12) << k;
  }
  // After 99 intervals of 1 ms: 0.15 + 0.85 x 0.99^99 = 0.4643.
  EXPECT_NEAR(evidence.reported_scale(1), 0.15 + 0.85 * std::pow(0.99, 99), 1e-12);
  EXPECT_EQ(evidence.reported_scale(0), 1.0);
  EXPECT_NEAR(evidence.reported_scale(2), 1.0, 1e-12);
  // A gap longer than the time constant takes the report whole (gain 1).
  RotorEfficiencyEstimate late = Report(1300000, 0.5, false);
  late.thrust_scale[0] = 2.5;  // above max_plausible_thrust_scale: rotor 1 keeps its value
  evidence.Note(late, 1300000, Ones());
  EXPECT_EQ(evidence.reported_scale(1), 0.5);
  EXPECT_EQ(evidence.reported_scale(0), 1.0);
}

TEST(ForceFloorEvidenceTest, RefusesReportsOutsideTheClockWindowsOldOrNotValid) {
  const SupervisionParams params;
  ForceFloorEvidence evidence(params, kLowPassS, kRotors);
  const int64_t now_us = 10000000;
  evidence.Note(Report(now_us - 1000, 1.0, false), now_us, Ones());  // the newest taken: 9.999 s
  const auto unchanged = [&](const RotorEfficiencyEstimate& report, int64_t at_us) {
    evidence.Note(report, at_us, Ones());
    return evidence.reported_scale(1) == 1.0;
  };
  // Older than clock_past_window_s (0.2 s) at its arrival.
  EXPECT_TRUE(unchanged(Report(now_us, 0.3, false), now_us + 200001));
  // Ahead of the clock by more than clock_future_window_s (0.01 s).
  EXPECT_TRUE(unchanged(Report(now_us + 10001, 0.3, false), now_us));
  // Not newer than the newest taken.
  EXPECT_TRUE(unchanged(Report(now_us - 1000, 0.3, false), now_us));
  EXPECT_TRUE(unchanged(Report(now_us - 2000, 0.3, false), now_us));
  // Not VALID.
  RotorEfficiencyEstimate invalid = Report(now_us, 0.3, false);
  invalid.valid = false;
  EXPECT_TRUE(unchanged(invalid, now_us));
  // Within the windows and newer: taken, 6 ms after the newest (gain 0.06).
  EXPECT_FALSE(unchanged(Report(now_us + 5000, 0.3, false), now_us));
  EXPECT_NEAR(evidence.reported_scale(1), 1.0 + 0.06 * (0.3 - 1.0), 1e-12);
}

TEST(ForceFloorEvidenceTest, ReportOfAnotherRotorCountIsNoEvidence) {
  const SupervisionParams params;
  ForceFloorEvidence evidence(params, kLowPassS, kRotors);
  EXPECT_EQ(evidence.rotor_count(), 3);
  // Four flagged reports, then one of 2 rotors (another vehicle's): it sets
  // nothing and ends the run, so the next four are refused again.
  for (int k = 1; k < params.at_floor_samples; ++k) {
    RotorEfficiencyEstimate report = Report(1000 * k, 0.15, true);
    EXPECT_EQ(evidence.FlyAtTheFloor(&report), 0);
  }
  RotorEfficiencyEstimate two = Report(5000, 0.15, true);
  two.n_rotors = 2;
  EXPECT_EQ(evidence.FlyAtTheFloor(&two), 0);
  EXPECT_EQ(two.thrust_scale[1], 0.15);
  for (int k = 1; k < params.at_floor_samples; ++k) {
    RotorEfficiencyEstimate report = Report(5000 + 1000 * k, 0.15, true);
    EXPECT_EQ(evidence.FlyAtTheFloor(&report), 0);
  }
  // Nor is it noted, nor does it become the newest.
  evidence.Note(Report(100000, 1.0, false), 100000, Ones());
  two.utime = 200000;
  evidence.Note(two, 200000, Ones());
  EXPECT_EQ(evidence.reported_scale(1), 1.0);
  evidence.Note(Report(150000, 0.5, false), 150000, Ones());
  EXPECT_NEAR(evidence.reported_scale(1), 1.0 + 0.5 * (0.5 - 1.0), 1e-12);  // 50 ms after the newest
}

// The birotor's FORCE (VehicleController) goes through the same code: its
// fault bits kStatusRotor1Fault / kStatusRotor2Fault are rotor_fault_bits
// 1 / 2, and its answers are its converted report's, to the bit.
TEST(ForceFloorEvidenceTest, BirotorForceGivesItsReportsAnswers) {
  const SupervisionParams params;
  ForceFloorEvidence birotor(params, kLowPassS, kBirotorRotors);
  ForceFloorEvidence generic(params, kLowPassS, kBirotorRotors);
  const double baseline[kBirotorRotors] = {1.0, 0.9};
  std::array<double, kMaxArms> baselines = Ones();
  baselines[1] = 0.9;
  for (int k = 0; k < 20; ++k) {
    ForceEstimate force;
    force.utime = 1000 * (k + 1);
    force.thrust_scale[0] = 0.9 - 0.01 * k;
    force.thrust_scale[1] = 0.17;
    force.status = kStatusValid | kStatusRotor2Fault | (k % 7 == 3 ? kStatusRotor1Fault : 0);
    const RotorEfficiencyEstimate report = RotorEfficiencyReportOf(force);
    EXPECT_EQ(report.n_rotors, 2);
    EXPECT_TRUE(report.valid);
    EXPECT_EQ(report.rotor_fault_bits, k % 7 == 3 ? 3 : 2);
    ForceEstimate flown = force;
    RotorEfficiencyEstimate flown_report = report;
    EXPECT_EQ(birotor.FlyAtTheFloor(&flown), generic.FlyAtTheFloor(&flown_report));
    for (int i = 0; i < kBirotorRotors; ++i) EXPECT_EQ(flown.thrust_scale[i], flown_report.thrust_scale[i]);
    birotor.Note(force, force.utime, baseline);
    generic.Note(report, force.utime, baselines);
    for (int i = 0; i < kBirotorRotors; ++i) EXPECT_EQ(birotor.reported_scale(i), generic.reported_scale(i));
  }
  ForceEstimate last;
  last.thrust_scale[1] = 0.17;
  last.status = kStatusValid | kStatusRotor2Fault;
  EXPECT_EQ(birotor.FlyAtTheFloor(&last), 1);  // the 21st flagged in a row
  EXPECT_EQ(last.thrust_scale[1], params.min_plausible_thrust_scale);
}

}  // namespace
}  // namespace birotor
