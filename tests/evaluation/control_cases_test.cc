// Every case of birotor-eval --control (evaluation/control_cases.cc) flown
// lock-step in both modes on the scenario's own seed: force feedback within
// 1.5x of the figures measured on the development VM (docs/controller.md,
// seed 1 of the table), and no worse than nominal where issue 25's target is
// met (5 % on RMS position, fault-relative tilt and altitude deviation).
#include "evaluation/control_cases.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "evaluation/closed_loop.h"
#include "evaluation/control_metrics.h"
#include "evaluation/descent_floor.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"

namespace birotor {
namespace {

std::string ConfigFile(const std::string& name) { return std::string(BIROTOR_SOURCE_DIR) + "/config/" + name; }

// The scenario flown with the shipped files, nominal (entry 0) and force
// feedback (entry 1).
void FlyBothModes(const Scenario& scenario, ClosedLoopRun (&runs)[2], ControlMetrics (&m)[2]) {
  const EstimatorConfig estimator = LoadEstimatorConfig(ConfigFile("estimator.yaml"));
  for (const bool force_feedback : {false, true}) {
    ControllerConfig config = LoadControllerConfig(ConfigFile("controller.yaml"));
    config.force_feedback = force_feedback;
    runs[force_feedback] = RunClosedLoop(scenario, estimator, config, ClosedLoopOptions());
    m[force_feedback] = EvaluateControl(runs[force_feedback]);
  }
}

// The case of the list by name, flown in both modes (FlyBothModes).
void FlyCaseBothModes(const std::string& name, ClosedLoopRun (&runs)[2], ControlMetrics (&m)[2]) {
  const ControlCase* c = FindControlCase(name);
  ASSERT_NE(c, nullptr) << name;
  FlyBothModes(LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides), runs, m);
}

struct Measured {
  double rms_m, tilt_rad, altitude_m;  // force feedback, measured
  bool no_worse;                       // issue 25's target met on this seed
};

// birotor-eval --control (one seed each), commit of this test.
const std::map<std::string, Measured>& MeasuredFigures() {
  static const std::map<std::string, Measured> figures = {
      {"hover", {0.0033, 0.0101, 0.0068, true}},
      {"gentle", {0.0030, 0.0079, 0.0047, true}},
      {"aggressive", {0.0089, 0.1901, 0.0085, true}},
      // The fastest trajectory SETPOINT accepts: the tilt limit binds, x lags (seed 3).
      {"aggressive_limit", {0.3570, 0.5681, 0.1245, true}},
      {"thrust_loss", {0.0039, 0.0120, 0.0037, true}},
      {"stiffness_-20", {0.0033, 0.0101, 0.0068, true}},
      {"mass_-15", {0.0559, 0.0093, 0.1138, true}},
      {"motor_tau_+70", {0.0031, 0.0083, 0.0050, true}},
      // The cascade's thrust lead holds a motor 3x slower than the file (lost from 1.9x without it).
      {"motor_tau_x3", {0.0036, 0.0180, 0.0080, true}},
      // FORCE's thrust scales swing with the lag before MODEL_MISMATCH: the change flown is bounded
      // (max_change_gain); nominal 0.2317 / 0.1368 / 0.4866 on this seed (4).
      {"motor_tau_+70_loss_50", {0.0642, 0.0615, 0.1760, true}},
      // The estimator raises MODEL_MISMATCH (a gauge scale of 0.7), VALID is withdrawn and force feedback flies the
      // nominal map: equal to nominal on all 10 seeds (was RMS 0.1062 m, 31x nominal, before the mismatch detector).
      {"gauge_scale_0.7", {0.0033, 0.0101, 0.0068, true}},
      // Seed 4 (the scenario's): MODEL_MISMATCH (the untared offset), so force feedback flies the nominal map
      // but rotor 2's loss relative to rotor 1 (MismatchChangeRule): nominal 0.0737 / 0.0450 / 0.1593.
      {"untared_loss", {0.0121, 0.0440, 0.0394, true}},
      {"ground_start", {0.0024, 0.0079, 0.0031, true}},
      {"severe_gap", {0.0847, 0.0806, 0.2511, true}},
      {"imu_noise", {0.0077, 0.0196, 0.0092, true}},
      // Issue 21's fault cases, flown by the cascade here (the MPC: mpc_comparison_test.cc).
      {"loss_40", {0.0058, 0.0266, 0.0136, true}},
      {"loss_60", {0.0140, 0.0587, 0.0486, true}},
      {"loss_70", {0.2998, 0.0718, 0.4000, true}},
      // Issue 34: hover-infeasible losses mid-climb of the aggressive move (seed 3) and in hover (seed 4).
      {"agg_loss70_r1", {0.6979, 0.1041, 1.3000, true}},
      {"agg_loss70_r2", {0.6957, 0.1079, 1.3000, true}},
      {"agg_loss80_r1", {0.7681, 0.1396, 1.3000, true}},
      {"agg_loss80_r2", {0.7724, 0.1108, 1.3000, true}},
      {"loss_80", {0.3037, 0.1053, 0.4000, true}},
      // Issue 36 item 5 (seed 1 of birotor-eval --control --seeds 5, nominal in the comments). A trusted
      // efficiency is flown: c_T -15 % and thinner air sag less (nominal 0.0785 / 0.0115 / 0.1652 and
      // 0.0785 / 0.0115 / 0.1654).
      {"ct_-15", {0.0133, 0.0112, 0.0451, true}},
      {"density_0.85", {0.0157, 0.0112, 0.0541, true}},
      // The payload raises MODEL_MISMATCH from take-off (the fast test) and holds it: force feedback flies the
      // nominal map but rotor 1's loss relative to rotor 2, confirmed 30 ms after its flag (MismatchChangeRule;
      // nominal 0.1976 / 0.0821 / 0.3788).
      {"payload_+15_loss_40", {0.0607, 0.0616, 0.0827, true}},
      // The same at 40 %: the nominal map falls 1.3 m (0.7518 / 0.1665 / 1.3173), force feedback 0.27 m.
      {"payload_+15_loss_60", {0.1101, 0.1213, 0.2684, true}},
      // MODEL_MISMATCH throughout (gauge scale 0.7): the nominal map.
      {"all_different", {0.0158, 0.0093, 0.0360, true}},
      // mu0 within absolute_threshold of 1: nothing flown (nominal equal).
      {"tip_mass_+20", {0.0125, 0.0105, 0.0270, true}},
      {"turbulence_0.05", {0.0129, 0.0436, 0.0131, true}},
  };
  return figures;
}

TEST(ControlCasesTest, EveryCaseWithinItsMeasuredFigures) {
  const ControllerConfig base = LoadControllerConfig(ConfigFile("controller.yaml"));
  const EstimatorConfig estimator = LoadEstimatorConfig(ConfigFile("estimator.yaml"));
  ASSERT_EQ(ControlCases().size(), MeasuredFigures().size());
  for (const ControlCase& c : ControlCases()) {
    const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c.scenario + ".yaml"), c.overrides);
    ControlMetrics m[2];
    for (const bool force_feedback : {false, true}) {
      ControllerConfig config = ControllerForCase(c, base);
      config.force_feedback = force_feedback;
      m[force_feedback] = EvaluateControl(RunClosedLoop(scenario, estimator, config, ClosedLoopOptions()));
    }
    const Measured& expected = MeasuredFigures().at(c.name);
    EXPECT_LT(m[1].rms_position_error_m, 1.5 * expected.rms_m) << c.name;
    EXPECT_LT(m[1].fault_peak_tilt_rad, 1.5 * expected.tilt_rad) << c.name;
    EXPECT_LT(m[1].peak_altitude_deviation_m, 1.5 * expected.altitude_m) << c.name;
    if (c.name == "thrust_loss") {
      // Issue 25 kept targets: tilt at least 2.5x and altitude deviation at
      // least 10x smaller than nominal (measured on this seed: 3.75x, 43x).
      EXPECT_GE(m[0].fault_peak_tilt_rad, 2.5 * m[1].fault_peak_tilt_rad);
      EXPECT_GE(m[0].peak_altitude_deviation_m, 10.0 * m[1].peak_altitude_deviation_m);
    }
    if (expected.no_worse) {
      EXPECT_LE(m[1].rms_position_error_m, 1.05 * m[0].rms_position_error_m) << c.name;
      EXPECT_LE(m[1].fault_peak_tilt_rad, 1.05 * m[0].fault_peak_tilt_rad) << c.name;
      EXPECT_LE(m[1].peak_altitude_deviation_m, 1.05 * m[0].peak_altitude_deviation_m) << c.name;
    }
  }
}

