#include "services/birotor_sim_vehicle.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "controller/reference_point.h"
#include "nodes/multi_arm_esc_command_node.h"
#include "numerics/time_units.h"
#include "program/program_options.h"
#include "program/shutdown.h"
#include "security/replay_guard.h"
#include "services/live_pacer.h"
#include "simulator/multi_arm_simulator.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sinks/wire_sample_sink.h"
#include "sources/authenticating_handler.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

// The live extras of a step: the ESCs' commands from the source (when
// flying on an external controller) and the trajectory on SETPOINT.
struct LiveStepInputs {
  MessageSource* source = nullptr;        // the commands' source; null: the autopilot flies
  MultiArmEscCommandNode* esc = nullptr;  // with source
  int64_t setpoint_every_steps = 0;       // 0: no SETPOINT
};

// Steps sim to the end (or a signal) into sink, the description on VEHICLE
// at every multiple of period_us of simulated time (the first at t = 0);
// paced when pacer is not null, stopped when the log (if any) failed.
// Returns the VEHICLE messages sent.
int32_t StepVehicle(MultiArmSimulator* sim, WireSampleSink* sink, int64_t period_us, LivePacer* pacer,
                    const LogSink* log, const LiveStepInputs& live) {
  const VehicleDescription& vehicle = sim->vehicle();
  int32_t vehicle_seq = 0, setpoint_seq = 0;
  const int64_t step_us = SecondsToUtime(sim->scenario().step_s);
  for (int64_t k = 0; !(log != nullptr && log->failed()) && !ShutdownRequested() && !sim->done(); ++k) {
    if ((k * step_us) % period_us == 0) sink->OnVehicle(vehicle, "birotor-sim", sim->utime(), vehicle_seq++);
    if (live.setpoint_every_steps > 0 && k % live.setpoint_every_steps == 0)
      sink->OnSetpoint(SetpointFromReference(sim->ReferenceAt(sim->time_s()), sim->utime(), setpoint_seq++));
    if (live.source != nullptr) {
      while (live.source->DeliverOne()) {
      }
      live.esc->Tick();
    }
    sim->Step(sink);
    if (pacer != nullptr) pacer->AfterStep(sim->time_s());
  }
  return vehicle_seq;
}

// The ESCs' counters at the end, one line.
void LogEscCounters(const MultiArmEscCommandNode& esc, const AuthenticatingHandler& authentication) {
  const EscCounters& n = esc.rule().counters();
  spdlog::info(
      "MOTOR_COMMAND_N received {}, decode errors {} ({} of another rotor count); ESCs accepted {}, refused {} "
      "foreign, {} held, {} out of range, {} future, {} stale; {} command timeouts",
      esc.received(), esc.decode_errors(), esc.count_refusals().Total(), n.accepted, n.foreign, n.held, n.out_of_range,
      n.future, n.stale, esc.rule().timeouts());
  spdlog::info("authentication: {}", authentication.Summary());
}

}  // namespace

bool RunVehicleScenario(const VehicleRunOptions& options, const VehicleDescription& vehicle, const Scenario& scenario,
                        const ChannelNames& channels, lcm::LCM* lcm, MessageSource* source,
                        const ChannelSecurity& security) {
  std::unique_ptr<MultiArmSimulator> sim;
  try {
    sim = std::make_unique<MultiArmSimulator>(vehicle, scenario);
  } catch (const std::invalid_argument& e) {
    ReportError(options.vehicle_file + ": " + e.what());
    return false;
  }
  if (options.wall_clock) sim->set_utime_offset_us(WallClockUs());
  const int64_t period_us = SecondsToUtime(options.vehicle_period_s);
  const bool live = options.output.empty();
  LogWriter writer;
  std::string error;
  if (!live && !writer.Open(options.output, &error)) {
    ReportError("cannot open the output log: " + error);
    return false;
  }
  LogSink log_sink(&writer);
  LcmSink lcm_sink(lcm);
  // Live: POSE and SETPOINT sealed unless the site lets them through unsigned.
  SigningSink signing_sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(),
                           RandomPublisherId());
  MessageSink* messages = live ? static_cast<MessageSink*>(&signing_sink) : &log_sink;
  WireSampleSink sink(channels, messages, options.publish_truth);
  std::unique_ptr<LivePacer> pacer;
  if (live) pacer = std::make_unique<LivePacer>(options.speed, scenario.step_s);
  LiveStepInputs inputs;
  std::unique_ptr<MultiArmEscCommandNode> esc;
  std::unique_ptr<AuthenticatingHandler> authenticated;
  if (live && options.external_controller && source != nullptr) {
    sim->UseExternalCommands();
    esc = std::make_unique<MultiArmEscCommandNode>(channels.motor_command_n, sim.get(), options.command_timeout_s);
    // MOTOR_COMMAND_N only authenticated (MOTOR_COMMAND_N_AUTH) unless the site lets it through unsigned.
    authenticated = std::make_unique<AuthenticatingHandler>(
        esc.get(), SealedMessages::kVerify, security.authenticator.get(), channels,
        std::vector<AuthenticatedChannel>{AuthenticatedChannel::kMotorCommandN}, security.unsigned_channels);
    if (!source->Subscribe(authenticated->WithSealedChannels(esc->InputChannels()), authenticated.get(), &error)) {
      ReportError(error);
      return false;
    }
    inputs.source = source;
    inputs.esc = esc.get();
  }
  if (live && options.publish_setpoints)
    inputs.setpoint_every_steps =
        std::max<int64_t>(1, std::llround(1.0 / (options.setpoint_rate_hz * scenario.step_s)));
  const int32_t vehicle_messages =
      StepVehicle(sim.get(), &sink, period_us, pacer.get(), live ? nullptr : &log_sink, inputs);
  if (esc) LogEscCounters(*esc, *authenticated);
  if (!live) {
    if (log_sink.failed() || sink.encode_failures() > 0 || !writer.Close()) {
      writer.Abandon();
      ReportError("writing " + options.output + " failed" + (writer.error().empty() ? "" : ": " + writer.error()) +
                  "; no log is left behind");
      return false;
    }
  } else if (lcm_sink.failures() > 0) {
    spdlog::warn("{} LCM publish calls failed", lcm_sink.failures());
  }
  if (ShutdownRequested()) spdlog::warn("stopped by a signal at t = {:.3f} s", sim->time_s());
  const ChannelCounts& n = sim->emitted();
  spdlog::info(
      "vehicle '{}' ({} arms) from {}, scenario '{}' ({}): simulated {:.3f} s; samples: strain {}, motor {}, imu {}, "
      "pose {}, loadcell {}, truth {}{}, vehicle {}; {} fault events; {}",
      vehicle.name, vehicle.arm_count, options.vehicle_file, scenario.name, scenario.mode, sim->time_s(), n.strain,
      n.motor, n.imu, n.pose, n.loadcell, n.truth, options.publish_truth ? "" : " (not published: --no-truth)",
      vehicle_messages, sim->fault_events().size(),
      live ? "published live" : "wrote " + std::to_string(writer.events_written()) + " events to " + options.output);
  return true;
}

}  // namespace birotor
