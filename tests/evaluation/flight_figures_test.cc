// One flight, one set of figures (issue 39): a lock-step flight written to a
// log, then its RMS position error, max tilt and fallbacks as birotor-sim
// --controller and birotor-eval --control print them (ClosedLoopRun::figures,
// EvaluateControl) and as birotor-review reads them back from the log
// (FlightData::figures, ComputeHeadline): equal to the printed digits, and
// equal to the controller's and the MPC's own counts.
#include "samples/flight_figures.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "evaluation/closed_loop.h"
#include "evaluation/control_metrics.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "review/flight_data.h"
#include "review/flight_headline.h"
#include "samples/motor_command.h"
#include "sinks/message_sink.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

std::string ConfigFile(const std::string& name) { return std::string(BIROTOR_SOURCE_DIR) + "/config/" + name; }

struct FlownFlight {
  ClosedLoopRun run;
  ControlMetrics metrics;  // birotor-eval --control's
  FlightData data;         // birotor-review's reading of the log
  FlightHeadline headline;
};

// Flies scenario_name (its own seed) for duration_s in the given mode into a
// log, as birotor-sim --controller --output does, and reads the log back.
// deadline_work: the MPC's work budget per solve (0: config/controller.yaml's).
FlownFlight FlyAndReview(const std::string& scenario_name, double duration_s, bool ground, const std::string& mode,
                         int deadline_work = 0) {
  Scenario scenario = LoadScenario(ConfigFile("scenarios/" + scenario_name + ".yaml"));
  scenario.duration_s = duration_s;
  scenario.ground.enabled = ground;
  ControllerConfig controller = LoadControllerConfig(ConfigFile("controller.yaml"));
  controller.force_feedback = mode != "nominal";
  controller.model_predictive = mode == "mpc";
  if (deadline_work > 0) controller.mpc.deadline_work = deadline_work;
  const std::string path = ::testing::TempDir() + "/flight_figures_" + std::to_string(::getpid()) + ".lcm";
  FlownFlight out;
  LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.Open(path, &error)) << error;
  LogSink sink(&writer);
  out.run = RunClosedLoop(scenario, LoadEstimatorConfig(ConfigFile("estimator.yaml")), controller, ClosedLoopOptions(),
                          &sink);
  EXPECT_FALSE(sink.failed());
  EXPECT_TRUE(writer.Close());
  out.metrics = EvaluateControl(out.run);
  EXPECT_TRUE(ReadFlightData(path, "BIROTOR_", 0.5, &out.data, &error)) << error;
  std::remove(path.c_str());
  out.headline = ComputeHeadline(out.data);
  return out;
}

void ExpectOneSetOfFigures(const FlownFlight& f) {
  const FlightFigureValues sim = f.run.figures.Result();  // birotor-sim and birotor-eval print this
  const FlightFigureValues review = f.headline.figures;
  std::printf("sim/eval: %s\nreview:   %s\ncontroller fallbacks %lld, mpc fallbacks %lld, scored %lld of %zu\n",
              sim.Line().c_str(), review.Line().c_str(), static_cast<long long>(f.run.controller.fallbacks),
              static_cast<long long>(f.run.mpc.Fallbacks()), static_cast<long long>(sim.scored_samples),
              f.run.samples.size());
  EXPECT_EQ(sim.Line(), review.Line());
  EXPECT_EQ(sim.scored_samples, review.scored_samples);
  EXPECT_DOUBLE_EQ(f.metrics.rms_position_error_m, sim.rms_position_error_m);
  EXPECT_DOUBLE_EQ(f.metrics.peak_tilt_rad, sim.max_tilt_rad);
  EXPECT_DOUBLE_EQ(f.headline.verdict.max_tilt_rad, review.max_tilt_rad);
  EXPECT_EQ(sim.fallbacks, f.run.controller.fallbacks);
  EXPECT_EQ(f.headline.fallbacks, f.run.controller.fallbacks);
  EXPECT_EQ(sim.mpc_fallbacks, f.run.mpc.Fallbacks());
}

TEST(FlightFiguresTest, AFlightWithoutSetpointsSaysSoInsteadOfNan) {
  // A live flight that holds its first POSE (tools/demo.sh --controller ...)
  // publishes no SETPOINT: nothing to score the position against.
  FlightFigures figures;
  TruthSample truth;
  truth.utime = 1000;
  truth.x_dot_m_s = 0.1;
  truth.phi_rad = 0.02;
  figures.AddTruth(truth);
  const std::string line = figures.Result().Line();
  EXPECT_EQ(line, "RMS position error - (no SETPOINT), max tilt 0.0200 rad, fallbacks 0, MPC fallbacks 0");
  Setpoint setpoint;
  setpoint.utime = 1000;
  setpoint.x_m = 0.1;
  figures.AddSetpoint(setpoint);
  truth.utime = 2000;
  figures.AddTruth(truth);
  EXPECT_EQ(figures.Result().Line(), "RMS position error 0.1000 m, max tilt 0.0200 rad, fallbacks 0, MPC fallbacks 0");
}

