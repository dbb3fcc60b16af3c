// The N-rotor controller node (nodes/multi_arm_controller_service.h) on the
// trirotor, through its one way in on its own host clock: a FORCE_N of
// another rotor count is refused and counted, a stale or absent FORCE_N
// flies the nominal map (STATUS_FALLBACK_ACTIVE) and force feedback resumes
// only after force_recovery_s of healthy FORCE_N, a flagged scale below the
// floor is flown at the floor, a future stamp is refused,
// every MOTOR_COMMAND_N carries 3 rotor speeds within [0, omega_max], and a
// plain FORCE_N in front of the sealed channel is refused, and
// CONTROLLER_ROTORS_N goes out with CONTROLLER_STATUS carrying every rotor.
#include "nodes/multi_arm_controller_service.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "birotor/controller_rotors_n_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "model/vehicle_description_checksum.h"
#include "nodes/guard_status_message.h"
#include "params/vehicle_description_yaml.h"
#include "security/message_authenticator.h"
#include "sources/authenticating_handler.h"
#include "tests/security/counting_key.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

// Keeps the MOTOR_COMMAND_N, CONTROLLER_STATUS and CONTROLLER_ROTORS_N the node publishes.
class CommandSink : public MessageSink {
 public:
  explicit CommandSink(std::string channel, std::string status_channel = "", std::string rotors_channel = "")
      : channel_(std::move(channel)),
        status_channel_(std::move(status_channel)),
        rotors_channel_(std::move(rotors_channel)) {}
  void Publish(const std::string& channel, int64_t, const void* data, size_t size) override {
    motor_command_n_t command;
    controller_status_t status;
    controller_rotors_n_t rotors;
    if (channel == channel_ && DecodeMessage(data, size, &command) == DecodeError::kNone) commands.push_back(command);
    if (channel == status_channel_ && DecodeMessage(data, size, &status) == DecodeError::kNone)
      statuses.push_back(status);
    if (channel == rotors_channel_ && DecodeMessage(data, size, &rotors) == DecodeError::kNone)
      rotors_messages.push_back(rotors);
  }
  std::vector<motor_command_n_t> commands;
  std::vector<controller_status_t> statuses;
  std::vector<controller_rotors_n_t> rotors_messages;

 private:
  std::string channel_;
  std::string status_channel_;
  std::string rotors_channel_;
};

template <class Message>
std::vector<uint8_t> Encoded(const Message& message) {
  std::vector<uint8_t> bytes;
  EncodeMessage(message, &bytes);
  return bytes;
}

// Each rotor's force: its scale times its hover thrust (rotor 1 27.47 N,
// the others 14.32 N: trirotor.yaml's header), sigma 0.05 N.
std::vector<uint8_t> ForceN(int n, int64_t utime, int32_t seq, int32_t status, double rotor1_scale = 0.8,
                            int32_t rotor_fault_bits = 0, double others_scale = 0.8) {
  force_estimate_n_t m{};
  m.utime = utime;
  m.seq = seq;
  m.n_rotors = static_cast<int8_t>(n);
  m.force_std_n.assign(static_cast<size_t>(n), 0.05);
  m.thrust_scale.assign(static_cast<size_t>(n), others_scale);  // 20 % lost on every rotor
  m.thrust_scale[0] = rotor1_scale;
  m.force_n.assign(static_cast<size_t>(n), 14.32 * others_scale);
  m.force_n[0] = 27.47 * rotor1_scale;
  m.status = status;
  m.rotor_fault_bits = rotor_fault_bits;
  return Encoded(m);
}

