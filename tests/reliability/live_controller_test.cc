// The three processes of the closed loop live on a private udpm URL:
// birotor-sim --external-controller (the vehicle and its ESCs),
// birotor-estimator and birotor-controller. The estimator is SIGKILLed
// mid-flight and restarted: the controller falls back to the nominal map
// within 10 ms of the last FORCE, the vehicle keeps flying, and force
// feedback is back within 0.5 s of the restart. Times are taken on the
// vehicle clock (the utime of FORCE and MOTOR_COMMAND), which CPU load on the
// shared machine does not stretch; host arrival times are printed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "birotor/motor_command_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "birotor/truth_t.hpp"
#include "controller/reference_point.h"
#include "evaluation/closed_loop.h"
#include "evaluation/control_metrics.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "tests/reliability/live_harness.h"
#include "tests/reliability/machine_stall_watch.h"
#include "transport/message_conversion.h"

namespace birotor::reliability {
namespace {

struct CommandRecord {
  double arrival_s = 0;
  motor_command_t message;
};

// Subscribes to MOTOR_COMMAND and TRUTH on its own thread.
class ClosedLoopListener {
 public:
  ClosedLoopListener(const std::string& url, const std::string& prefix) : listener_(url, prefix) {
    listener_.Subscribe(listener_.channels().motor_command, &ClosedLoopListener::OnCommand, this);
    listener_.Subscribe(listener_.channels().truth, &ClosedLoopListener::OnTruth, this);
    listener_.Start();
  }
  bool good() { return listener_.good(); }
  std::vector<CommandRecord> Commands() {
    std::lock_guard<std::mutex> lock(mutex_);
    return commands_;
  }
  double max_altitude_error_m() {
    std::lock_guard<std::mutex> lock(mutex_);
    return max_altitude_error_m_;
  }
  int64_t truth_count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return truth_count_;
  }

 private:
  void OnCommand(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    AppendDecoded(buffer, &mutex_, &commands_);
  }
  void OnTruth(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    truth_t truth{};  // value-initialised: the decoder fills every field or fails
    if (DecodeMessage(buffer->data, buffer->data_size, &truth) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    ++truth_count_;
    max_altitude_error_m_ = std::max(max_altitude_error_m_, std::fabs(truth.z_m));  // hold at z = 0
  }

  std::mutex mutex_;
  std::vector<CommandRecord> commands_;
  double max_altitude_error_m_ = 0;
  int64_t truth_count_ = 0;
  ListenerThread listener_;  // last: stops first
};

TEST(LiveControllerTest, EstimatorKilledMidFlightFallsBackAndReturns) {
  const std::string url = PrivateUrl(7697);
  const std::string prefix = UniquePrefix("CTL_KILL_");
  DaemonListener forces(url, prefix);
  ClosedLoopListener loop(url, prefix);
  ASSERT_TRUE(forces.good());
  ASSERT_TRUE(loop.good());
  ChildProcess estimator, controller, sim;
  ASSERT_TRUE(estimator.Start(DaemonCommand(url, prefix), TempPath("controller_test_estimator.log")));
  ASSERT_TRUE(
      controller.Start(ControllerCommand(url, prefix, "force_feedback"), TempPath("controller_test_controller.log")));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let them subscribe
  ASSERT_TRUE(
      sim.Start({BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml",
                 "--lcm-url", url, "--prefix", prefix, "--set", "scenario.duration_s=6", "--external-controller",
                 "--log-level", "warn", "--realtime-priority", kSimPriority},
                TempPath("controller_test_sim.log")));
  // Flying in force feedback.
  ASSERT_TRUE(DaemonListener::WaitUntil(
      [&] {
        const std::vector<CommandRecord> c = loop.Commands();
        return c.size() > 500 && !(c.back().message.status & motor_command_t::STATUS_FALLBACK_ACTIVE);
      },
      20.0))
      << "no force-feedback command before the kill";
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  estimator.Kill(SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  const double restart_s = SteadyClockS();
  ASSERT_TRUE(estimator.Start(DaemonCommand(url, prefix), TempPath("controller_test_estimator.log")));
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 30.0)) << "the simulator did not finish";

