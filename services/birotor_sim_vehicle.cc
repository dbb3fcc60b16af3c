#include "services/birotor_sim_vehicle.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <stdexcept>

#include "numerics/time_units.h"
#include "program/program_options.h"
#include "program/shutdown.h"
#include "services/live_pacer.h"
#include "simulator/multi_arm_simulator.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "transport/host_clock.h"
#include "transport/log_io.h"

namespace birotor {
namespace {

// Steps sim to the end (or a signal) into sink, the description on VEHICLE
// at every multiple of period_us of simulated time (the first at t = 0);
// paced when pacer is not null, stopped when the log (if any) failed.
// Returns the VEHICLE messages sent.
int32_t StepVehicle(MultiArmSimulator* sim, WireSampleSink* sink, int64_t period_us, LivePacer* pacer,
                    const LogSink* log) {
  const VehicleDescription& vehicle = sim->vehicle();
  int32_t vehicle_seq = 0;
  const int64_t step_us = SecondsToUtime(sim->scenario().step_s);
  for (int64_t k = 0; !(log != nullptr && log->failed()) && !ShutdownRequested() && !sim->done(); ++k) {
    if ((k * step_us) % period_us == 0) sink->OnVehicle(vehicle, "birotor-sim", sim->utime(), vehicle_seq++);
    sim->Step(sink);
    if (pacer != nullptr) pacer->AfterStep(sim->time_s());
  }
  return vehicle_seq;
}

}  // namespace

bool RunVehicleScenario(const VehicleRunOptions& options, const VehicleDescription& vehicle, const Scenario& scenario,
                        const ChannelNames& channels, lcm::LCM* lcm) {
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
  MessageSink* messages = live ? static_cast<MessageSink*>(&lcm_sink) : &log_sink;
  WireSampleSink sink(channels, messages, options.publish_truth);
  std::unique_ptr<LivePacer> pacer;
  if (live) pacer = std::make_unique<LivePacer>(options.speed, scenario.step_s);
  const int32_t vehicle_messages = StepVehicle(sim.get(), &sink, period_us, pacer.get(), live ? nullptr : &log_sink);
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