// The node on the trirotor in mode force_feedback (kMpc false) or mpc.
template <bool kMpc>
class ServiceFixture : public ::testing::Test {
 protected:
  // One packet at host time host_us; the vehicle clock is host time - 1 s.
  void Send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t host_us) {
    host_us_ = host_us;
    service_.HandlePacket(channel, bytes.data(), bytes.size(), -1);
  }
  // POSE (at rest at x_m, else the origin) and IMU stamped at the vehicle time of host_us.
  void SendPoseAndImu(int64_t host_us, int32_t seq, double x_m = 0.0) {
    pose_t pose{};
    pose.utime = host_us - kOffsetUs;
    pose.seq = seq;
    pose.x_m = x_m;
    imu_t imu{};
    imu.utime = host_us - kOffsetUs;
    imu.seq = seq;
    imu.accel_z_m_s2 = vehicle_.gravity_m_s2;  // hover: the specific force holds up the weight
    Send(channels_.pose, Encoded(pose), host_us);
    Send(channels_.imu, Encoded(imu), host_us);
  }
  // The daemon's loop: a period whenever one is due, checked every 1 ms up to host_us.
  void RunUntil(int64_t host_us) {
    for (; now_us_ <= host_us; now_us_ += 1000) service_.RunIfDue(now_us_);
  }
  // POSE (unless without_pose) and IMU at 100 Hz, FORCE_N (VALID, 20 % lost)
  // at 1 kHz and the periods, over host time [from_us, to_us].
  void Fly(int64_t from_us, int64_t to_us, bool without_pose = false) {
    for (int64_t host_us = from_us; host_us <= to_us; host_us += 1000) {
      if (host_us % 10000 == 0 && !without_pose) SendPoseAndImu(host_us, ++pose_seq_);
      if (host_us % 10000 == 0 && without_pose) SendImu(host_us);
      Send(channels_.force_n,
           ForceN(3, host_us - kOffsetUs, static_cast<int32_t>(host_us / 1000), force_estimate_n_t::STATUS_VALID,
                  rotor1_scale_, rotor_fault_bits_, others_scale_),
           host_us);
      RunUntil(host_us);
    }
  }
  // 2 s of healthy FORCE_N (every rotor at 1) up to host 4.999 s: the
  // controller's EfficiencyConditioner airborne (airborne_s 0.05 s) with its
  // baselines settled (baseline_tau_s 1 s) and its blend into following
  // over (blend_s 1.5 s), so Fly's 20 % is a change it follows (fault_tau_s
  // 0.01 s).
  void Settle() {
    now_us_ = 3000000;
    rotor1_scale_ = others_scale_ = 1.0;
    Fly(3000000, 4999000);
    rotor1_scale_ = others_scale_ = 0.8;
  }
  double rotor1_scale_ = 0.8;     // FORCE_N's thrust_scale of rotor 1 in Fly
  double others_scale_ = 0.8;     // ... of rotors 2 and 3
  int32_t rotor_fault_bits_ = 0;  // ... and its rotor_fault_bits
  void SendImu(int64_t host_us) {
    imu_t imu{};
    imu.utime = host_us - kOffsetUs;
    imu.seq = ++pose_seq_;
    imu.accel_z_m_s2 = vehicle_.gravity_m_s2;
    Send(channels_.imu, Encoded(imu), host_us);
  }
  int32_t pose_seq_ = 0;

  static constexpr int64_t kOffsetUs = 1000000;  // host time - vehicle time [us]
  const VehicleDescription vehicle_ =
      LoadVehicleDescription(std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml");
  const ChannelNames channels_ = MakeChannelNames("TEST_");
  CommandSink sink_{channels_.motor_command_n, channels_.controller_status, channels_.controller_rotors_n};
  int64_t host_us_ = 0;
  int64_t now_us_ = 5000000;  // RunUntil's next check
  MultiArmControllerService service_{vehicle_, Config(), channels_, &sink_, [this] { return host_us_; }};

 private:
  static ControllerConfig Config() {
    ControllerConfig config;
    config.model_predictive = kMpc;
    return config;
  }
};
using MultiArmControllerServiceTest = ServiceFixture<false>;
using MultiArmControllerServiceMpcTest = ServiceFixture<true>;

