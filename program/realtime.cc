#include "program/realtime.h"

#include <sched.h>
#include <spdlog/spdlog.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

namespace birotor {

void AddRealtimeOption(CLI::App& app, int* priority) {
  app.add_option("--realtime-priority", *priority,
                 "SCHED_FIFO priority (1-99) and locked memory for the process and its threads; 0 keeps the normal "
                 "scheduler. Refused by the system (no CAP_SYS_NICE / LimitRTPRIO): one warning, normal scheduler")
      ->check(CLI::Range(0, 99));
}

RealtimeOutcome ApplyRealtimePriority(int priority) {
  RealtimeOutcome out;
  out.requested_priority = priority;
  if (priority <= 0) return out;
  sched_param param{};
  param.sched_priority = priority;
  if (sched_setscheduler(0, SCHED_FIFO, &param) == 0) {
    out.fifo = true;
  } else {
    out.warning = "cannot set SCHED_FIFO priority " + std::to_string(priority) + " (" + std::strerror(errno) +
                  "; needs CAP_SYS_NICE or LimitRTPRIO): normal scheduler";
  }
  if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
    out.memory_locked = true;
  } else {
    const std::string why = std::string("cannot lock memory (") + std::strerror(errno) + "; needs LimitMEMLOCK)";
    out.warning = out.warning.empty() ? why : out.warning + "; " + why;
  }
  return out;
}

void LogRealtimeOutcome(const RealtimeOutcome& outcome) {
  if (!outcome.warning.empty()) {
    spdlog::warn("{}", outcome.warning);
  } else if (outcome.fifo) {
    spdlog::info("SCHED_FIFO priority {}, memory locked", outcome.requested_priority);
  }
}

}  // namespace birotor
