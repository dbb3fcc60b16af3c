// The daemons' one receive loop: wait for input until the next periodic
// deadline (at most max_wait_s, so a shutdown request is seen), deliver every
// ready packet without running past the deadline (a flood waits in the socket
// and the periodic work, status messages and timer-driven commands, stays on
// time), then call the node's periodic work, which does what is due and
// returns its next deadline. Dropped datagrams are said in the log
// (DroppedDatagramLog, at most once a second).
#pragma once

#include <cstdint>
#include <functional>

#include "sources/message_source.h"

namespace birotor {

struct ReceiveLoopOptions {
  // Longest single wait [s]: how late a shutdown request may be noticed
  // when nothing arrives.
  double max_wait_s = 0.1;
};

// Periodic work at steady time now_us [us]: called after every wake-up (a
// timeout or a batch of packets), it checks itself what is due and returns
// the steady time [us] by which it wants to be called again.
using PeriodicWork = std::function<int64_t(int64_t now_us)>;

// Runs until ShutdownRequested() (program/shutdown.h) or the source is
// finished; returns false when the source stopped with an error
// (source->error()), true otherwise. work runs once before the first wait.
bool RunReceiveLoop(MessageSource* source, const PeriodicWork& work,
                    const ReceiveLoopOptions& options = ReceiveLoopOptions());

// One turn for programs with a control flow of their own (the monitor, the
// probes, the simulator): waits up to wait_s [s] for a packet, then delivers
// ready packets (at least one) until none is left or the steady clock
// reaches until_us [us]. Returns the number of packets taken.
int64_t ReceiveUntil(MessageSource* source, double wait_s, int64_t until_us);

}  // namespace birotor