TEST_F(MultiArmControllerServiceTest, AForceNOfAnotherRotorCountIsRefusedAndCounted) {
  SendPoseAndImu(5000000, 1);
  ASSERT_EQ(service_.VehicleTimeUs(5000000), 5000000 - kOffsetUs);
  Send(channels_.force_n, ForceN(2, 4000000, 1, force_estimate_n_t::STATUS_VALID), 5000000);
  Send(channels_.force_n, ForceN(4, 4000000, 2, force_estimate_n_t::STATUS_VALID), 5000000);
  EXPECT_EQ(service_.force_count_refusals().mismatch, 2);
  EXPECT_EQ(service_.decode_errors(ControllerInput::kForce), 2);
  EXPECT_EQ(service_.health().force.received, 0);  // never reached the supervision
  Send(channels_.force_n, ForceN(3, 4000000, 3, force_estimate_n_t::STATUS_VALID), 5000000);
  EXPECT_EQ(service_.health().force.accepted, 1);
}

TEST_F(MultiArmControllerServiceTest, StaleOrInvalidForceNFliesTheNominalMapAndSaysSo) {
  Settle();
  // 0.2 s of POSE (100 Hz), IMU and FORCE_N (1 kHz) reporting a 20 % loss.
  Fly(5000000, 5200000);
  ASSERT_FALSE(sink_.commands.empty());
  EXPECT_EQ(sink_.commands.back().status & motor_command_n_t::STATUS_FALLBACK_ACTIVE, 0);
  // The efficiency in use is the reported 0.8 (changed by more than change_threshold).
  const double followed = service_.controller().EfficiencyInUse()[1];
  EXPECT_NEAR(followed, 0.8, 1e-6);
  // FORCE_N silent for 10 ms (force_timeout_s 5 ms): the fallback, the
  // efficiency decaying towards the nominal map's 1 over decay_s (3 s).
  RunUntil(5210000);
  EXPECT_NE(sink_.commands.back().status & motor_command_n_t::STATUS_FALLBACK_ACTIVE, 0);
  EXPECT_EQ(service_.health().fallbacks, 1);
  EXPECT_GT(service_.controller().EfficiencyInUse()[1], followed);
  EXPECT_LT(service_.controller().EfficiencyInUse()[1], 0.81);
  // Back, but not VALID: still the nominal map.
  Send(channels_.force_n, ForceN(3, 5211000 - kOffsetUs, 5211, 0), 5211000);
  RunUntil(5212000);
  EXPECT_NE(sink_.commands.back().status & motor_command_n_t::STATUS_FALLBACK_ACTIVE, 0);
  EXPECT_EQ(service_.health().force_unhealthy, 1);
  for (const motor_command_n_t& command : sink_.commands) {
    ASSERT_EQ(command.n_rotors, 3);
    for (double omega : command.omega_cmd_rad_s) {
      EXPECT_GE(omega, 0.0);
      EXPECT_LE(omega, vehicle_.omega_max_rad_s);
    }
  }
}