  // The last FORCE of the killed estimator (every FORCE that arrived before
  // the restart is its: under load one in flight at the kill can reach this
  // listener more than 50 ms later), and the first fallback after it.
  ForceRecord last_force;
  last_force.arrival_s = -1;
  last_force.message.utime = -1;
  for (const ForceRecord& r : forces.Forces()) {
    if (r.arrival_s < restart_s && r.message.utime > last_force.message.utime) last_force = r;
  }
  ASSERT_GE(last_force.arrival_s, 0);
  const std::vector<CommandRecord> commands = loop.Commands();
  const CommandRecord* fallback = nullptr;
  const CommandRecord* back = nullptr;
  for (const CommandRecord& c : commands) {
    for (double omega : c.message.omega_cmd_rad_s) {
      ASSERT_TRUE(std::isfinite(omega));
      ASSERT_GE(omega, 0.0);
      ASSERT_LE(omega, 1200.0);  // omega_max of config/controller.yaml
    }
    const bool falls_back = c.message.status & motor_command_t::STATUS_FALLBACK_ACTIVE;
    if (fallback == nullptr && c.message.utime > last_force.message.utime && falls_back) fallback = &c;
    if (fallback != nullptr && back == nullptr && c.arrival_s > restart_s && !falls_back) back = &c;
  }
  ASSERT_NE(fallback, nullptr) << "no fallback after the kill";
  ASSERT_NE(back, nullptr) << "force feedback did not come back after the restart";
  const double fallback_vehicle_s = 1e-6 * static_cast<double>(fallback->message.utime - last_force.message.utime);
  // From the restart: the first FORCE of the new process (vehicle clock) to
  // the first force-feedback command.
  const ForceRecord first_new = forces.FirstForceWith(0, restart_s);
  ASSERT_GE(first_new.arrival_s, 0);
  const double back_vehicle_s = 1e-6 * static_cast<double>(back->message.utime - first_new.message.utime);
  std::printf(
      "fallback %.1f ms after the last FORCE (vehicle clock; %.1f ms host); force feedback back %.3f s after the "
      "first FORCE of the restarted estimator (%.3f s after exec, host); max |z| %.4f m; %zu commands, %lld truth\n",
      1e3 * fallback_vehicle_s, 1e3 * (fallback->arrival_s - last_force.arrival_s), back_vehicle_s,
      back->arrival_s - restart_s, loop.max_altitude_error_m(), commands.size(),
      static_cast<long long>(loop.truth_count()));
  // The rule, independent of scheduling: no command decided on a FORCE older
  // than force_timeout_s (5 ms, config/controller.yaml) is force feedback, from
  // the kill until the restarted estimator's first FORCE. (How soon the first
  // fallback command goes out also depends on when the controller gets the CPU:
  // 5-8 ms on a quiet machine, 11 ms measured with five busy loops beside it;
  // the figure is the README's, the bound here is only a sanity check.)
  // The listener may lose the killed estimator's last FORCE or two on a
  // loaded machine (UDP), which the controller got: 2 ms (two strain
  // periods) of slack on the stamp it saw last.
  constexpr int64_t kForceTimeoutUs = 5000, kMissedForcesUs = 2000;
  int64_t stale_commands = 0;
  for (const CommandRecord& c : commands) {
    if (c.message.utime > last_force.message.utime + kForceTimeoutUs + kMissedForcesUs &&
        c.message.utime < first_new.message.utime) {
      ++stale_commands;
      EXPECT_TRUE(c.message.status & motor_command_t::STATUS_FALLBACK_ACTIVE) << "command at " << c.message.utime;
    }
  }
  EXPECT_GT(stale_commands, 100);  // the 0.7 s without an estimator, at 500 Hz
  EXPECT_LE(fallback_vehicle_s, 0.05);
  EXPECT_LE(back_vehicle_s, 0.5);
  EXPECT_LT(loop.max_altitude_error_m(), 0.5);  // no crash
  EXPECT_GT(loop.truth_count(), 3000);          // 6000 sent; a loaded machine drops some
  EXPECT_TRUE(controller.Alive());
  EXPECT_EQ(controller.Stop(), 0);
  EXPECT_EQ(estimator.Stop(), 0);
}

// TRUTH and SETPOINT of a live flight: the RMS position error against the
// setpoint the controller was sent (extrapolated with its feed-forward, as
// the controller does).
class SetpointFlightListener {
 public:
  SetpointFlightListener(const std::string& url, const std::string& prefix) : listener_(url, prefix) {
    listener_.Subscribe(listener_.channels().truth, &SetpointFlightListener::OnTruth, this);
    listener_.Subscribe(listener_.channels().setpoint, &SetpointFlightListener::OnSetpoint, this);
    listener_.Start();
  }
  bool good() { return listener_.good(); }
  // RMS |p - p_ref| over the TRUTH samples that have a setpoint [m]; *count: how many.
  double RmsPositionErrorM(int64_t* count) {
    std::lock_guard<std::mutex> lock(mutex_);
    *count = count_;
    return count_ > 0 ? std::sqrt(sum_squared_m2_ / static_cast<double>(count_)) : -1.0;
  }
  int64_t setpoints() {
    std::lock_guard<std::mutex> lock(mutex_);
    return setpoints_;
  }
  // Largest |p - p_ref| over the same samples [m].
  double MaxPositionErrorM() {
    std::lock_guard<std::mutex> lock(mutex_);
    return max_error_m_;
  }

