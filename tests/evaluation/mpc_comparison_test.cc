// Mode mpc in the lock-step loop with the shipped config/controller.yaml and
// config/estimator.yaml, scored by evaluation/mpc_comparison.h: the aggressive
// manoeuvre (issue 21: RMS at least 25 % below the force-feedback cascade's),
// every command within bounds and the rate limit, no fallback; the command
// checks counting a command they must refuse; and the mismatch and loss cases
// within their measured figures.
#include "evaluation/mpc_comparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "evaluation/control_cases.h"
#include "evaluation/descent_floor.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"

namespace birotor {
namespace {

std::string ConfigFile(const std::string& name) { return std::string(BIROTOR_SOURCE_DIR) + "/config/" + name; }

// The scenario flown in mode mpc with the shipped configs (*controller: the one flown).
ClosedLoopRun FlyInModeMpc(const Scenario& scenario, ControllerConfig* controller,
                           const ControlCase& as_case = ControlCase()) {
  *controller = ControllerForCase(as_case, LoadControllerConfig(ConfigFile("controller.yaml")));
  controller->force_feedback = controller->model_predictive = true;
  return RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")), *controller, ClosedLoopOptions());
}

TEST(MpcComparisonTest, AggressiveInModeMpc) {
  ControllerConfig controller;
  const ClosedLoopRun run = FlyInModeMpc(LoadScenario(ConfigFile("scenarios/aggressive.yaml")), &controller);
  const ControlMetrics metrics = EvaluateControl(run);
  const MpcRunFigures f = MpcFiguresOf(run, metrics, controller);
  std::printf("aggressive mpc: rms %.4f m, max change %.0f rad/s, solves %lld, fallbacks %lld\n", f.control.rms_m,
              f.max_command_change_rad_s, static_cast<long long>(f.solves), static_cast<long long>(f.fallbacks));
  // Measured 0.0046 m on seed 2 (the force-feedback cascade: 0.0099 m); the
  // bound is issue 21's target, 25 % below the cascade (tighter than 1.5x).
  EXPECT_LT(f.control.rms_m, 0.75 * 0.0099);
  EXPECT_EQ(f.commands_out_of_bounds, 0);
  EXPECT_EQ(f.commands_over_rate, 0);
  // 8 s at 200 Hz, the first period without POSE: 1599 solves.
  EXPECT_EQ(f.solves, 1599);
  EXPECT_EQ(run.mpc.solver_failed + run.mpc.non_finite + run.mpc.infeasible, 0);

  // A command over the limit and one over the rate limit are counted.
  ClosedLoopRun bad = run;
  bad.commands[100].omega_cmd_rad_s[0] = controller.vehicle.omega_max_rad_s + 1.0;
  bad.commands[200].omega_cmd_rad_s[1] = bad.commands[199].omega_cmd_rad_s[1] + 400.0;
  const MpcRunFigures g = MpcFiguresOf(bad, metrics, controller);
  EXPECT_EQ(g.commands_out_of_bounds, 1);
  EXPECT_GE(g.commands_over_rate, 2);  // the jump to omega_max + 1 and the jump at 200 (and their returns)
}

// The scenario of case name (evaluation/control_cases.cc) with its overrides,
// on the scenario's own seed; a failure (and the default scenario) if unknown.
Scenario CaseScenario(const std::string& name) {
  const ControlCase* c = FindControlCase(name);
  EXPECT_NE(c, nullptr) << name;
  if (c == nullptr) return Scenario();
  return LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides);
}

// Figures of case name flown in mode mpc (model_predictive) or by the nominal cascade.
ControlFigures FlyCase(const std::string& name, bool model_predictive) {
  ControllerConfig controller =
      ControllerForCase(*FindControlCase(name), LoadControllerConfig(ConfigFile("controller.yaml")));
  controller.force_feedback = controller.model_predictive = model_predictive;
  return FiguresOf(EvaluateControl(RunClosedLoop(CaseScenario(name), LoadEstimatorConfig(ConfigFile("estimator.yaml")),
                                                 controller, ClosedLoopOptions())));
}

// The peak tilt of case name on seed flown in mode mpc or by the nominal cascade [rad].
double PeakTiltOnSeed(const std::string& name, bool model_predictive, int seed) {
  const ControlCase* c = FindControlCase(name);
  EXPECT_NE(c, nullptr) << name;
  if (c == nullptr) return 0.0;
  std::vector<std::string> overrides = c->overrides;
  overrides.push_back("scenario.seed=" + std::to_string(seed));
  ControllerConfig controller = ControllerForCase(*c, LoadControllerConfig(ConfigFile("controller.yaml")));
  controller.force_feedback = controller.model_predictive = model_predictive;
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), overrides);
  return FiguresOf(EvaluateControl(RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")),
                                                 controller, ClosedLoopOptions())))
      .tilt_rad;
}

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