// The force recovery rule (ForceRecovery, the birotor's): force feedback
// resumes only after force_recovery_s (0.05 s) of healthy, on-time FORCE_N,
// so a run of late FORCE_N on a loaded host is one fallback, not one per
// late sample. POSE at 100 Hz, FORCE_N at 1 kHz, periods at 500 Hz; 0.3 s
// healthy, then three late FORCE_N (each 8 ms after the one before,
// force_timeout_s 5 ms) 20 ms apart. Measured on this sequence: the node
// before ForceRecovery (main at 8d7227e) entered the fallback 3 times (once
// per late FORCE_N) and STATUS_FALLBACK_ACTIVE toggled 6 times; with it 1
// entry, 3 toggles (the start's exit included), force feedback back at
// host 5.390 s = the last late one + 50 ms (bound: + one 2 ms period).
TEST_F(MultiArmControllerServiceTest, LateForceNTogglesTheFallbackOnceAndRecoversAfterForceRecoveryS) {
  Settle();
  const int64_t late_host_us[3] = {5300000, 5320000, 5340000};
  int64_t recovered_host_us = -1;
  for (int64_t host_us = 5000000; host_us <= 5500000; host_us += 1000) {
    if (host_us % 10000 == 0) SendPoseAndImu(host_us, ++pose_seq_);
    // The 7 FORCE_N before each late one are not sent (stamps 8 ms apart).
    bool withheld = false;
    for (int64_t late_us : late_host_us) withheld = withheld || (host_us > late_us - 8000 && host_us < late_us);
    if (!withheld)
      Send(channels_.force_n,
           ForceN(3, host_us - kOffsetUs, static_cast<int32_t>(host_us / 1000), force_estimate_n_t::STATUS_VALID),
           host_us);
    const bool was_fallback = service_.health().fallback_active;
    RunUntil(host_us);
    if (host_us > late_host_us[2] && was_fallback && !service_.health().fallback_active && recovered_host_us < 0)
      recovered_host_us = host_us;
  }
  int toggles = 0;
  for (size_t i = 1; i < sink_.commands.size(); ++i) {
    const int32_t flag = motor_command_n_t::STATUS_FALLBACK_ACTIVE;
    toggles += (sink_.commands[i].status & flag) != (sink_.commands[i - 1].status & flag) ? 1 : 0;
  }
  // The start in the fallback (FORCE_N not yet healthy for 50 ms, in Settle) is not an entry.
  EXPECT_EQ(service_.health().fallbacks, 1);
  EXPECT_EQ(toggles, 3);  // start -> flown on FORCE_N, the late run's entry, its recovery
  // The last late FORCE_N (vehicle time 4.34 s) starts the healthy run again:
  // force feedback at its stamp + force_recovery_s, on the 500 Hz grid.
  EXPECT_GE(recovered_host_us, late_host_us[2] + 50000);
  EXPECT_LE(recovered_host_us, late_host_us[2] + 52000);
  EXPECT_EQ(sink_.commands.back().status & motor_command_n_t::STATUS_FALLBACK_ACTIVE, 0);
  EXPECT_NEAR(service_.controller().EfficiencyInUse()[1], 0.8, 1e-6);
}

// CONTROLLER_STATUS in mode mpc: one solve per 200 Hz period, the solve
// times (the birotor's window, MpcSolveTimes) filled, no longer NaN, and the
// efficiency of rotors 1 and 2 (the message's two slots): on its way from 1
// to the reported 0.8 after 0.2 s, then 0.8 (every rotor at 0.8 from
// take-off: the absolute rule, airborne after airborne_s 0.05 s, trusted
// absolute_settle_s 0.02 s later, then a towards mu0 = 0.8 with
// absolute_tau_s 0.2 s, within 1e-3 1.4 s later).
TEST_F(MultiArmControllerServiceMpcTest, ControllerStatusCarriesTheMpcSolveTimes) {
  Fly(5000000, 5200000);
  service_.PublishStatus(0, 5200000);
  ASSERT_EQ(sink_.statuses.size(), 1u);
  const controller_status_t& status = sink_.statuses.back();
  // The first POSE comes before the clock is set (by the IMU after it,
  // ControllerClock) and is not flown: periods at 200 Hz from the second
  // POSE at host 5.01 s to 5.2 s, both included: 39, each a solve.
  EXPECT_EQ(static_cast<int64_t>(sink_.commands.size()), 39);
  EXPECT_EQ(status.mpc_solves, 39);
  ASSERT_TRUE(std::isfinite(status.mpc_solve_p50_us));
  EXPECT_GT(status.mpc_solve_p50_us, 0.0);
  EXPECT_LE(status.mpc_solve_p50_us, status.mpc_solve_p99_us);
  EXPECT_LE(status.mpc_solve_p99_us, status.mpc_solve_max_us);
  EXPECT_GE(status.mpc_max_iterations, status.mpc_iterations);
  for (int i = 0; i < 2; ++i) {
    EXPECT_GT(status.efficiency[i], 0.81) << i;
    EXPECT_LT(status.efficiency[i], 1.0) << i;
  }
  Fly(5201000, 6600000);
  service_.PublishStatus(0, 6600000);
  EXPECT_NEAR(sink_.statuses.back().efficiency[0], 0.8, 1e-3);
  EXPECT_NEAR(sink_.statuses.back().efficiency[1], 0.8, 1e-3);
}