TEST(ControlCasesTest, ThrustCoefficientMinus15SagsLessWithForceFeedback) {
  // Issue 36 item 5: the rotors make 0.85 of the map (c_T 3.91e-5 of 4.6e-5)
  // from the start. Nominal sags g x 0.15 / position_kp = 0.164 m until the
  // integrator catches up (measured 0.1659 m); force feedback flies the
  // estimator's mu0 (0.85 within its accuracy) once trusted. Measured on seed
  // 1 (the scenario's): sag 0.1659 -> 0.1059 m, a 0.060 m gain; RMS 0.0786 ->
  // 0.0302 m; final efficiencies 0.841, 0.848 (5 seeds 0.837-0.856).
  ClosedLoopRun runs[2];
  ControlMetrics m[2];
  FlyCaseBothModes("ct_-15", runs, m);
  EXPECT_GT(m[0].peak_altitude_deviation_m - m[1].peak_altitude_deviation_m, 0.060 / 1.5);
  EXPECT_LT(m[1].rms_position_error_m, m[0].rms_position_error_m / (0.0786 / 0.0302 / 1.5));
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(runs[1].controller.efficiency[i], 0.85, 1.5 * 0.0093) << i;
}

TEST(ControlCasesTest, SeventyPercentLossDescendsLevelAndFlares) {
  // Issue 25: a level descent (|tilt| < 0.3 rad) reaching the ground below
  // 1 m/s. Level, the rotors make 2 x 0.3 c_T omega_max^2 = 39.7 N of the
  // 44.9 N weight and the body comes down at 1.03-1.06 m/s (10 seeds); the
  // flare (controller/rotor_allocation.h, flare_tilt_rad 0.08, flare_time_s
  // 0.1) lets rotor 1 exceed rotor 2 in the last ~0.1 s. Measured on this
  // seed (4): touchdown 0.91 m/s (10 seeds 0.91-0.95), tilt at touchdown
  // 0.062 rad, pitch rate 1.92 rad/s, lower tip 1.39 m/s (10 seeds 1.33-1.39:
  // the price, level it was 0.96-1.11), peak tilt since the fault 0.094 rad
  // (the fault transient). docs/controller.md.
  const ControlCase* c = FindControlCase("loss_70");
  ASSERT_NE(c, nullptr);
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides);
  const ClosedLoopRun run = RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")),
                                          LoadControllerConfig(ConfigFile("controller.yaml")), ClosedLoopOptions());
  const ControlMetrics m = EvaluateControl(run);
  EXPECT_LT(m.tilt_before_touchdown_rad, 0.3);  // the target
  EXPECT_LT(m.touchdown_speed_m_s, 0.98);       // the target < 1; 10 seeds at most 0.95
  EXPECT_GT(m.touchdown_speed_m_s, 0.91 / 1.5);
  EXPECT_LT(m.tilt_at_touchdown_rad, 1.5 * 0.062);
  EXPECT_LT(m.pitch_rate_at_touchdown_rad_s, 1.5 * 1.92);
  EXPECT_LT(m.tip_touchdown_speed_m_s, 1.45);
  EXPECT_EQ(run.controller.infeasible, 1);
  EXPECT_EQ(run.controller.flares, 1);
}