TEST(MpcComparisonTest, AHoverAndASlowMoveTiltNoMoreThanTheCascade) {
  // A controller is never worse than the nominal map it replaces: with the
  // tracking pitch rate weight in the hover the MPC's peak tilt was 1.09x
  // the led cascade's on a hover (0.0093 against 0.0085 rad) and 1.23x on
  // gentle with the motor +70 % (0.0122 against 0.0099; medians of seeds
  // 1-5); the steady weights (mpc_params.h) fly them at 0.84x and 0.94x
  // (0.0071, 0.0093 rad; docs/mpc.md "Steady weights").
  for (const std::string name : {"hover", "motor_tau_+70"}) {
    std::vector<double> mpc, nominal;
    for (int seed = 1; seed <= 5; ++seed) {
      mpc.push_back(PeakTiltOnSeed(name, true, seed));
      nominal.push_back(PeakTiltOnSeed(name, false, seed));
    }
    std::printf("%s peak tilt, median of seeds 1-5: mpc %.4f rad, nominal cascade %.4f rad\n", name.c_str(),
                Median(mpc), Median(nominal));
    EXPECT_LE(Median(mpc), 1.05 * Median(nominal)) << name;
  }
}

TEST(MpcComparisonTest, MismatchAndLossCasesInModeMpc) {
  // birotor-eval --control --mpc --seeds 10 (docs/mpc.md), the scenario's own
  // seed of each case: MPC with the efficiencies (RMS, fault tilt, altitude),
  // bounds 1.5x those figures; in the mismatch cases (issue 21) no worse than
  // the nominal cascade by more than 5 % (its thrust lead took its hover tilt
  // to 0.0090-0.0101 rad here; the MPC's steady pitch rate weight took the
  // MPC's from 0.0093-0.0096 to 0.0082-0.0086); in the loss cases the fault's
  // peak tilt at most half the force-feedback cascade's on this seed
  // (measured 0.49x and 0.46x).
  struct Expected {
    std::string name;
    ControlFigures mpc;
    bool no_worse_than_nominal;
    double half_feedback_tilt_rad;  // 0: not a loss case
  };
  const std::vector<Expected> cases = {
      {"stiffness_-20", {0.0007, 0.0086, 0.0010}, true, 0.0},      // seed 1; nominal 0.0033, 0.0101, 0.0068
      {"mass_-15", {0.0009, 0.0082, 0.0028}, true, 0.0},           // seed 1; nominal 0.0559, 0.0093, 0.1138
      {"loss_40", {0.0011, 0.0181, 0.0045}, false, 0.5 * 0.0370},  // seed 4; force feedback 0.0059, 0.0249, 0.0137
      {"loss_60", {0.0064, 0.0369, 0.0361}, false, 0.5 * 0.0800},  // seed 4; force feedback 0.0166, 0.0541, 0.0531
  };
  for (const Expected& e : cases) {
    const ControlFigures mpc = FlyCase(e.name, true);
    std::printf("%s mpc: rms %.4f m, tilt %.4f rad, altitude %.4f m\n", e.name.c_str(), mpc.rms_m, mpc.tilt_rad,
                mpc.altitude_m);
    EXPECT_LT(mpc.rms_m, 1.5 * e.mpc.rms_m) << e.name;
    EXPECT_LT(mpc.tilt_rad, 1.5 * e.mpc.tilt_rad) << e.name;
    EXPECT_LT(mpc.altitude_m, 1.5 * e.mpc.altitude_m) << e.name;
    if (e.half_feedback_tilt_rad > 0.0) {
      EXPECT_LE(mpc.tilt_rad, e.half_feedback_tilt_rad) << e.name;
    }
    if (!e.no_worse_than_nominal) continue;
    const ControlFigures nominal = FlyCase(e.name, false);
    std::printf("%s nominal: rms %.4f m, tilt %.4f rad, altitude %.4f m\n", e.name.c_str(), nominal.rms_m,
                nominal.tilt_rad, nominal.altitude_m);
    EXPECT_LE(mpc.rms_m, 1.05 * nominal.rms_m) << e.name;
    EXPECT_LE(mpc.tilt_rad, 1.05 * nominal.tilt_rad) << e.name;
    EXPECT_LE(mpc.altitude_m, 1.05 * nominal.altitude_m) << e.name;
  }
}

