// Issue 37 on the live closed loop (three processes on a private udpm URL,
// the test's site key): a peer on the same host sends, for 2 s at 1 kHz each,
// forged MOTOR_COMMAND, SETPOINT, POSE and FORCE - plain on the channels the
// wire contract names, sealed under another key on their _AUTH twins - and
// replays a captured, correctly sealed POSE_AUTH. None is accepted: each is
// counted refused (or replayed) in the receivers' GUARD_STATUS, and the
// vehicle holds its hover, in force feedback and in mode mpc. The counts
// allow for loopback datagrams the kernel drops on a busy machine; every
// count is printed. And a future-stamped IMU stream on the bus before the
// controller starts does not latch its clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "birotor/truth_t.hpp"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "tests/reliability/live_harness.h"
#include "tests/reliability/machine_stall_watch.h"
#include "transport/authenticated_envelope.h"
#include "transport/lcm_codec.h"

namespace birotor::reliability {
namespace {

constexpr double kAttackStartS = 2.0;  // after the simulator started [s]
constexpr double kAttackS = 2.0;
constexpr int kAttackRateHz = 1000;
// Not lost, on a machine that stalled through every attempt
// (machine_stall_watch.h): the live programs' verdict calls a flight lost
// beyond 1 rad of tilt. Measured through 100-250 ms stalls: up to 0.31 rad
// (the MPC) [rad].
constexpr double kLostTiltRad = 1.0;

// TRUTH (the hover's worst deviation after 1 s), GUARD_STATUS (the newest
// per program) and one real POSE_AUTH packet to replay, on its own thread.
class ForgeryListener {
 public:
  ForgeryListener(const std::string& url, const std::string& prefix) : lcm_(url), channels_(MakeChannelNames(prefix)) {
    lcm_.subscribe(channels_.truth, &ForgeryListener::OnTruth, this)->setQueueCapacity(100000);
    lcm_.subscribe(channels_.guard_status, &ForgeryListener::OnGuard, this)->setQueueCapacity(1000);
    lcm_.subscribe(channels_.pose_auth, &ForgeryListener::OnPoseAuth, this)->setQueueCapacity(1000);
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~ForgeryListener() {
    stop_ = true;
    thread_.join();
  }
  bool good() { return lcm_.good(); }
  double max_position_error_m() {
    std::lock_guard<std::mutex> lock(mutex_);
    return max_position_error_m_;
  }
  double max_tilt_rad() {
    std::lock_guard<std::mutex> lock(mutex_);
    return max_tilt_rad_;
  }
  bool Guard(int32_t program, guard_status_t* out) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = guards_.find(program);
    if (it == guards_.end()) return false;
    *out = it->second;
    return true;
  }
  std::vector<uint8_t> captured_pose_auth() {
    std::lock_guard<std::mutex> lock(mutex_);
    return pose_auth_;
  }

 private:
  void OnTruth(const lcm::ReceiveBuffer* buffer, const std::string&) {
    truth_t truth{};
    if (DecodeMessage(buffer->data, buffer->data_size, &truth) != DecodeError::kNone) return;
    if (truth.utime < 1000000) return;  // after the first second
    std::lock_guard<std::mutex> lock(mutex_);
    max_position_error_m_ = std::max({max_position_error_m_, std::fabs(truth.x_m), std::fabs(truth.z_m)});
    max_tilt_rad_ = std::max(max_tilt_rad_, std::fabs(truth.phi_rad));
  }
  void OnGuard(const lcm::ReceiveBuffer* buffer, const std::string&) {
    guard_status_t guard{};
    if (DecodeMessage(buffer->data, buffer->data_size, &guard) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    guards_[guard.program] = guard;
  }
  void OnPoseAuth(const lcm::ReceiveBuffer* buffer, const std::string&) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!pose_auth_.empty()) return;
    const uint8_t* bytes = static_cast<const uint8_t*>(buffer->data);
    pose_auth_.assign(bytes, bytes + buffer->data_size);
  }

