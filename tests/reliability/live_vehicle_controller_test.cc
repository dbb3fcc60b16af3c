// The N-rotor closed loop live on a private udpm URL (ttl=0) with the site
// key: birotor-sim --vehicle (the trirotor, its ESCs on MOTOR_COMMAND_N_AUTH,
// the scenario's trajectory on SETPOINT_AUTH), birotor-estimator --vehicle
// (FORCE_N_AUTH) and birotor-controller --vehicle. The vehicle hovers, then
// follows a 0.4 m altitude step; every MOTOR_COMMAND_N is within bounds; a
// forger on the bus (plain FORCE_N, a sealed FORCE_N of another rotor count,
// MOTOR_COMMAND_N sealed under another key) is refused and counted. Errors
// are taken from TRUTH_N on the vehicle clock, which CPU load on the shared
// machine does not stretch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "birotor/controller_status_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "model/vehicle_description.h"
#include "params/vehicle_description_yaml.h"
#include "security/message_authenticator.h"
#include "security/site_key.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "tests/reliability/live_harness.h"
#include "tests/reliability/machine_stall_watch.h"

namespace birotor::reliability {
namespace {

constexpr double kStepAtS = 2.0;    // the setpoint step's time on the scenario clock [s]
constexpr double kStepZM = 0.4;     // its altitude [m] (within setpoint.max_jump_m, 0.5 m)
constexpr double kMoveS = 1.0;      // its move time (a 1 ms move is refused: feed-forward inconsistent) [s]
constexpr double kDurationS = 7.0;  // the flight [s]
constexpr int kForgeries = 100;     // of each kind, at 100 Hz from 3 s on
constexpr int kRotors = 3;

// TRUTH_N's altitude errors in two windows, MOTOR_COMMAND_N's bounds and the
// controller's GUARD_STATUS, on its own thread.
class VehicleLoopListener {
 public:
  VehicleLoopListener(const std::string& url, const std::string& prefix, double omega_max_rad_s)
      : omega_max_rad_s_(omega_max_rad_s), listener_(url, prefix) {
    listener_.Subscribe(listener_.channels().truth_n, &VehicleLoopListener::OnTruth, this);
    listener_.Subscribe(listener_.channels().motor_command_n, &VehicleLoopListener::OnCommand, this);
    listener_.Subscribe(listener_.channels().guard_status, &VehicleLoopListener::OnGuard, this);
    listener_.Subscribe(listener_.channels().controller_status, &VehicleLoopListener::OnStatus, this);
    listener_.Start();
  }
  bool good() { return listener_.good(); }

  struct Figures {
    int64_t truths = 0, commands = 0, commands_out_of_bounds = 0;
    double hover_max_error_m = 0;    // max |z| over [1, kStepAtS) s
    double settled_max_error_m = 0;  // max |z - kStepZM| over [kStepAtS + kMoveS + 2, kDurationS) s
    double max_abs_x_m = 0;          // over the whole flight after 1 s
    guard_status_t controller_guard{};
    // The fallback (nominal map): entries in the newest CONTROLLER_STATUS
    // (-1 before one), commands flagged STATUS_FALLBACK_ACTIVE, flag changes.
    int64_t fallbacks = -1, fallback_commands = 0, fallback_toggles = 0;
    int64_t conflicts = -1;  // entries into STATUS_INPUT_CONFLICT (CONTROLLER_STATUS)
    // Commands flagged STATUS_FALLBACK_ACTIVE over the judged span [1, kDurationS - 0.05) s
    // (the flight's end, when FORCE_N stops, falls back too).
    int64_t fallback_commands_judged = 0;
    std::string fallback_entries_s;  // vehicle time of each entry [s], the first 8
  };
  Figures figures() {
    std::lock_guard<std::mutex> lock(mutex_);
    return figures_;
  }

