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
#include "birotor/truth_t.hpp"
#include "tests/reliability/live_harness.h"

namespace birotor::reliability {
namespace {

struct CommandRecord {
  double arrival_s = 0;
  motor_command_t message;
};

// Subscribes to MOTOR_COMMAND and TRUTH on its own thread.
class ClosedLoopListener {
 public:
  ClosedLoopListener(const std::string& url, const std::string& prefix)
      : lcm_(url), channels_(MakeChannelNames(prefix)) {
    lcm_.subscribe(channels_.motor_command, &ClosedLoopListener::OnCommand, this)->setQueueCapacity(100000);
    lcm_.subscribe(channels_.truth, &ClosedLoopListener::OnTruth, this)->setQueueCapacity(100000);
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~ClosedLoopListener() {
    stop_ = true;
    thread_.join();
  }
  bool good() { return lcm_.good(); }
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
    CommandRecord record;
    record.arrival_s = SteadyClockS();
    if (DecodeMessage(buffer->data, buffer->data_size, &record.message) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    commands_.push_back(record);
  }
  void OnTruth(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    truth_t truth{};  // value-initialised: the decoder fills every field or fails
    if (DecodeMessage(buffer->data, buffer->data_size, &truth) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    ++truth_count_;
    max_altitude_error_m_ = std::max(max_altitude_error_m_, std::fabs(truth.z_m));  // hold at z = 0
  }

  lcm::LCM lcm_;
  ChannelNames channels_;
  std::mutex mutex_;
  std::vector<CommandRecord> commands_;
  double max_altitude_error_m_ = 0;
  int64_t truth_count_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
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
  ASSERT_TRUE(controller.Start(
      {BIROTOR_CONTROLLER_BIN, "--lcm-url", url, "--prefix", prefix, "--mode", "force_feedback", "--log-level", "warn"},
      TempPath("controller_test_controller.log")));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let them subscribe
  ASSERT_TRUE(sim.Start(
      {BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml", "--lcm-url",
       url, "--prefix", prefix, "--set", "scenario.duration_s=6", "--external-controller", "--log-level", "warn"},
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
  const double kill_s = SteadyClockS();
  estimator.Kill(SIGKILL);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  const double restart_s = SteadyClockS();
  ASSERT_TRUE(estimator.Start(DaemonCommand(url, prefix), TempPath("controller_test_estimator.log")));
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 30.0)) << "the simulator did not finish";

  // The last FORCE of the killed estimator, and the first fallback after it.
  ForceRecord last_force;
  last_force.arrival_s = -1;
  for (const ForceRecord& r : forces.Forces()) {
    if (r.arrival_s < kill_s + 0.05) last_force = r;  // in flight when the kill landed
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
  constexpr int64_t kForceTimeoutUs = 5000;
  int64_t stale_commands = 0;
  for (const CommandRecord& c : commands) {
    if (c.message.utime > last_force.message.utime + kForceTimeoutUs && c.message.utime < first_new.message.utime) {
      ++stale_commands;
      EXPECT_TRUE(c.message.status & motor_command_t::STATUS_FALLBACK_ACTIVE) << "command at " << c.message.utime;
    }
  }
  EXPECT_GT(stale_commands, 100);  // the 0.7 s without an estimator, at 500 Hz
  EXPECT_LE(fallback_vehicle_s, 0.05);
  EXPECT_LE(back_vehicle_s, 0.5);
  EXPECT_LE(back->arrival_s - restart_s, 10.0);  // generous: start-up on a shared, loaded machine
  EXPECT_LT(loop.max_altitude_error_m(), 0.5);   // no crash
  EXPECT_GT(loop.truth_count(), 3000);           // 6000 sent; a loaded machine drops some
  EXPECT_TRUE(controller.Alive());
  EXPECT_EQ(controller.Stop(), 0);
  EXPECT_EQ(estimator.Stop(), 0);
}

}  // namespace
}  // namespace birotor::reliability
