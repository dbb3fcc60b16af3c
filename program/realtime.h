// Real-time scheduling for the flight processes: SCHED_FIFO at a priority
// above every normal process (a busy computer's CPU hogs cannot delay a
// strain sample or a motor command), and memory locked so that no page fault
// stalls the loop. One option, one call before LCM starts its threads (they
// inherit the policy), and one warning where the system does not permit it
// (no CAP_SYS_NICE, no LimitRTPRIO / LimitMEMLOCK): the program then runs on
// the normal scheduler, as it would without the option.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace birotor {

// What the process asked for and what it got.
struct RealtimeOutcome {
  int requested_priority = 0;  // 0: nothing was asked
  bool fifo = false;           // SCHED_FIFO at requested_priority is in force
  bool memory_locked = false;  // mlockall(MCL_CURRENT | MCL_FUTURE) succeeded
  std::string warning;         // one sentence when something asked for was refused; empty otherwise
};

// Adds --realtime-priority N (0-99; 0 keeps the normal scheduler) with the
// given default (the services' documented defaults: docs/realtime.md).
void AddRealtimeOption(CLI::App& app, int* priority);

// Sets SCHED_FIFO at priority for the calling process and locks its memory.
// Never fails the program: what was refused is in the outcome's warning.
RealtimeOutcome ApplyRealtimePriority(int priority);

// Logs the outcome once (spdlog: info when in force, one warning when
// refused). Call it after InstallShutdownHandlers: a log line before that on
// a closed standard stream would end the process with SIGPIPE.
void LogRealtimeOutcome(const RealtimeOutcome& outcome);

}  // namespace birotor