  lcm::LCM lcm_;
  ChannelNames channels_;
  std::mutex mutex_;
  double max_position_error_m_ = 0;
  double max_tilt_rad_ = 0;
  std::map<int32_t, guard_status_t> guards_;
  std::vector<uint8_t> pose_auth_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// The forged messages of one millisecond k: every one a takeover if accepted.
void SendForgeries(int64_t k, const ChannelNames& channels, MessageSink* plain, MessageSink* wrong_key) {
  std::vector<uint8_t> bytes;
  const int64_t utime = 2000000 + 1000 * k;  // near the simulator's clock
  motor_command_t command{};
  command.utime = utime;
  command.seq = static_cast<int32_t>(100000 + k);
  EncodeMessage(command, &bytes);  // omega 0: the rotors stop
  for (MessageSink* sink : {plain, wrong_key}) sink->Publish(channels.motor_command, utime, bytes.data(), bytes.size());
  setpoint_t setpoint{};
  setpoint.utime = utime;
  setpoint.seq = static_cast<int32_t>(100000 + k);
  setpoint.x_m = 0.4;  // a jump within the bounds, every millisecond
  setpoint.x_dot_m_s = setpoint.z_dot_m_s = setpoint.x_ddot_m_s2 = setpoint.z_ddot_m_s2 = 0;
  EncodeMessage(setpoint, &bytes);
  for (MessageSink* sink : {plain, wrong_key}) sink->Publish(channels.setpoint, utime, bytes.data(), bytes.size());
  pose_t pose{};
  pose.utime = utime;
  pose.seq = static_cast<int32_t>(100000 + k);
  pose.x_m = -1.0;  // a metre off
  EncodeMessage(pose, &bytes);
  for (MessageSink* sink : {plain, wrong_key}) sink->Publish(channels.pose, utime, bytes.data(), bytes.size());
  force_estimate_t force{};
  force.utime = utime;
  force.seq = static_cast<int32_t>(100000 + k);
  force.force_n[0] = force.force_n[1] = 22.0;
  force.force_std_n[0] = force.force_std_n[1] = 0.1;
  force.thrust_scale[0] = 0.5;  // a rotor "losing" half its thrust
  force.thrust_scale[1] = 1.0;
  force.status = force_estimate_t::STATUS_VALID;
  EncodeMessage(force, &bytes);
  for (MessageSink* sink : {plain, wrong_key}) sink->Publish(channels.force, utime, bytes.data(), bytes.size());
}

struct ForgeryFlight {
  std::string mode;
  int64_t attack_count = 0;                                   // forgeries of each kind sent per channel
  guard_status_t at_controller{}, at_estimator{}, at_escs{};  // their last GUARD_STATUS
  double max_position_error_m = 0.0, max_tilt_rad = 0.0;      // after 1 s
  bool controller_alive = false, estimator_alive = false;
};

// One flight of the closed loop in mode (force_feedback or mpc) under the
// attack; a fatal failure ends it early.
void FlyOneForgeryAttack(const std::string& mode, int port, const std::string& prefix, ForgeryFlight* flight) {
  const std::string url = PrivateUrl(port);
  const ChannelNames channels = MakeChannelNames(prefix);
  ForgeryListener listener(url, prefix);
  ASSERT_TRUE(listener.good());
  ChildProcess estimator, controller, sim;
  ASSERT_TRUE(estimator.Start(DaemonCommand(url, prefix), TempPath("forgery_estimator_" + mode + ".log")));
  ASSERT_TRUE(controller.Start(ControllerCommand(url, prefix, mode), TempPath("forgery_controller_" + mode + ".log")));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let them subscribe
  ASSERT_TRUE(
      sim.Start({BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml",
                 "--lcm-url", url, "--prefix", prefix, "--set", "scenario.duration_s=7", "--external-controller",
                 "--publish-setpoints", "--log-level", "warn", "--realtime-priority", kSimPriority},
                TempPath("forgery_sim_" + mode + ".log")));
  std::this_thread::sleep_for(std::chrono::duration<double>(kAttackStartS));

  // The attacker: plain messages, the same sealed under a key of its own,
  // and a real POSE_AUTH sent again.
  lcm::LCM attacker_lcm(url);
  ASSERT_TRUE(attacker_lcm.good());
  LcmSink plain(&attacker_lcm);
  SiteKey::Bytes other_bytes{};
  other_bytes.fill(0x5a);
  const MessageAuthenticator other_key{SiteKey(other_bytes)};
  SigningSink wrong_key(&plain, &other_key, channels, ChannelSet{true, true, true, true}, 12345);
  const std::vector<uint8_t> replay = listener.captured_pose_auth();
  ASSERT_FALSE(replay.empty()) << "no POSE_AUTH from the simulator";
  flight->mode = mode;
  flight->attack_count = static_cast<int64_t>(kAttackS * kAttackRateHz);
  const double start_s = SteadyClockS();
  for (int64_t k = 0; k < flight->attack_count; ++k) {
    SendForgeries(k, channels, &plain, &wrong_key);
    attacker_lcm.publish(channels.pose_auth, replay.data(), static_cast<unsigned>(replay.size()));
    const double next_s = start_s + static_cast<double>(k + 1) / kAttackRateHz;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::max(0.0, next_s - SteadyClockS())));
  }
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 60.0)) << "the simulator did not finish";
  std::this_thread::sleep_for(std::chrono::milliseconds(400));  // the last GUARD_STATUS of the daemons
  flight->controller_alive = controller.Alive();
  flight->estimator_alive = estimator.Alive();
  ASSERT_TRUE(listener.Guard(guard_status_t::PROGRAM_CONTROLLER, &flight->at_controller));
  ASSERT_TRUE(listener.Guard(guard_status_t::PROGRAM_ESTIMATOR, &flight->at_estimator));
  ASSERT_TRUE(listener.Guard(guard_status_t::PROGRAM_SIM, &flight->at_escs));
  flight->max_position_error_m = listener.max_position_error_m();
  flight->max_tilt_rad = listener.max_tilt_rad();
}

