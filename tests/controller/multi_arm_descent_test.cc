// The N-rotor controller's degraded flight (issue 38): HoverFeasibility on
// N rotors (at N = 2 the birotor's answers on the same inputs; the trirotor
// of config/vehicles/trirotor.yaml feasible after 40 % on rotor 1, not after
// 70 or 80 %) and MultiArmController's controlled descent (entered after
// infeasible_s, counted once, commands slewed by degraded_omega_rate_rad_s2,
// levelling first; POSE lost: the descent without the latch; a loss whose
// reports are refused below the floor found from the sink, its weak rotor
// from the low-passed reports). Defaults of
// ControllerConfig (config/controller.yaml's). The flown descents (tilt,
// touchdown against the floor) are tests/evaluation/multi_arm_closed_loop_test.cc's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "controller/hover_feasibility.h"
#include "controller/hover_space.h"
#include "controller/multi_arm_controller.h"
#include "model/multi_arm_linearization.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {
namespace {

constexpr double kDtS = 0.002;                                // 500 Hz, rate_hz
constexpr double kMaxRotorForceN = 4.6e-5 * 1200.0 * 1200.0;  // c_T omega_max^2, 66.24 N
constexpr double kWeightN = 4.57624 * 9.81;                   // the reference birotor [N]

VehicleDescription Trirotor() {
  return LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
}

HoverFeasibility TrirotorFeasibility() {
  const VehicleDescription vehicle = Trirotor();
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  const double max_n[3] = {kMaxRotorForceN, kMaxRotorForceN, kMaxRotorForceN};
  const double hover_n[3] = {hover.force_n(0), hover.force_n(1), hover.force_n(2)};
  return HoverFeasibility(EfficiencyParams(), 3, max_n, hover_n);
}

// Runs one second of in; returns the phase.
HoverFeasibility::Phase RunOneSecond(HoverFeasibility* f, const FeasibilityInputs& in) {
  for (int k = 0; k < 500; ++k) f->Update(in, kDtS);
  return f->phase();
}

// N = 2 with each rotor hovering at weight / 2 is the birotor's constructor:
// the same bound (0.3457, hover_feasibility_test.cc) and, period by period,
// the same phase, weak rotor and latched efficiency on the same inputs
// (efficiencies on either side, a sink with FORCE apart or not).
TEST(MultiArmFeasibilityTest, TwoRotorsGiveTheBirotorsAnswers) {
  const double max_n[2] = {kMaxRotorForceN, kMaxRotorForceN};
  const double hover_n[2] = {0.5 * kWeightN, 0.5 * kWeightN};
  const double efficiency_pairs[4][2] = {{1.0, 0.3}, {0.3, 1.0}, {0.5, 0.34}, {0.36, 0.9}};
  for (const auto& pair : efficiency_pairs) {
    for (const bool sink : {false, true}) {
      HoverFeasibility birotor(EfficiencyParams(), kMaxRotorForceN, kWeightN);
      HoverFeasibility n_rotor(EfficiencyParams(), 2, max_n, hover_n);
      EXPECT_EQ(n_rotor.FeasibilityBound(0), birotor.FeasibilityBound());
      EXPECT_EQ(n_rotor.FeasibilityBound(1), birotor.FeasibilityBound());
      FeasibilityInputs in;
      in.efficiency[0] = sink ? 1.0 : pair[0];
      in.efficiency[1] = sink ? 1.0 : pair[1];
      in.reported_scale[0] = pair[0];
      in.reported_scale[1] = pair[1];
      in.command_rad_s[0] = 900.0;
      in.command_rad_s[1] = 1200.0;
      in.allocation_limited = sink;
      in.altitude_lag_m = sink ? 0.3 : 0.0;
      in.sink_behind_m_s = sink ? 0.5 : 0.0;
      in.following_force = true;
      for (int k = 0; k < 200; ++k) {
        in.tilt_rad = k < 100 ? 0.2 : 0.01;
        ASSERT_EQ(n_rotor.Update(in, kDtS), birotor.Update(in, kDtS)) << k;
        ASSERT_EQ(n_rotor.weak_rotor(), birotor.weak_rotor()) << k;
        ASSERT_EQ(n_rotor.weak_efficiency(), birotor.weak_efficiency()) << k;
        ASSERT_EQ(n_rotor.cause(), birotor.cause()) << k;
      }
    }
  }
}

// The trirotor hovers rotor 1 at 27.47 N and rotors 2 and 3 at 14.32 N
// (trirotor.yaml's header), so the bounds are 1.02 x 27.47 / 66.24 = 0.4230
// and 1.02 x 14.32 / 66.24 = 0.2205 (the deflected hover within 1e-3).
TEST(MultiArmFeasibilityTest, TrirotorBoundsFollowEachRotorsHoverThrust) {
  const HoverFeasibility f = TrirotorFeasibility();
  EXPECT_NEAR(f.FeasibilityBound(0), 0.4230, 1e-3);
  EXPECT_NEAR(f.FeasibilityBound(1), 0.2205, 1e-3);
  EXPECT_NEAR(f.FeasibilityBound(2), 0.2205, 1e-3);
}

TEST(MultiArmFeasibilityTest, TrirotorFeasibleAtFortyPercentInfeasibleAtSeventyAndEightyOnRotorOne) {
  for (const double e1 : {0.6, 0.3, 0.2}) {
    HoverFeasibility f = TrirotorFeasibility();
    FeasibilityInputs in;
    in.efficiency[0] = e1;
    in.following_force = true;
    const bool infeasible = e1 < 0.4230;
    EXPECT_EQ(RunOneSecond(&f, in) != HoverFeasibility::Phase::kFeasible, infeasible) << e1;
    if (!infeasible) continue;
    EXPECT_EQ(f.weak_rotor(), 0) << e1;
    EXPECT_EQ(f.weak_efficiency(), e1) << e1;
  }
  // 70 % on rotor 2 (0.3 > 0.2205): still feasible, the weight is on rotor 1.
  HoverFeasibility f = TrirotorFeasibility();
  FeasibilityInputs in;
  in.efficiency[1] = 0.3;
  in.following_force = true;
  EXPECT_EQ(RunOneSecond(&f, in), HoverFeasibility::Phase::kFeasible);
}

// With the trirotor's hovers (HoverSpace: no spare rotor, but it may hover
// tilted), rotor 2 at 20 % is below its level bound 0.2205 yet feasible (a
// hover 0.04 rad off level); at 5 %, or at the floor's 0.2 while FORCE
// reports it below the floor at 0.02, it is not (beyond
// spare_hover_tilt_rad 0.25 rad); rotor 1 at 30 % is not (tilting does not
// move rotor 1's share). The cascade's check (LimitTiltedHoverShare(
// spare_max_share): room above the weak rotor) still holds rotor 2 and 3
// at 20 % (0.11 rad) and 12 % (0.22 rad), not at 8.5 % (beyond 0.25 rad),
// which mode mpc's holds up to 1 / margin. Up to the default 0.45 rad
// every loss on rotor 2 or 3 is held, a dead one too (0.40 rad, the rotor
// at 0 N).
TEST(MultiArmFeasibilityTest, TrirotorHoldsATiltedHoverBelowRotorTwosLevelBound) {
  const VehicleDescription vehicle = Trirotor();
  const MultiArmHover hover = SolveMultiArmHover(vehicle);
  const double max_n[3] = {kMaxRotorForceN, kMaxRotorForceN, kMaxRotorForceN};
  const double hover_n[3] = {hover.force_n(0), hover.force_n(1), hover.force_n(2)};
  const HoverSpace space(vehicle, MultiArmControlModeFor(vehicle), hover.force_n);
  EfficiencyParams params;
  params.spare_hover_tilt_rad = 0.25;
  const auto phase = [&](int rotor, double efficiency, double report,
                         double max_share = 1.0 / EfficiencyParams().feasibility_margin) {
    HoverFeasibility f(params, 3, max_n, hover_n, space);
    f.LimitTiltedHoverShare(max_share);
    FeasibilityInputs in;
    in.efficiency[rotor] = efficiency;
    in.below_floor_report[rotor] = report;
    in.following_force = true;
    return RunOneSecond(&f, in);
  };
  EXPECT_EQ(phase(1, 0.2, kNaNReport), HoverFeasibility::Phase::kFeasible);
  EXPECT_EQ(phase(2, 0.2, kNaNReport), HoverFeasibility::Phase::kFeasible);
  EXPECT_NE(phase(1, 0.05, kNaNReport), HoverFeasibility::Phase::kFeasible);
  EXPECT_NE(phase(1, 0.2, 0.02), HoverFeasibility::Phase::kFeasible);
  EXPECT_NE(phase(0, 0.3, kNaNReport), HoverFeasibility::Phase::kFeasible);
  EXPECT_EQ(phase(0, 0.6, kNaNReport), HoverFeasibility::Phase::kFeasible);
  const double cascade_share = EfficiencyParams().spare_max_share;
  EXPECT_EQ(phase(1, 0.2, kNaNReport, cascade_share), HoverFeasibility::Phase::kFeasible);
  EXPECT_EQ(phase(2, 0.2, kNaNReport, cascade_share), HoverFeasibility::Phase::kFeasible);
  EXPECT_EQ(phase(1, 0.12, kNaNReport, cascade_share), HoverFeasibility::Phase::kFeasible);
  EXPECT_EQ(phase(2, 0.12, kNaNReport, cascade_share), HoverFeasibility::Phase::kFeasible);
  EXPECT_NE(phase(1, 0.085, kNaNReport, cascade_share), HoverFeasibility::Phase::kFeasible);
  EXPECT_EQ(phase(1, 0.085, kNaNReport), HoverFeasibility::Phase::kFeasible);
  params.spare_hover_tilt_rad = EfficiencyParams().spare_hover_tilt_rad;
  for (int rotor : {1, 2}) {
    for (double e : {0.085, 0.05, 0.0}) {
      EXPECT_EQ(phase(rotor, e, kNaNReport, cascade_share), HoverFeasibility::Phase::kFeasible) << rotor << " " << e;
      EXPECT_EQ(phase(rotor, 0.2, e, cascade_share), HoverFeasibility::Phase::kFeasible) << rotor << " " << e;
    }
  }
  EXPECT_NE(phase(0, 0.3, kNaNReport), HoverFeasibility::Phase::kFeasible);
}

// A VALID trirotor estimate with rotor 1 at scale, flagged when below 1;
// each rotor's force its hover thrust (trirotor.yaml's header) times its
// scale, sigma 1 %.
RotorEfficiencyEstimate RotorOneAt(int64_t utime, double scale) {
  constexpr double kHoverN[3] = {27.47, 14.32, 14.32};
  RotorEfficiencyEstimate estimate;
  estimate.utime = utime;
  estimate.n_rotors = 3;
  estimate.valid = true;
  estimate.status = kStatusValid;
  estimate.thrust_scale = {scale, 1.0, 1.0};
  estimate.thrust_scale_std = {0.01, 0.01, 0.01};
  for (size_t i = 0; i < 3; ++i) {
    estimate.force_n[i] = kHoverN[i] * estimate.thrust_scale[i];
    estimate.force_std_n[i] = 0.01 * estimate.force_n[i];
  }
  estimate.rotor_fault_bits = scale < 1.0 ? 1 : 0;
  return estimate;
}

// The loss comes after 2 s of healthy reports: airborne (airborne_s 0.05 s),
// the conditioner's baseline settled (baseline_tau_s 1 s) and its blend into
// following over (blend_s 1.5 s from airborne).
constexpr int kLossPeriod = 1000;

struct DescentRun {
  int descending_from = -1;                // first period descending, from kLossPeriod
  int hover_infeasible_from = -1;          // first period with the latch, from kLossPeriod
  double max_step_in_descent_rad_s = 0.0;  // max |omega_k - omega_k-1| while descending
};

// The trirotor level and still at 1 m (POSE every 5th period, the IMU at
// g), rotor 1 reported at 1, then at scale from period kLossPeriod (force
// feedback) or, with pose_lost, POSE lost from kLossPeriod + 100 and the IMU
// in free fall (0 m/s^2: the observer sinks, the law asks for thrust at
// once), for 1 s after kLossPeriod.
DescentRun Fly(MultiArmController* controller, double scale, bool pose_lost) {
  DescentRun run;
  std::array<double, kMaxArms> last{};
  for (int k = 0; k < kLossPeriod + 500; ++k) {
    const int64_t now_us = 2000 * k;
    const int since_loss = k - kLossPeriod;
    const bool lost = pose_lost && since_loss >= 100;
    if (k % 5 == 0) controller->OnPose(PoseSample{now_us, k / 5, 0.0, 1.0, 0.0});
    controller->OnImu(ImuSample{now_us, k, 0.0, 0.0, lost ? 0.0 : 9.81});
    controller->OnEfficiency(RotorOneAt(now_us, since_loss >= 0 ? scale : 1.0));
    ReferencePoint reference;
    reference.position_m = Eigen::Vector2d(0.0, 1.0);
    const MultiArmRotorCommand command = controller->Update(now_us, reference, lost);
    const MultiArmDegradation& d = controller->degradation();
    if (d.descending && run.descending_from < 0) run.descending_from = since_loss;
    if (d.hover_infeasible && run.hover_infeasible_from < 0) run.hover_infeasible_from = since_loss;
    if (d.descending && since_loss > run.descending_from) {
      for (int i = 0; i < 3; ++i) {
        const size_t r = static_cast<size_t>(i);
        run.max_step_in_descent_rad_s =
            std::max(run.max_step_in_descent_rad_s, std::abs(command.omega_cmd_rad_s[r] - last[r]));
      }
    }
    last = command.omega_cmd_rad_s;
  }
  return run;
}

// 80 % lost on rotor 1: the conditioned e_1 falls by max_rate_1_s x dt =
// 0.1 a period, below the bound 0.423 in the 6th period after the loss
// (k = 5: 0.4), then infeasible after infeasible_s (0.1 s: 50 periods more,
// k = 55, latches), one descent and one infeasible entry, rotor 1 flown at
// its 0.2, each command within degraded_omega_rate_rad_s2 x dt = 20000 x
// 0.002 = 40 rad/s of the last.
TEST(MultiArmDescentTest, EightyPercentOnRotorOneDescendsWithSlewedCommands) {
  const VehicleDescription vehicle = Trirotor();
  ControllerConfig config;
  config.force_feedback = true;
  MultiArmController controller(vehicle, config, SolveMultiArmHover(vehicle));
  const DescentRun run = Fly(&controller, 0.2, false);
  EXPECT_EQ(run.hover_infeasible_from, 55);
  EXPECT_EQ(run.descending_from, 55);
  const MultiArmDegradation& d = controller.degradation();
  EXPECT_EQ(d.descents, 1);
  EXPECT_EQ(d.infeasible, 1);
  EXPECT_EQ(d.infeasible_by_sink, 0);
  EXPECT_EQ(d.weak_rotor, 0);
  EXPECT_NEAR(controller.flown_efficiency()[0], 0.2, 1e-9);
  EXPECT_LE(run.max_step_in_descent_rad_s, 40.0 + 1e-9);
}

// 40 % lost on rotor 1 stays feasible: no descent.
TEST(MultiArmDescentTest, FortyPercentOnRotorOneDoesNotDescend) {
  const VehicleDescription vehicle = Trirotor();
  ControllerConfig config;
  config.force_feedback = true;
  MultiArmController controller(vehicle, config, SolveMultiArmHover(vehicle));
  const DescentRun run = Fly(&controller, 0.6, false);
  EXPECT_EQ(run.descending_from, -1);
  EXPECT_EQ(controller.degradation().descents, 0);
}

// Rotor 2 at 15 %, FORCE VALID but not flagging it: every report is refused
// (below min_plausible_thrust_scale, 0.2), the nominal map flies, and the
// vehicle sinks at 3 m/s from 0.5 s, the allocation limited. HoverFeasibility
// finds it from the sink, the weak rotor and its efficiency from the
// reports low-passed over infeasible_s (ForceFloorEvidence, NoteReport):
// rotor 2 (its 0.153 apart from the others' 1; with every report at 1 the
// hardest-driven rotor, rotor 1, is latched), flown at r_m = 0.15 + 0.85 x
// 0.99^m after m reports of 1 ms (below its bound 0.2205, so not the bound).
TEST(MultiArmDescentTest, RefusedLossBelowTheFloorIsFoundFromTheSinkAtTheLowPassedReport) {
  const VehicleDescription vehicle = Trirotor();
  ControllerConfig config;
  config.force_feedback = true;
  MultiArmController controller(vehicle, config, SolveMultiArmHover(vehicle));
  constexpr int64_t kLowFromUs = 200000;   // rotor 2 reported at 0.15 from 0.2 s
  constexpr int64_t kSinkFromUs = 500000;  // POSE sinking at 3 m/s from 0.5 s
  ReferencePoint reference;
  reference.position_m = Eigen::Vector2d(0.0, 1.0);
  int low_reports = 0;
  int latched_period = -1;
  double reported_at_latch = 0.0;
  int latched_low_reports = 0;
  for (int k = 0; k < 600 && latched_period < 0; ++k) {
    const int64_t now_us = 2000 * k;
    for (int64_t t = now_us - 1000; t <= now_us; t += 1000) {  // the samples of (now - 2 ms, now]
      if (t < 0) continue;
      const double z_m = t < kSinkFromUs ? 1.0 : 1.0 - 3.0 * 1e-6 * static_cast<double>(t - kSinkFromUs);
      controller.OnImu(ImuSample{t, static_cast<int32_t>(t / 1000), 0.0, 0.0, 9.81});
      if (t % 10000 == 0) controller.OnPose(PoseSample{t, static_cast<int32_t>(t / 10000), 0.0, z_m, 0.0});
      RotorEfficiencyEstimate report;
      report.utime = t;
      report.n_rotors = 3;
      report.valid = true;
      report.thrust_scale = {1.0, t >= kLowFromUs ? 0.15 : 1.0, 1.0};
      report.thrust_scale_std = {0.01, 0.01, 0.01};
      low_reports += t >= kLowFromUs ? 1 : 0;
      controller.OnEfficiency(controller.NoteReport(report, t));
    }
    controller.Update(now_us, reference);
    if (controller.degradation().hover_infeasible) {
      latched_period = k;
      reported_at_latch = controller.floor_evidence().reported_scale(1);
      latched_low_reports = low_reports;
    }
  }
  ASSERT_GE(latched_period, 0);
  // Found from the sink (not from the efficiencies: every e_i was 1).
  const MultiArmDegradation& d = controller.degradation();
  EXPECT_EQ(d.infeasible_by_sink, 1);
  EXPECT_EQ(d.infeasible, 1);
  EXPECT_EQ(d.weak_rotor, 1);
  EXPECT_EQ(controller.refused_estimates(), latched_low_reports);
  // Measured: latched at 0.770 s, 0.270 s after the sink began (at least
  // 50 ms to fall 0.15 m behind, then sink_detect_s 0.1 s); margin 1.5x.
  EXPECT_GE(latched_period * 2000 - kSinkFromUs, 180000);
  EXPECT_LE(latched_period * 2000 - kSinkFromUs, 405000);
  // Each low report 1 ms after the one before: m steps of gain 1 ms / 0.1 s from 1.
  EXPECT_NEAR(reported_at_latch, 0.15 + 0.85 * std::pow(0.99, latched_low_reports), 1e-9);
  EXPECT_LT(reported_at_latch, controller.feasibility().FeasibilityBound(1));
  EXPECT_EQ(controller.feasibility().weak_efficiency(), reported_at_latch);
  EXPECT_EQ(controller.flown_efficiency()[1], reported_at_latch);
}

// The nominal map flies no efficiency: its infeasibility is not known (as
// the birotor's); a lost POSE descends without the latch, slewed too: the
// law's rise towards the free fall's thrust (measured up to 25.5 rad/s a
// period at the default 20000 rad/s^2) comes at exactly 2000 x 0.002 = 4
// rad/s a period with degraded_omega_rate_rad_s2 at 2000.
TEST(MultiArmDescentTest, NominalMapDoesNotLatchAndPoseLostDescends) {
  const VehicleDescription vehicle = Trirotor();
  ControllerConfig config;
  config.force_feedback = false;
  config.supervision.degraded_omega_rate_rad_s2 = 2000.0;
  MultiArmController controller(vehicle, config, SolveMultiArmHover(vehicle));
  const DescentRun run = Fly(&controller, 0.2, true);
  EXPECT_EQ(run.hover_infeasible_from, -1);
  EXPECT_EQ(run.descending_from, 100);
  EXPECT_EQ(controller.degradation().descents, 1);
  EXPECT_EQ(controller.degradation().infeasible, 0);
  EXPECT_NEAR(run.max_step_in_descent_rad_s, 4.0, 1e-9);
}

}  // namespace
}  // namespace birotor