 private:
  void OnSetpoint(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    setpoint_t message;
    if (DecodeMessage(buffer->data, buffer->data_size, &message) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    newest_ = FromMessage(message);
    ++setpoints_;
  }
  void OnTruth(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    truth_t m{};  // value-initialised: the decoder fills every field or fails
    if (DecodeMessage(buffer->data, buffer->data_size, &m) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (setpoints_ == 0 || m.utime < newest_.utime) return;
    const ReferencePoint r = ReferenceFromSetpoint(newest_, 1e-6 * static_cast<double>(m.utime - newest_.utime));
    const double dx = m.x_m - r.position_m.x(), dz = m.z_m - r.position_m.y();
    sum_squared_m2_ += dx * dx + dz * dz;
    max_error_m_ = std::max(max_error_m_, std::hypot(dx, dz));
    ++count_;
  }

  std::mutex mutex_;
  Setpoint newest_;
  int64_t setpoints_ = 0;
  double sum_squared_m2_ = 0;
  double max_error_m_ = 0;
  int64_t count_ = 0;
  ListenerThread listener_;  // last: stops first
};

// The lock-step RMS position error of a scenario with overrides, flown in
// mode (force_feedback or mpc, as birotor-controller --mode) [m].
double LockStepRms(const std::string& scenario_name, const std::vector<std::string>& overrides,
                   const std::string& mode) {
  const std::string config = std::string(BIROTOR_SOURCE_DIR) + "/config/";
  const Scenario scenario = LoadScenario(config + "scenarios/" + scenario_name + ".yaml", overrides);
  ControllerConfig controller = LoadControllerConfig(config + "controller.yaml");
  controller.force_feedback = true;  // mpc falls back to the force-feedback cascade
  controller.model_predictive = mode == "mpc";
  const ClosedLoopRun run =
      RunClosedLoop(scenario, LoadEstimatorConfig(config + "estimator.yaml"), controller, ClosedLoopOptions());
  return EvaluateControl(run).rms_position_error_m;
}

// birotor-sim --external-controller --publish-setpoints, the estimator and
// birotor-controller --mode <mode> over udpm fly gentle and aggressive
// (duration_s each, real time). What holds on any machine, however busy: every
// command finite and within [0, omega_max] (the ESCs' own check), the vehicle
// kept within kKeptErrorM of its setpoint, every process alive and stopping
// cleanly. How close the live RMS comes to the lock-step figure depends on the
// scheduling of four processes on the cores; it is printed as a figure (docs/
// realtime.md quotes it), not asserted.
// The vehicle is kept: four times the largest error measured live (0.023 m,
// force feedback on aggressive), far below a lost flight (metres) [m].
constexpr double kKeptErrorM = 0.1;
// On a machine that stalled through every attempt (machine_stall_watch.h):
// not lost. Measured on the development VM through 100 ms host stalls:
// 0.29 m on aggressive (the ESCs spooled down in the stall) [m].
constexpr double kNotLostErrorM = 1.0;

struct SetpointFlight {
  int64_t truths = 0;  // TRUTH samples compared with the setpoint
  int64_t setpoints = 0;
  double live_rms_m = 0.0, max_error_m = 0.0;
  bool controller_alive = false;
  int controller_exit = -1, estimator_exit = -1;
};

// One live flight of scenario name; a fatal failure ends it early.
void FlyOneSetpointFlight(const std::string& mode, const std::string& name, int port, int duration_s,
                          const std::string& prefix, SetpointFlight* flight) {
  const std::string url = PrivateUrl(port);
  SetpointFlightListener listener(url, prefix);
  ASSERT_TRUE(listener.good());
  ChildProcess estimator, controller, sim;
  ASSERT_TRUE(estimator.Start(DaemonCommand(url, prefix), TempPath("setpoint_test_estimator_" + mode + ".log")));
  ASSERT_TRUE(
      controller.Start(ControllerCommand(url, prefix, mode), TempPath("setpoint_test_controller_" + mode + ".log")));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let them subscribe
  ASSERT_TRUE(sim.Start(
      {BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml",
       "--lcm-url", url, "--prefix", prefix, "--set", "scenario.duration_s=" + std::to_string(duration_s),
       "--external-controller", "--publish-setpoints", "--log-level", "warn", "--realtime-priority", kSimPriority},
      TempPath("setpoint_test_sim_" + mode + ".log")));
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 60.0)) << "the simulator did not finish";
  flight->live_rms_m = listener.RmsPositionErrorM(&flight->truths);
  flight->max_error_m = listener.MaxPositionErrorM();
  flight->setpoints = listener.setpoints();
  flight->controller_alive = controller.Alive();
  flight->controller_exit = controller.Stop();
  flight->estimator_exit = estimator.Stop();
}

void FlySetpointsLive(const std::string& mode, int port, int duration_s) {
  for (const std::string name : {"gentle", "aggressive"}) {
    const double lock_step_rms = LockStepRms(name, {"scenario.duration_s=" + std::to_string(duration_s)}, mode);
    FlyJudgedOnRealTime<SetpointFlight>(
        [&](int attempt, SetpointFlight* f) {
          FlyOneSetpointFlight(mode, name, port, duration_s,
                               UniquePrefix("CTL_SP_" + name + std::to_string(attempt) + "_"), f);
        },
        [&](const SetpointFlight& f, const MachineStallWatch& watch) {
          std::printf(
              "%s %s: live RMS %.4f m (max %.4f m) over %lld TRUTH samples (%lld setpoints), lock-step %.4f m "
              "(ratio %.3f); %s\n",
              mode.c_str(), name.c_str(), f.live_rms_m, f.max_error_m, static_cast<long long>(f.truths),
              static_cast<long long>(f.setpoints), lock_step_rms, f.live_rms_m / lock_step_rms,
              watch.Summary().c_str());
        },
        [&](const SetpointFlight& f, bool strict) {
          EXPECT_GT(f.truths, 500 * duration_s);  // 1000 a second sent; a loaded machine drops some
          EXPECT_LT(f.max_error_m, strict ? kKeptErrorM : kNotLostErrorM) << mode << " " << name;
          EXPECT_TRUE(f.controller_alive);
          EXPECT_EQ(f.controller_exit, 0);
          EXPECT_EQ(f.estimator_exit, 0);
        });
    if (::testing::Test::HasFatalFailure()) return;
  }
}

// The cascade with force feedback, 8 s each.
TEST(LiveControllerTest, SetpointsFlownLiveKeepTheVehicle) { FlySetpointsLive("force_feedback", 7699, 8); }

// The MPC (its solves on the wall clock, deadline 5 ms, the cascade its
// per-period fallback), 4 s each to keep the suite's time: aggressive's 2 s
// move to (1, 1) and 2 s of hold, gentle's first 4 s.
TEST(LiveControllerTest, SetpointsFlownLiveByTheMpcKeepTheVehicle) { FlySetpointsLive("mpc", 7698, 4); }

}  // namespace
}  // namespace birotor::reliability