TEST(ControlCasesTest, HoverInfeasibleLossesLevelFirstAndLandAtTheLevelFloor) {
  // Issue 34 targets, force feedback: a 70 or 80 % loss of either rotor mid-climb
  // of the aggressive move descends with the peak tilt from the fault to
  // touchdown <= 0.3 rad and touches down within 10 % of the level descent's
  // floor (evaluation/descent_floor.h); an 80 % loss in hover descends.
  // Measured on the scenarios' seeds (docs/controller.md): tilt 0.132, 0.140,
  // 0.184, 0.141 rad; touchdown / floor 1.01, 0.85, 0.99, 0.89; loss_80 (FORCE
  // at its plausibility floor, flown as the floor) 0.92 x floor, tilt 0.151.
  const ControllerConfig controller = LoadControllerConfig(ConfigFile("controller.yaml"));
  const EstimatorConfig estimator = LoadEstimatorConfig(ConfigFile("estimator.yaml"));
  for (const char* name : {"agg_loss70_r1", "agg_loss70_r2", "agg_loss80_r1", "agg_loss80_r2", "loss_80"}) {
    const ControlCase* c = FindControlCase(name);
    ASSERT_NE(c, nullptr) << name;
    const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides);
    const ClosedLoopRun run = RunClosedLoop(scenario, estimator, controller, ClosedLoopOptions());
    const ControlMetrics m = EvaluateControl(run);
    const DescentFloor floor = LevelDescentFloor(run, scenario);
    ASSERT_TRUE(floor.found) << name;
    EXPECT_EQ(run.controller.infeasible, 1) << name;
    EXPECT_LE(m.touchdown_speed_m_s, 1.1 * floor.touchdown_m_s) << name;
    EXPECT_LE(m.tilt_before_touchdown_rad, 0.3) << name;
  }
}