// POSE lost (pose_timeout_s 0.05 s): the controlled descent
// (DescentReference), STATUS_DESCENDING with STATUS_INPUT_STALE, one entry;
// POSE back: the setpoint again.
TEST_F(MultiArmControllerServiceTest, LostPoseGivesTheControlledDescentOnce) {
  Fly(5000000, 5200000);
  EXPECT_EQ(sink_.commands.back().status & motor_command_n_t::STATUS_DESCENDING, 0);
  Fly(5201000, 5300000, /*without_pose=*/true);
  // The last POSE at vehicle 4.200 s; its age exceeds 0.05 s first in the
  // 500 Hz period at 4.252 s.
  int64_t first_descending_us = -1;
  for (const motor_command_n_t& command : sink_.commands)
    if ((command.status & motor_command_n_t::STATUS_DESCENDING) != 0 && first_descending_us < 0)
      first_descending_us = command.utime;
  EXPECT_EQ(first_descending_us, 4252000);
  EXPECT_NE(sink_.commands.back().status & motor_command_n_t::STATUS_INPUT_STALE, 0);
  EXPECT_EQ(service_.health().descents, 1);
  EXPECT_TRUE(service_.health().descending);
  Fly(5301000, 5320000);
  EXPECT_EQ(sink_.commands.back().status & motor_command_n_t::STATUS_DESCENDING, 0);
  EXPECT_EQ(service_.health().descents, 1);
}

// FORCE_N reporting rotor 1 at 0.2 (below its hover bound 0.423, docs/
// controller.md "Degrading with N rotors"): after infeasible_s (0.1 s) the
// controller's descent, STATUS_DESCENDING with STATUS_HOVER_INFEASIBLE
// (latched), one descent and one infeasible entry, rotor 1 flown at 0.2.
TEST_F(MultiArmControllerServiceTest, InfeasibleHoverGivesTheLatchedDescent) {
  Settle();
  Fly(5000000, 5200000);
  EXPECT_EQ(sink_.commands.back().status & motor_command_n_t::STATUS_HOVER_INFEASIBLE, 0);
  rotor1_scale_ = 0.2;
  Fly(5201000, 5400000);
  const int32_t status = sink_.commands.back().status;
  EXPECT_NE(status & motor_command_n_t::STATUS_DESCENDING, 0);
  EXPECT_NE(status & motor_command_n_t::STATUS_HOVER_INFEASIBLE, 0);
  EXPECT_EQ(status & motor_command_n_t::STATUS_INPUT_STALE, 0);
  EXPECT_EQ(service_.health().descents, 1);
  EXPECT_EQ(service_.health().infeasible, 1);
  EXPECT_NEAR(service_.health().efficiency[0], 0.2, 1e-6);
  for (const motor_command_n_t& command : sink_.commands)
    for (double omega : command.omega_cmd_rad_s) EXPECT_TRUE(omega >= 0.0 && omega <= 1200.0);
}