TEST(MpcComparisonTest, FastestAcceptedTrajectoryKeepsItsAltitudeWithoutFallback) {
  // Issue 34: on the fastest trajectory SETPOINT accepts (case
  // aggressive_limit, 10 m/s^2 per axis) the tilt limit binds; the MPC keeps
  // its altitude with no fallback. Measured on this seed (3): MPC 0.1726 m
  // at |tilt| 0.512 rad; the cascade 0.1245 m, its tilt past its 0.5 rad
  // target (0.2282 m before its thrust lead, which the MPC then kept within
  // 10 %; docs/mpc.md "At the limits"); before altitude_weight_factor and
  // DENSE-IPM: 0.478 m and 8 late solves.
  ControllerConfig controller;
  const ClosedLoopRun run =
      FlyInModeMpc(CaseScenario("aggressive_limit"), &controller, *FindControlCase("aggressive_limit"));
  const ControlMetrics m = EvaluateControl(run);
  const MpcRunFigures f = MpcFiguresOf(run, m, controller);
  const ControlFigures cascade = FlyCase("aggressive_limit", false);
  std::printf("aggressive_limit: mpc altitude %.4f m, tilt %.4f rad; cascade altitude %.4f m; fallbacks %lld\n",
              f.control.altitude_m, f.control.tilt_rad, cascade.altitude_m, static_cast<long long>(f.fallbacks));
  EXPECT_LT(f.control.altitude_m, 1.5 * 0.1725);
  EXPECT_LT(f.control.tilt_rad, controller.mpc.max_tilt_rad + 0.02);  // the soft limit, 0.012 rad over measured
  EXPECT_EQ(f.fallbacks, 0);
  EXPECT_EQ(f.commands_out_of_bounds, 0);
  EXPECT_EQ(f.commands_over_rate, 0);
}

TEST(MpcComparisonTest, LossesMidClimbLandLevelInModeMpc) {
  // Issue 34's targets in mode mpc: a 70 or 80 % loss of either rotor mid-climb
  // (cases agg_loss*) descends with |tilt| <= 0.3 rad from the fault to
  // touchdown, at most 10 % above the level descent's floor
  // (evaluation/descent_floor.h). Measured on the scenarios' seeds with
  // descent_tilt_weight 5000 (docs/mpc.md): tilt 0.24-0.29 rad, touchdown
  // 0.88-0.98 x floor; with 500 the r2 cases touched down at 0.33-0.35 rad.
  for (const char* name : {"agg_loss70_r1", "agg_loss70_r2", "agg_loss80_r1", "agg_loss80_r2"}) {
    const Scenario scenario = CaseScenario(name);
    ControllerConfig controller;
    const ClosedLoopRun run = FlyInModeMpc(scenario, &controller);
    const ControlMetrics m = EvaluateControl(run);
    const DescentFloor floor = LevelDescentFloor(run, scenario);
    ASSERT_TRUE(floor.found) << name;
    std::printf("%s mpc: tilt %.3f rad, touchdown %.2f m/s = %.2f x floor\n", name, m.tilt_before_touchdown_rad,
                m.touchdown_speed_m_s, m.touchdown_speed_m_s / floor.touchdown_m_s);
    EXPECT_LE(m.tilt_before_touchdown_rad, 0.3) << name;
    EXPECT_LE(m.touchdown_speed_m_s, 1.1 * floor.touchdown_m_s) << name;
  }
}

TEST(MpcComparisonTest, SeventyPercentLossDescendsLevelAndFlaresInModeMpc) {
  // Issue 21: a level descent (|tilt| < 0.3 rad) reaching the ground below
  // 1 m/s, in mode mpc: the descent planned with the descent weights
  // (mpc_params.h), the last ~0.1 s the cascade's flare. Measured on this
  // seed (4, birotor-eval --control --mpc --seeds 10, docs/mpc.md):
  // touchdown 0.87 m/s (10 seeds 0.85-0.90), tilt at touchdown 0.047 rad,
  // pitch rate 2.05 rad/s, lower tip 1.38 m/s, peak tilt since the fault
  // 0.065 rad.
  ControllerConfig controller;
  const ClosedLoopRun run = FlyInModeMpc(CaseScenario("loss_70"), &controller);
  const ControlMetrics m = EvaluateControl(run);
  const MpcRunFigures f = MpcFiguresOf(run, m, controller);
  std::printf("loss_70 mpc: touchdown %.3f m/s, tilt before %.4f, at touchdown %.4f rad, rate %.3f rad/s, tip %.3f\n",
              m.touchdown_speed_m_s, m.tilt_before_touchdown_rad, m.tilt_at_touchdown_rad,
              m.pitch_rate_at_touchdown_rad_s, m.tip_touchdown_speed_m_s);
  EXPECT_LT(m.tilt_before_touchdown_rad, 0.3);  // the target
  EXPECT_LT(m.touchdown_speed_m_s, 0.95);       // the target < 1; this seed 0.87
  EXPECT_GT(m.touchdown_speed_m_s, 0.87 / 1.5);
  EXPECT_LT(m.tilt_at_touchdown_rad, 1.5 * 0.047);
  EXPECT_LT(m.pitch_rate_at_touchdown_rad_s, 1.5 * 2.05);
  EXPECT_LT(m.tip_touchdown_speed_m_s, 1.5 * 1.38);
  EXPECT_EQ(f.commands_out_of_bounds, 0);
  EXPECT_EQ(f.commands_over_rate, 0);
  EXPECT_EQ(f.fallbacks, 0);
  EXPECT_EQ(run.controller.infeasible, 1);
  EXPECT_EQ(run.controller.flares, 1);
}

}  // namespace
}  // namespace birotor