TEST(ControlCasesTest, ASinkLatchIsUndoneWhenTheRotorsHoldTheWeight) {
  // Body +15 % (the controller does not know it; FORCE is MODEL_MISMATCH
  // throughout), rotor 1 at 0.3 from 5 s and back to 0.45 from 5.6 s (a motor
  // that partly recovers): the growing sink latches hover infeasible at 5.4 s;
  // level and descending, the rotors then hold the weight with a margin and
  // the latch is undone (6.4 s): force feedback climbs back as the nominal
  // map does. Measured on this seed (4): altitude deviation 1.5452 m against
  // nominal 1.6341, RMS 0.5949 against 0.7384 m (rotor 1's loss flown
  // relative to rotor 2 under the mismatch; without that rule 1.6597 and
  // 0.6519 m); with the latch held for the flight 2.0969 m and 1.3610 m.
  const Scenario scenario =
      LoadScenario(ConfigFile("scenarios/thrust_loss_severe.yaml"),
                   {"scenario.duration_s=10", "vehicle.body_mass_kg=4.6",
                    "faults.thrust_steps=[{time_s: 5.0, rotor: 1, scale: 0.3}, {time_s: 5.6, rotor: 1, scale: 0.45}]"});
  ClosedLoopRun runs[2];
  ControlMetrics m[2];
  FlyBothModes(scenario, runs, m);
  EXPECT_EQ(runs[1].controller.infeasible_by_sink, 1);
  EXPECT_EQ(runs[1].controller.infeasible_undone, 1);
  EXPECT_LE(m[1].peak_altitude_deviation_m, 1.05 * m[0].peak_altitude_deviation_m);
  EXPECT_LE(m[1].rms_position_error_m, m[0].rms_position_error_m);
  EXPECT_LT(m[1].rms_position_error_m, 1.5 * 0.5949);
}