constexpr int kCommand = guard_status_t::CHANNEL_MOTOR_COMMAND, kSetpoint = guard_status_t::CHANNEL_SETPOINT,
              kPose = guard_status_t::CHANNEL_POSE, kForce = guard_status_t::CHANNEL_FORCE;

void PrintForgeryFlight(const ForgeryFlight& f, const MachineStallWatch& watch) {
  const guard_status_t &at_controller = f.at_controller, &at_estimator = f.at_estimator, &at_escs = f.at_escs;
  std::printf(
      "mode %s: sent per channel: %lld plain + %lld under another key (sealed and its plain copy); POSE_AUTH "
      "replayed %lld\n"
      "refused at the ESCs MOTOR_COMMAND %lld; at the controller SETPOINT %lld, POSE %lld (replayed %lld), "
      "FORCE %lld; at the estimator POSE %lld (replayed %lld)\n"
      "accepted at the ESCs %lld, at the controller SETPOINT %lld POSE %lld FORCE %lld\n"
      "vehicle after 1 s: max |x|, |z| %.4f m, max |phi| %.4f rad; %s\n",
      f.mode.c_str(), static_cast<long long>(f.attack_count), static_cast<long long>(f.attack_count),
      static_cast<long long>(f.attack_count), static_cast<long long>(at_escs.refused[kCommand]),
      static_cast<long long>(at_controller.refused[kSetpoint]), static_cast<long long>(at_controller.refused[kPose]),
      static_cast<long long>(at_controller.replayed[kPose]), static_cast<long long>(at_controller.refused[kForce]),
      static_cast<long long>(at_estimator.refused[kPose]), static_cast<long long>(at_estimator.replayed[kPose]),
      static_cast<long long>(at_escs.accepted[kCommand]), static_cast<long long>(at_controller.accepted[kSetpoint]),
      static_cast<long long>(at_controller.accepted[kPose]), static_cast<long long>(at_controller.accepted[kForce]),
      f.max_position_error_m, f.max_tilt_rad, watch.Summary().c_str());
}