// Rotor 1 at 15 %, below min_plausible_thrust_scale (0.2): without the
// fault flag every FORCE_N is refused (the nominal map); flagged, the first
// at_floor_samples - 1 (4) are refused and every later one is flown at the
// floor (the controller's ForceFloorEvidence, before the node's checks),
// once ForceRecovery has seen force_recovery_s of them.
TEST_F(MultiArmControllerServiceTest, AFlaggedForceNBelowTheFloorIsFlownAtTheFloor) {
  Settle();
  Fly(5000000, 5200000);
  const int64_t refused_before = service_.health().force.rejected_invalid;
  rotor1_scale_ = 0.15;
  Fly(5201000, 5210000);  // 10 FORCE_N, unflagged
  EXPECT_EQ(service_.health().force.rejected_invalid - refused_before, 10);
  EXPECT_EQ(service_.health().force_at_floor, 0);
  EXPECT_NE(sink_.commands.back().status & motor_command_n_t::STATUS_FALLBACK_ACTIVE, 0);
  // Flagged: the 5th (5215 ms) is the first accepted, late after the
  // refusals, so force feedback resumes force_recovery_s (50 ms) later.
  // The conditioner then follows the floor from the 0.8 it held (within
  // 1e-3 of 0.2 by 5.37 s).
  rotor_fault_bits_ = 1;
  Fly(5211000, 5370000);  // 160 FORCE_N, flagged
  EXPECT_EQ(service_.health().force.rejected_invalid - refused_before, 14);
  EXPECT_EQ(service_.health().force_at_floor, 156);
  EXPECT_EQ(sink_.commands.back().status & motor_command_n_t::STATUS_FALLBACK_ACTIVE, 0);
  EXPECT_NEAR(service_.controller().EfficiencyInUse()[0], 0.2, 1e-3);
}

// CONTROLLER_ROTORS_N: every rotor's efficiency and hover bound (rotor 1
// carries the most: 0.423, rotors 2 and 3 0.2205, docs/controller.md), the
// weak rotor once hover is infeasible, paired with CONTROLLER_STATUS by seq.
TEST_F(MultiArmControllerServiceTest, ControllerRotorsNCarriesEveryRotorAndTheWeakOne) {
  Settle();
  Fly(5000000, 5200000);
  service_.PublishStatus(0, 5200000);
  ASSERT_EQ(sink_.rotors_messages.size(), 1u);
  ASSERT_EQ(sink_.statuses.size(), 1u);
  const controller_rotors_n_t& feasible = sink_.rotors_messages.back();
  EXPECT_EQ(feasible.seq, sink_.statuses.back().seq);
  EXPECT_EQ(feasible.utime, sink_.statuses.back().utime);
  EXPECT_EQ(feasible.vehicle_checksum, DescriptionChecksum(vehicle_));
  ASSERT_EQ(feasible.n_rotors, 3);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(feasible.efficiency[static_cast<size_t>(i)], 0.8, 1e-6) << i;
  EXPECT_NEAR(feasible.feasibility_bound[0], 0.423, 0.001);
  EXPECT_NEAR(feasible.feasibility_bound[1], 0.2205, 0.001);
  EXPECT_NEAR(feasible.feasibility_bound[2], 0.2205, 0.001);
  EXPECT_EQ(feasible.weak_rotor, 0);
  EXPECT_TRUE(std::isnan(feasible.weak_efficiency));

  rotor1_scale_ = 0.2;
  Fly(5201000, 5400000);
  service_.PublishStatus(0, 5400000);
  ASSERT_EQ(sink_.rotors_messages.size(), 2u);
  const controller_rotors_n_t& infeasible = sink_.rotors_messages.back();
  EXPECT_EQ(infeasible.seq, sink_.statuses.back().seq);
  EXPECT_EQ(infeasible.weak_rotor, 1);
  EXPECT_NEAR(infeasible.weak_efficiency, 0.2, 1e-6);
  EXPECT_NEAR(infeasible.efficiency[0], 0.2, 1e-6);
  EXPECT_NEAR(infeasible.efficiency[2], 0.8, 1e-6);
}

