// Mode mpc in the lock-step loop with the shipped config/controller.yaml and
// config/estimator.yaml, scored by evaluation/mpc_comparison.h: the aggressive
// manoeuvre (issue 21: RMS at least 25 % below the force-feedback cascade's),
// every command within bounds and the rate limit, no fallback; and the
// command checks counting a command they must refuse.
#include "evaluation/mpc_comparison.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"

namespace birotor {
namespace {

std::string ConfigFile(const std::string& name) { return std::string(BIROTOR_SOURCE_DIR) + "/config/" + name; }

TEST(MpcComparisonTest, AggressiveInModeMpc) {
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/aggressive.yaml"));
  ControllerConfig controller = LoadControllerConfig(ConfigFile("controller.yaml"));
  controller.force_feedback = controller.model_predictive = true;
  const ClosedLoopRun run =
      RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")), controller, ClosedLoopOptions());
  const ControlMetrics metrics = EvaluateControl(run);
  const MpcRunFigures f = MpcFiguresOf(run, metrics, controller);
  std::printf("aggressive mpc: rms %.4f m, max change %.0f rad/s, solves %lld, fallbacks %lld\n", f.control.rms_m,
              f.max_command_change_rad_s, static_cast<long long>(f.solves), static_cast<long long>(f.fallbacks));
  // Measured 0.0066 m on seed 2 (the force-feedback cascade: 0.0099 m); the
  // bound is issue 21's target, 25 % below the cascade (tighter than 1.5x).
  EXPECT_LT(f.control.rms_m, 0.75 * 0.0099);
  EXPECT_EQ(f.commands_out_of_bounds, 0);
  EXPECT_EQ(f.commands_over_rate, 0);
  // 8 s at 100 Hz, the first period without POSE: 799 solves.
  EXPECT_EQ(f.solves, 799);
  EXPECT_EQ(run.mpc.solver_failed + run.mpc.non_finite + run.mpc.infeasible, 0);

  // A command over the limit and one over the rate limit are counted.
  ClosedLoopRun bad = run;
  bad.commands[100].omega_cmd_rad_s[0] = controller.vehicle.omega_max_rad_s + 1.0;
  bad.commands[200].omega_cmd_rad_s[1] = bad.commands[199].omega_cmd_rad_s[1] + 400.0;
  const MpcRunFigures g = MpcFiguresOf(bad, metrics, controller);
  EXPECT_EQ(g.commands_out_of_bounds, 1);
  EXPECT_GE(g.commands_over_rate, 2);  // the jump to omega_max + 1 and the jump at 200 (and their returns)
}

}  // namespace
}  // namespace birotor