// The flight against its bounds: strict when the machine kept real time
// through it; else the counts of a machine that ran for less of the flight
// (half) and the hover not lost.
void JudgeForgeryFlight(const ForgeryFlight& f, bool strict) {
  EXPECT_TRUE(f.controller_alive);
  EXPECT_TRUE(f.estimator_alive);
  // Every forged message refused: 3 per millisecond and channel (the plain
  // one, and the other key's sealed one with its plain copy), less what the
  // kernel dropped on the way (a busy machine), never more than sent.
  const int64_t forged = 3 * f.attack_count;
  for (const int64_t refused : {f.at_escs.refused[kCommand], f.at_controller.refused[kSetpoint],
                                f.at_controller.refused[kPose], f.at_controller.refused[kForce]}) {
    EXPECT_GE(refused, forged * 9 / 10);
    EXPECT_LE(refused, forged);
  }
  EXPECT_GE(f.at_controller.replayed[kPose], f.attack_count * 9 / 10);
  EXPECT_GE(f.at_estimator.replayed[kPose], f.attack_count * 9 / 10);
  // The real streams flew the vehicle: the simulator's last GUARD_STATUS
  // (at 6 s) counts 6 s of commands at 500 Hz (mode mpc: 200 Hz), less the
  // start; POSE at 100 Hz.
  const int64_t command_rate_hz = f.mode == "mpc" ? 200 : 500;
  const int64_t share = strict ? 1 : 2;
  EXPECT_GT(f.at_escs.accepted[kCommand], 5 * command_rate_hz / share);
  EXPECT_GT(f.at_controller.accepted[kPose], 600 / share);
  EXPECT_GT(f.at_controller.accepted[kSetpoint], 600 / share);
  EXPECT_GT(f.at_controller.accepted[kForce], 6000 / share);
  // The hover held: issue 37's bound (0.2 m, 0.1 rad); not lost on a
  // machine that stalled through every attempt.
  EXPECT_LT(f.max_position_error_m, strict ? 0.2 : 1.0);
  EXPECT_LT(f.max_tilt_rad, strict ? 0.1 : kLostTiltRad);
}

// The closed loop in mode (force_feedback or mpc) under the attack.
void FlyUnderForgery(const std::string& mode, int port) {
  FlyJudgedOnRealTime<ForgeryFlight>(
      [&](int attempt, ForgeryFlight* flight) {
        FlyOneForgeryAttack(mode, port, UniquePrefix("FORGERY_" + mode + std::to_string(attempt) + "_"), flight);
      },
      PrintForgeryFlight, JudgeForgeryFlight);
}

TEST(LiveForgeryTest, ForgedAndReplayedSafetyMessagesAreRefusedAndTheCascadeHolds) {
  FlyUnderForgery("force_feedback", 7752);
}

TEST(LiveForgeryTest, ForgedAndReplayedSafetyMessagesAreRefusedAndTheMpcHolds) { FlyUnderForgery("mpc", 7753); }

struct FutureImuFlight {
  int64_t sent = 0;          // future-stamped IMU messages
  int64_t esc_accepted = 0;  // MOTOR_COMMAND accepted at the ESCs (their last GUARD_STATUS)
  double max_position_error_m = 0.0, max_tilt_rad = 0.0;  // after 1 s
  bool controller_alive = false;
};