// Issue 36's closed-loop target: a 40 % loss on a vehicle carrying a +15 %
// payload, force feedback at least 2x better than the nominal map in
// altitude. FORCE is MODEL_MISMATCH throughout (the payload), so only rotor
// 1's loss relative to rotor 2 is flown (MismatchChangeRule); without the
// rule force feedback is the nominal map. Measured on the scenario's seed
// (1): 0.0852 m against 0.3727 m (4.4x; 5 seeds 4.4x median, 3.8x worst).
TEST(ControlCasesTest, ALossOnAPayloadIsFlownRelativeToTheOtherRotor) {
  ClosedLoopRun runs[2];
  ControlMetrics m[2];
  FlyCaseBothModes("payload_+15_loss_40", runs, m);
  EXPECT_GE(m[0].peak_altitude_deviation_m, 2.0 * m[1].peak_altitude_deviation_m);
  EXPECT_LT(m[1].peak_altitude_deviation_m, 1.5 * 0.0852);
  EXPECT_LT(m[1].fault_peak_tilt_rad, m[0].fault_peak_tilt_rad);
  ControllerConfig off = LoadControllerConfig(ConfigFile("controller.yaml"));
  off.efficiency.mismatch_relative = false;
  const ControlCase* c = FindControlCase("payload_+15_loss_40");
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides);
  const ControlMetrics without = EvaluateControl(
      RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")), off, ClosedLoopOptions()));
  EXPECT_DOUBLE_EQ(without.peak_altitude_deviation_m, m[0].peak_altitude_deviation_m);
}

// A motor lag 70 % longer than the file, and rotor 2 loses 50 %: FORCE stays
// VALID for 0.5 s while rotor 1's thrust scale swings with the lag (0.8 ->
// 2.3 -> 0.7). Without the cascade's thrust lead and with the change
// followed unbounded, force feedback flew rotor 1 at 1.68 and lost the
// vehicle on seed 1 (54 m down, 7 rad); either one alone holds it. Measured
// on seed 1 with both: altitude deviation 0.1772 m against the nominal
// map's 0.4765 m, tilt 0.0595 against 0.1363 rad.
TEST(ControlCasesTest, AMotorLagTheFileLacksDoesNotLoseTheVehicleAfterALoss) {
  const ControlCase* c = FindControlCase("motor_tau_+70_loss_50");
  ASSERT_NE(c, nullptr);
  std::vector<std::string> overrides = c->overrides;
  overrides.push_back("scenario.seed=1");
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), overrides);
  ClosedLoopRun runs[2];
  ControlMetrics m[2];
  FlyBothModes(scenario, runs, m);
  EXPECT_FALSE(m[1].verdict.lost);
  EXPECT_LT(m[1].peak_altitude_deviation_m, 0.5 * m[0].peak_altitude_deviation_m);
  EXPECT_LT(m[1].fault_peak_tilt_rad, 1.5 * 0.0595);
  const EstimatorConfig estimator = LoadEstimatorConfig(ConfigFile("estimator.yaml"));
  ControllerConfig neither = LoadControllerConfig(ConfigFile("controller.yaml"));
  neither.force_feedback = true;
  neither.efficiency.max_change_gain = 10.0;
  neither.efficiency.thrust_lead_s = 0.0;
  EXPECT_TRUE(EvaluateControl(RunClosedLoop(scenario, estimator, neither, ClosedLoopOptions())).verdict.lost);
  for (const bool lead : {false, true}) {
    ControllerConfig one = neither;
    if (lead) {
      one.efficiency.thrust_lead_s = 0.035;
    } else {
      one.efficiency.max_change_gain = 1.2;
    }
    EXPECT_FALSE(EvaluateControl(RunClosedLoop(scenario, estimator, one, ClosedLoopOptions())).verdict.lost) << lead;
  }
}