// The POSE innovation gate (PoseGate, the birotor's): a POSE 1 m from the
// observer (gate 0.3 m) is refused; a consistent run of
// pose_reacquire_count (5) at 0.5 m moves the observer there on the fifth.
TEST_F(MultiArmControllerServiceTest, PoseOutsideTheGateIsRefusedUntilAConsistentRunReacquires) {
  Fly(5000000, 5200000);
  SendPoseAndImu(5210000, ++pose_seq_, 1.0);
  RunUntil(5210000);
  EXPECT_EQ(service_.health().pose.rejected_gate, 1);
  EXPECT_NEAR(service_.controller().body_state().position_m.x(), 0.0, 0.01);
  for (int k = 1; k <= 5; ++k) SendPoseAndImu(5210000 + 10000 * k, ++pose_seq_, 0.5);
  EXPECT_EQ(service_.health().pose.rejected_gate, 1 + 4);
  EXPECT_EQ(service_.health().pose_reacquisitions, 1);
  EXPECT_DOUBLE_EQ(service_.controller().body_state().position_m.x(), 0.5);
}

TEST_F(MultiArmControllerServiceTest, AFutureStampedForceNIsRefused) {
  SendPoseAndImu(5000000, 1);
  // 1 s ahead of the clock; clock_future_window_s is 0.01 s.
  Send(channels_.force_n, ForceN(3, 5000000, 1, force_estimate_n_t::STATUS_VALID), 5000000);
  EXPECT_EQ(service_.health().force.rejected_future, 1);
  EXPECT_EQ(service_.health().force.accepted, 0);
}

// The sealed twins in front of the node: a plain FORCE_N (a forgery) is
// refused, a sealed one of the site key reaches the node; GUARD_STATUS
// counts FORCE_N in CHANNEL_FORCE's slot.
TEST_F(MultiArmControllerServiceTest, PlainForceNIsRefusedAndCountedInGuardStatusForceSlot) {
  const MessageAuthenticator key{CountingKeyFrom(3)};
  AuthenticatingHandler authenticated(&service_, SealedMessages::kVerify, &key, channels_,
                                      {AuthenticatedChannel::kPose, AuthenticatedChannel::kForceN}, ChannelSet{});
  CommandSink bus{"none"};
  ChannelSet sealed{};
  sealed[static_cast<int>(AuthenticatedChannel::kPose)] = sealed[static_cast<int>(AuthenticatedChannel::kForceN)] =
      true;
  // A sealing publisher whose messages go to the handler (sealed first, then the plain copy).
  class Loopback : public MessageSink {
   public:
    explicit Loopback(PacketHandler* handler) : handler_(handler) {}
    void Publish(const std::string& channel, int64_t, const void* data, size_t size) override {
      handler_->HandlePacket(channel, data, size, -1);
    }

   private:
    PacketHandler* handler_;
  } loopback(&authenticated);
  SigningSink signing(&loopback, &key, channels_, sealed, 9);
  const std::vector<uint8_t> forged = ForceN(3, 4000000, 1, force_estimate_n_t::STATUS_VALID);
  authenticated.HandlePacket(channels_.force_n, forged.data(), forged.size(), -1);
  const std::vector<uint8_t> honest = ForceN(3, 4000000, 2, force_estimate_n_t::STATUS_VALID);
  signing.Publish(channels_.force_n, 4000000, honest.data(), honest.size());
  const AuthenticationCounters& c = authenticated.counters(AuthenticatedChannel::kForceN);
  EXPECT_EQ(c.unauthenticated, 1);
  EXPECT_EQ(c.authenticated, 1);
  EXPECT_EQ(c.plain_copies, 1);
  guard_status_t guard{};
  BuildGuardStatus(guard_status_t::PROGRAM_CONTROLLER, 0, 0, &signing, &authenticated, nullptr, &guard);
  EXPECT_EQ(guard.refused[guard_status_t::CHANNEL_FORCE], 1);
  EXPECT_EQ(guard.accepted[guard_status_t::CHANNEL_FORCE], 1);
  EXPECT_EQ(guard.accepted[guard_status_t::CHANNEL_MOTOR_COMMAND], 0);
}

}  // namespace
}  // namespace birotor