 private:
  void OnTruth(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    if (DecodeMessage(buffer->data, buffer->data_size, &truth_) != DecodeError::kNone) return;
    const double t_s = 1e-6 * static_cast<double>(truth_.utime);
    std::lock_guard<std::mutex> lock(mutex_);
    ++figures_.truths;
    if (t_s >= 1.0) figures_.max_abs_x_m = std::max(figures_.max_abs_x_m, std::fabs(truth_.x_m));
    if (t_s >= 1.0 && t_s < kStepAtS)
      figures_.hover_max_error_m = std::max(figures_.hover_max_error_m, std::fabs(truth_.z_m));
    if (t_s >= kStepAtS + kMoveS + 2.0)
      figures_.settled_max_error_m = std::max(figures_.settled_max_error_m, std::fabs(truth_.z_m - kStepZM));
  }
  void OnCommand(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    if (DecodeMessage(buffer->data, buffer->data_size, &command_) != DecodeError::kNone) return;
    bool within = command_.n_rotors == kRotors;
    for (double omega : command_.omega_cmd_rad_s) within = within && omega >= 0.0 && omega <= omega_max_rad_s_;
    const bool fallback = (command_.status & motor_command_n_t::STATUS_FALLBACK_ACTIVE) != 0;
    std::lock_guard<std::mutex> lock(mutex_);
    if (figures_.commands > 0 && fallback != last_fallback_) ++figures_.fallback_toggles;
    if (figures_.commands > 0 && fallback && !last_fallback_ && figures_.fallback_toggles <= 16)
      figures_.fallback_entries_s += " " + std::to_string(1e-6 * static_cast<double>(command_.utime)).substr(0, 5);
    last_fallback_ = fallback;
    ++figures_.commands;
    if (fallback) ++figures_.fallback_commands;
    const double t_s = 1e-6 * static_cast<double>(command_.utime);
    if (fallback && t_s >= 1.0 && t_s < kDurationS - 0.05) ++figures_.fallback_commands_judged;
    if (!within) ++figures_.commands_out_of_bounds;
  }
  void OnStatus(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    controller_status_t status{};
    if (DecodeMessage(buffer->data, buffer->data_size, &status) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    figures_.fallbacks = status.fallbacks;
    figures_.conflicts = status.conflicts;
  }
  void OnGuard(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    guard_status_t guard{};
    if (DecodeMessage(buffer->data, buffer->data_size, &guard) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (guard.program == guard_status_t::PROGRAM_CONTROLLER) figures_.controller_guard = guard;
  }

  double omega_max_rad_s_;
  truth_n_t truth_{};
  motor_command_n_t command_{};
  bool last_fallback_ = false;
  std::mutex mutex_;
  Figures figures_;
  ListenerThread listener_;  // last: stops first
};

// A FORCE_N of n rotors, stamped utime, VALID.
std::vector<uint8_t> ForceN(int n, int64_t utime, int32_t seq) {
  force_estimate_n_t m{};
  m.utime = utime;
  m.seq = seq;
  m.n_rotors = static_cast<int8_t>(n);
  m.force_n.assign(static_cast<size_t>(n), 5.0);
  m.force_std_n.assign(static_cast<size_t>(n), 0.1);
  m.thrust_scale.assign(static_cast<size_t>(n), 0.5);
  m.status = force_estimate_n_t::STATUS_VALID;
  std::vector<uint8_t> bytes;
  EncodeMessage(m, &bytes);
  return bytes;
}

// The forger: kForgeries of each kind at 100 Hz.
void Forge(const std::string& url, const ChannelNames& channels, double omega_max_rad_s) {
  lcm::LCM lcm(url);
  LcmSink plain(&lcm);
  SiteKey key(SiteKey::Bytes{});
  std::string error;
  ASSERT_TRUE(SiteKey::Load(TestSiteKey(), &key, &error)) << error;
  const MessageAuthenticator site_key(key);
  SiteKey::Bytes other_bytes{};
  other_bytes.fill(0x5a);
  const MessageAuthenticator other_key{SiteKey(other_bytes)};
  ChannelSet sealed{};
  sealed[static_cast<int>(AuthenticatedChannel::kForceN)] =
      sealed[static_cast<int>(AuthenticatedChannel::kMotorCommandN)] = true;
  SigningSink right_key(&plain, &site_key, channels, sealed, 4242);
  SigningSink wrong_key(&plain, &other_key, channels, sealed, 4343);
  for (int k = 0; k < kForgeries; ++k) {
    const int64_t utime = static_cast<int64_t>(3e6) + 10000 * k;
    // A plain FORCE_N: not sealed, refused by authentication.
    const std::vector<uint8_t> forged = ForceN(kRotors, utime, 90000 + k);
    plain.Publish(channels.force_n, utime, forged.data(), forged.size());
    // Sealed with the site key but of 2 rotors: authentic, refused for its count.
    const std::vector<uint8_t> other_count = ForceN(2, utime, 80000 + k);
    right_key.Publish(channels.force_n, utime, other_count.data(), other_count.size());
    // Full throttle sealed under another key: refused by the ESCs' authentication.
    motor_command_n_t command{};
    command.utime = utime;
    command.seq = 70000 + k;
    command.n_rotors = kRotors;
    command.omega_cmd_rad_s.assign(kRotors, omega_max_rad_s);
    std::vector<uint8_t> bytes;
    EncodeMessage(command, &bytes);
    wrong_key.Publish(channels.motor_command_n, utime, bytes.data(), bytes.size());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// The first integer after the first `key` in text (-1: not there).
long NumberAfter(const std::string& text, const std::string& key) {
  const size_t at = text.find(key);
  return at == std::string::npos ? -1 : std::strtol(text.c_str() + at + key.size(), nullptr, 10);
}

struct TrirotorFlight {
  VehicleLoopListener::Figures figures;
  long count_refused = -1;                // FORCE_N refused for the rotor count (the controller's stop line)
  long esc_refused = -1;                  // MOTOR_COMMAND_N refused by the ESCs' authentication (the simulator's)
  std::string controller_text, sim_text;  // their logs
  int controller_exit = -1, estimator_exit = -1;
};

// One flight of the step with the forger; a fatal failure ends it early.
void FlyTheTrirotorStep(const std::string& prefix, TrirotorFlight* flight) {
  const std::string url = PrivateUrl(7763);
  const std::string source = BIROTOR_SOURCE_DIR;
  const std::string vehicle_file = source + "/config/vehicles/trirotor.yaml";
  const VehicleDescription vehicle = LoadVehicleDescription(vehicle_file);
  const std::string estimator_log = TempPath("nctl_estimator.log"), controller_log = TempPath("nctl_controller.log"),
                    sim_log = TempPath("nctl_sim.log");
  for (const std::string& log : {estimator_log, controller_log, sim_log}) std::remove(log.c_str());
  VehicleLoopListener listener(url, prefix, vehicle.omega_max_rad_s);
  ASSERT_TRUE(listener.good());
  ChildProcess estimator, controller, sim;
  ASSERT_TRUE(
      estimator.Start({BIROTOR_ESTIMATOR_BIN, "--vehicle", vehicle_file, "--lcm-url", url, "--prefix", prefix,
                       "--params", source + "/config/estimator.yaml", "--realtime-priority", kEstimatorPriority},
                      estimator_log));
  ASSERT_TRUE(controller.Start({BIROTOR_CONTROLLER_BIN, "--vehicle", vehicle_file, "--lcm-url", url, "--prefix", prefix,
                                "--status-rate-hz", "10", "--realtime-priority", kControllerPriority},
                               controller_log));
  for (const std::string& log : {estimator_log, controller_log}) {
    ASSERT_TRUE(DaemonListener::WaitUntil([&] { return ReadTextFile(log).find(": in ") != std::string::npos; }, 20))
        << ReadTextFile(log);
  }
  const std::string step = "trajectory.waypoints=[{start_s: " + std::to_string(kStepAtS) +
                           ", duration_s: " + std::to_string(kMoveS) + ", x_m: 0.0, z_m: " + std::to_string(kStepZM) +
                           "}]";
  ASSERT_TRUE(sim.Start(
      {BIROTOR_SIM_BIN, "--vehicle", vehicle_file, "--scenario", source + "/config/scenarios/lateral_step.yaml",
       "--set", "scenario.duration_s=" + std::to_string(kDurationS), "--set", step, "--external-controller",
       "--publish-setpoints", "--lcm-url", url, "--prefix", prefix, "--realtime-priority", kSimPriority},
      sim_log));
  std::this_thread::sleep_for(std::chrono::seconds(3));  // the step is flown; the forger starts
  Forge(url, MakeChannelNames(prefix), vehicle.omega_max_rad_s);
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 60)) << "the simulator did not finish";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the last GUARD_STATUS
  flight->controller_exit = controller.Stop();
  flight->estimator_exit = estimator.Stop();
  flight->controller_text = ReadTextFile(controller_log);
  flight->sim_text = ReadTextFile(sim_log);
  flight->figures = listener.figures();
  // The stop line: "... FORCE_N received R accepted A, refused: N rotor count, ...".
  const std::string& controller_text = flight->controller_text;
  const size_t stop_line = controller_text.rfind("stopped: ");
  if (stop_line != std::string::npos)
    flight->count_refused = NumberAfter(controller_text.substr(stop_line), "refused: ");
  const size_t esc_line = flight->sim_text.rfind("MOTOR_COMMAND_N: ");
  long esc_accepted = -1;
  if (esc_line != std::string::npos)
    std::sscanf(flight->sim_text.c_str() + esc_line, "MOTOR_COMMAND_N: %ld accepted, %ld refused", &esc_accepted,
                &flight->esc_refused);
}

void PrintTrirotorFlight(const TrirotorFlight& flight, const MachineStallWatch& watch) {
  const VehicleLoopListener::Figures& f = flight.figures;
  const int kForce = guard_status_t::CHANNEL_FORCE;
  std::printf(
      "trirotor live: %lld TRUTH_N, %lld MOTOR_COMMAND_N (%lld out of bounds); hover max |z| %.4f m, after the "
      "%.1f m step max |z - z_ref| %.4f m (from %.1f s), max |x| %.4f m; %s\n"
      "forgeries (%d of each): controller refused FORCE_N unsealed %lld (GUARD_STATUS), for its rotor count %ld; "
      "ESCs refused MOTOR_COMMAND_N (sealed under another key and its plain copy) %ld\n"
      "fallback: %lld entries (CONTROLLER_STATUS), %lld commands flagged (%lld from 1 s to the end), %lld flag "
      "changes, entries at [s]%s; %lld conflicts\n",
      static_cast<long long>(f.truths), static_cast<long long>(f.commands),
      static_cast<long long>(f.commands_out_of_bounds), f.hover_max_error_m, kStepZM, f.settled_max_error_m,
      kStepAtS + kMoveS + 2.0, f.max_abs_x_m, watch.Summary().c_str(), kForgeries,
      static_cast<long long>(f.controller_guard.refused[kForce]), flight.count_refused, flight.esc_refused,
      static_cast<long long>(f.fallbacks), static_cast<long long>(f.fallback_commands),
      static_cast<long long>(f.fallback_commands_judged), static_cast<long long>(f.fallback_toggles),
      f.fallback_entries_s.c_str(), static_cast<long long>(f.conflicts));
}

// The flight's figures against its bounds: strict when the machine kept
// real time through it and the controller flew force feedback through the
// judged span, else not lost.
void JudgeTrirotorFlight(const TrirotorFlight& flight, bool strict) {
  const VehicleLoopListener::Figures& f = flight.figures;
  EXPECT_EQ(flight.controller_exit, 0);
  EXPECT_EQ(flight.estimator_exit, 0);
  ASSERT_GT(f.truths, 3500) << flight.sim_text;  // 7 s at 1 kHz, less what a loaded kernel dropped
  EXPECT_GT(f.commands, strict ? 2000 : 1000);   // 500 Hz from the first POSE, while the machine ran
  EXPECT_EQ(f.commands_out_of_bounds, 0);
  // Measured live on this 2-core VM with the machine keeping real time, 13
  // runs (under other builds, under stress-ng, in a fresh-clone CI): hover
  // 0.0025-0.0028 m, settled 0.0053-0.0079 m (the CI run), |x| 0.0038-0.0046
  // m; bounds 2x the largest (a lost or oscillating flight is centimetres
  // off). On a machine that stalled through every attempt: not lost
  // (through 100 ms stalls: hover 0.012 m, settled 0.048 m, |x| 0.008 m; a
  // quarter of the time stalled: hover 0.15 m, settled 0.11 m).
  EXPECT_LT(f.hover_max_error_m, strict ? 0.0056 : 0.3);
  EXPECT_LT(f.settled_max_error_m, strict ? 0.016 : 0.3);
  EXPECT_LT(f.max_abs_x_m, strict ? 0.0092 : 0.3);
  // Each forgery counted once where it is refused (a loaded kernel may drop a few).
  const int kForce = guard_status_t::CHANNEL_FORCE;
  EXPECT_GE(f.controller_guard.refused[kForce], kForgeries * 95 / 100);
  EXPECT_LE(f.controller_guard.refused[kForce], kForgeries);
  EXPECT_GE(flight.count_refused, kForgeries * 95 / 100) << flight.controller_text;
  EXPECT_LE(flight.count_refused, kForgeries);
  EXPECT_GE(flight.esc_refused, 2 * kForgeries * 95 / 100) << flight.sim_text;
  EXPECT_LE(flight.esc_refused, 2 * kForgeries);
}

TEST(LiveVehicleControllerTest, TrirotorFliesAnAltitudeStepOnSealedChannelsAndRefusesForgeries) {
  FlyJudgedOnRealTime<TrirotorFlight>(
      [](int attempt, TrirotorFlight* flight) {
        FlyTheTrirotorStep(UniquePrefix("REL_NCTL" + std::to_string(attempt) + "_"), flight);
      },
      PrintTrirotorFlight, JudgeTrirotorFlight,
      // A FORCE_N later than force_timeout_s (5 ms) puts the controller on
      // the nominal map for at least force_recovery_s; the watch sees only
      // wakes 20 ms late, so a flight that fell back in its judged span did
      // not get its real time either (under stress-ng: at 5.25 and 6.25 s,
      // the settled error 0.0198 m against the strict 0.016 m).
      [](const TrirotorFlight& flight) { return flight.figures.fallback_commands_judged == 0; });
}

}  // namespace
}  // namespace birotor::reliability