// A motor three times slower than the file (tau_m 0.105 s) in hover: the
// cascade's thrust lead (thrust_lead_s 0.035, the file's tau_m, filtered
// by thrust_lead_filter_s 0.005) holds it in both modes; without the lead
// the attitude loop's limit cycle loses the vehicle (from 1.9x the file's
// tau_m). Measured on seed 1: RMS 0.0036 m, tilt 0.0180 rad with the lead.
TEST(ControlCasesTest, AMotorThreeTimesSlowerThanTheFileIsHeld) {
  const ControlCase* c = FindControlCase("motor_tau_x3");
  ASSERT_NE(c, nullptr);
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides);
  ClosedLoopRun runs[2];
  ControlMetrics m[2];
  FlyBothModes(scenario, runs, m);
  for (int mode = 0; mode < 2; ++mode) {
    EXPECT_FALSE(m[mode].verdict.lost) << mode;
    EXPECT_LT(m[mode].rms_position_error_m, 1.5 * 0.0036) << mode;
  }
  ControllerConfig no_lead = LoadControllerConfig(ConfigFile("controller.yaml"));
  no_lead.efficiency.thrust_lead_s = 0.0;
  const ControlMetrics without = EvaluateControl(
      RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")), no_lead, ClosedLoopOptions()));
  EXPECT_TRUE(without.verdict.lost);
}

// The rule's guard: a motor lag 70 % longer than the file makes the
// mismatched estimate flag the rotors by turns; following those flags locked
// the gentle flight of seed 1 into a limit cycle (RMS 15 m, lost). Force
// feedback must stay the nominal map there.
TEST(ControlCasesTest, AMotorLagMismatchFlagsNoLoss) {
  const Scenario scenario =
      LoadScenario(ConfigFile("scenarios/gentle.yaml"), {"vehicle.motor_time_constant_s=0.0595", "scenario.seed=1"});
  ClosedLoopRun runs[2];
  ControlMetrics m[2];
  FlyBothModes(scenario, runs, m);
  EXPECT_LE(m[1].rms_position_error_m, 1.05 * m[0].rms_position_error_m);
  EXPECT_LE(m[1].peak_tilt_rad, 1.05 * m[0].peak_tilt_rad);
}

TEST(ControlCasesTest, APayloadsHoverInfeasibleLandingStaysDown) {
  // Body +15 % (MODEL_MISMATCH throughout), at 0.6 m above the ground rotor 2
  // loses 70 %: the growing sink latches, the vehicle lands, and the latch is
  // not undone on the ground, where the observer's climb rate decays for a
  // while after the impact but the height does not move (with one recovery
  // window and no height check it "recovered" 0.4 s after touchdown and spun
  // up to take off). Measured on this seed (4): touchdown 1.55 m/s.
  const Scenario scenario =
      LoadScenario(ConfigFile("scenarios/thrust_loss.yaml"),
                   {"scenario.duration_s=12", "ground.enabled=true", "ground.rest_s=1.0", "trajectory.kind=waypoints",
                    "trajectory.waypoints=[{start_s: 0.0, duration_s: 2.0, x_m: 0.0, z_m: 0.6}]",
                    "vehicle.body_mass_kg=4.6", "faults.thrust_steps=[{time_s: 6.0, rotor: 2, scale: 0.3}]"});
  const ClosedLoopRun run = RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")),
                                          LoadControllerConfig(ConfigFile("controller.yaml")), ClosedLoopOptions());
  const ControlMetrics m = EvaluateControl(run);
  EXPECT_EQ(run.controller.infeasible, 1);
  EXPECT_EQ(run.controller.infeasible_by_sink, 1);
  EXPECT_EQ(run.controller.infeasible_undone, 0);
  EXPECT_GT(m.touchdown_speed_m_s, 0.0);
  EXPECT_LT(m.touchdown_speed_m_s, 1.5 * 1.55);
}

}  // namespace
}  // namespace birotor