TEST(FlightFiguresTest, ForceFeedbackFlightHasOneRmsTiltAndFallbackCount) {
  const FlownFlight f = FlyAndReview("sensor_faults", 20.0, false, "force_feedback");
  ExpectOneSetOfFigures(f);
  // Measured on the development VM: RMS 0.0036 m, max tilt 0.0116 rad, one
  // fallback (the 150 ms strain gap at 6 s).
  EXPECT_LT(f.headline.figures.rms_position_error_m, 1.5 * 0.0036);
  EXPECT_LT(f.headline.figures.max_tilt_rad, 1.5 * 0.0116);
  EXPECT_EQ(f.headline.figures.fallbacks, 1);
}

// Issue 39: the lock-step log carries the status channels at the daemons'
// rate (5 Hz on the vehicle clock), by the nodes' encoders, decodable.
TEST(FlightFiguresTest, LockStepLogCarriesBothStatusChannels) {
  const FlownFlight f = FlyAndReview("sensor_faults", 20.0, false, "force_feedback");
  const ChannelCount& estimator = f.data.channels.at("BIROTOR_ESTIMATOR_STATUS");
  const ChannelCount& controller = f.data.channels.at("BIROTOR_CONTROLLER_STATUS");
  const Table& c = f.data.controller_status;
  const Table& e = f.data.status;
  ASSERT_GT(c.rows(), 0u);
  ASSERT_GT(e.rows(), 0u);
  std::printf(
      "ESTIMATOR_STATUS %lld (decode errors %lld), CONTROLLER_STATUS %lld (%lld); last controller status: "
      "fallbacks %.0f commands %.0f mode %.0f; controller: %lld commands; last STRAIN received %.0f\n",
      static_cast<long long>(estimator.messages), static_cast<long long>(estimator.decode_errors),
      static_cast<long long>(controller.messages), static_cast<long long>(controller.decode_errors),
      c.columns[0].back(), c.columns[3].back(), c.columns[4].back(), static_cast<long long>(f.run.controller.commands),
      e.columns[3 * kReviewInputs].back());
  // 20 s at 5 Hz: one every 200 ms from 200 ms on (the first one period after the start).
  EXPECT_EQ(controller.messages, 100);
  EXPECT_NEAR(static_cast<double>(estimator.messages), 100.0, 1.0);
  EXPECT_EQ(controller.decode_errors + estimator.decode_errors, 0);
  // The counters are the controller's: at most one period (200 ms at 200 Hz:
  // 40 commands) behind its final health.
  EXPECT_EQ(c.columns[0].back(), static_cast<double>(f.run.controller.fallbacks));
  EXPECT_NEAR(c.columns[3].back(), static_cast<double>(f.run.controller.commands), 40.0);
  EXPECT_EQ(c.columns[4].back(), static_cast<double>(kModeForceFeedback));
  // ESTIMATOR_STATUS's STRAIN received (column 15: the fourth block of
  // kReviewInputs, input 0) counts the log's STRAIN, at most one period
  // behind (measured 19651 of the log's STRAIN).
  const double strain_in_log = static_cast<double>(f.data.channels.at("BIROTOR_STRAIN").messages);
  EXPECT_LE(e.columns[3 * kReviewInputs].back(), strain_in_log);
  EXPECT_GE(e.columns[3 * kReviewInputs].back(), strain_in_log - 0.2 * 1000.0);
}

TEST(FlightFiguresTest, GroundStartScoresFromTheLiftOff) {
  const FlownFlight f = FlyAndReview("hover", 8.0, true, "force_feedback");
  ExpectOneSetOfFigures(f);
  int64_t after_liftoff = 0;
  for (const TrackedSample& s : f.run.samples) after_liftoff += s.truth.utime >= f.run.liftoff_utime ? 1 : 0;
  std::printf("lift-off at %lld us; TRUTH samples from it %lld\n", static_cast<long long>(f.run.liftoff_utime),
              static_cast<long long>(after_liftoff));
  ASSERT_GE(f.run.liftoff_utime, 0);
  // The body leaves the support within a few truth samples of the
  // simulator's lift-off (measured: 3826 scored of 3840 from the lift-off);
  // before it, it is held still and nothing is flown. RMS measured 0.0025 m.
  EXPECT_LE(f.headline.figures.scored_samples, after_liftoff);
  EXPECT_GE(f.headline.figures.scored_samples, after_liftoff - 21);
  EXPECT_LT(f.headline.figures.rms_position_error_m, 1.5 * 0.0025);
}

// A work budget per solve small enough that some solves are late: the MPC's
// fallback periods (MPC_FALLBACK) appear in every program's figures.
constexpr int kTightWork = 25;

TEST(FlightFiguresTest, MpcFlightCountsItsFallbacksInTheReview) {
  const FlownFlight f = FlyAndReview("thrust_loss_severe", 15.0, false, "mpc", kTightWork);
  ExpectOneSetOfFigures(f);
  // Measured: 2998 of 2999 solves over the budget; the FORCE fallback of
  // mode mpc (one, as the controller counts it) is in the review's count.
  EXPECT_EQ(f.run.mpc.solves, 2999);
  EXPECT_GE(f.headline.figures.mpc_fallbacks, 2990);
  EXPECT_EQ(f.headline.fallbacks, 1);
}

}  // namespace
}  // namespace birotor