// One flight beside the future-stamped IMU stream; a fatal failure ends it early.
void FlyBesideAFutureStampedImuStream(const std::string& prefix, FutureImuFlight* flight) {
  const std::string url = PrivateUrl(7754);
  const ChannelNames channels = MakeChannelNames(prefix);
  ForgeryListener listener(url, prefix);
  ASSERT_TRUE(listener.good());
  std::atomic<bool> stop{false};
  std::atomic<int64_t> sent{0};
  std::thread attacker([&] {
    lcm::LCM lcm(url);
    imu_t imu{};
    imu.accel_z_m_s2 = 9.81;
    std::vector<uint8_t> bytes;
    for (int64_t k = 0; !stop.load(); ++k) {
      imu.utime = 1000000000 + 1000 * k;  // 1000 s ahead of the vehicle clock
      imu.seq = static_cast<int32_t>(k);
      EncodeMessage(imu, &bytes);
      lcm.publish(channels.imu, bytes.data(), static_cast<unsigned>(bytes.size()));
      ++sent;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  // Joins the attacker on every way out, a failed ASSERT too.
  struct Joiner {
    std::atomic<bool>* stop;
    std::thread* thread;
    ~Joiner() {
      *stop = true;
      if (thread->joinable()) thread->join();
    }
  } joiner{&stop, &attacker};
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the stream is on the bus first
  ChildProcess estimator, controller, sim;
  ASSERT_TRUE(estimator.Start(DaemonCommand(url, prefix), TempPath("future_imu_estimator.log")));
  ASSERT_TRUE(
      controller.Start(ControllerCommand(url, prefix, "force_feedback"), TempPath("future_imu_controller.log")));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_TRUE(
      sim.Start({BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml",
                 "--lcm-url", url, "--prefix", prefix, "--set", "scenario.duration_s=6", "--external-controller",
                 "--log-level", "warn", "--realtime-priority", kSimPriority},
                TempPath("future_imu_sim.log")));
  const bool finished = DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 60.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  ASSERT_TRUE(finished) << "the simulator did not finish";
  flight->controller_alive = controller.Alive();
  guard_status_t at_escs{};
  ASSERT_TRUE(listener.Guard(guard_status_t::PROGRAM_SIM, &at_escs));
  flight->sent = sent.load();
  flight->esc_accepted = at_escs.accepted[guard_status_t::CHANNEL_MOTOR_COMMAND];
  flight->max_position_error_m = listener.max_position_error_m();
  flight->max_tilt_rad = listener.max_tilt_rad();
}

// Issue 37's latched clock: an IMU stream stamped 1000 s ahead is on the bus
// before the controller starts (as after a Restart=always). POSE is
// authenticated and IMU alone does not set the controller's clock (two
// inputs must agree), so the real inputs set it and the vehicle flies.
TEST(LiveForgeryTest, AControllerStartedBesideAFutureStampedImuStreamFlies) {
  FlyJudgedOnRealTime<FutureImuFlight>(
      [](int attempt, FutureImuFlight* f) {
        FlyBesideAFutureStampedImuStream(UniquePrefix("FUTURE_IMU" + std::to_string(attempt) + "_"), f);
      },
      [](const FutureImuFlight& f, const MachineStallWatch& watch) {
        std::printf(
            "future-stamped IMU sent %lld; MOTOR_COMMAND accepted at the ESCs %lld; max |x|, |z| %.4f m, "
            "max |phi| %.4f rad after 1 s; %s\n",
            static_cast<long long>(f.sent), static_cast<long long>(f.esc_accepted), f.max_position_error_m,
            f.max_tilt_rad, watch.Summary().c_str());
      },
      [](const FutureImuFlight& f, bool strict) {
        EXPECT_TRUE(f.controller_alive);
        // The simulator's last GUARD_STATUS (at 5 s) counts 5 s at 500 Hz, less
        // the start; a machine that stalled ran the controller for less of it.
        EXPECT_GT(f.esc_accepted, strict ? 2000 : 1000);
        // Held in a hover; on a machine that stalled through every attempt: not
        // lost (measured through 100-250 ms stalls: up to 0.27 m, 0.11 rad).
        EXPECT_LT(f.max_position_error_m, strict ? 0.2 : 1.0);
        EXPECT_LT(f.max_tilt_rad, strict ? 0.1 : kLostTiltRad);
      });
}

}  // namespace
}  // namespace birotor::reliability
