// The replay rule of an authenticated channel: each publisher numbers its
// messages with a counter that only increases, and a receiver accepts a
// publisher's message only when its counter is above the newest it accepted
// from that publisher. The guard keeps the newest counter of the last
// kPublishers publishers heard (a new one takes the slot of the one heard
// from least recently). Only authenticated messages reach it, so a forger
// cannot fill it. No allocation.
#pragma once

#include <array>
#include <cstdint>

namespace birotor {

// A random 64-bit publisher identity (libsodium's randombytes), drawn once at
// a publisher's start-up: a restarted publisher is a new publisher, so its
// counter may start again at 1.
uint64_t RandomPublisherId();

class ReplayGuard {
 public:
  static constexpr int kPublishers = 8;

  // True (and counter recorded) when counter is above the newest accepted
  // from publisher, or publisher is new; false for a replay.
  bool Admit(uint64_t publisher, uint64_t counter);

 private:
  struct Slot {
    uint64_t publisher = 0;
    uint64_t newest_counter = 0;
    uint64_t last_heard = 0;  // admission tick; 0 = empty slot
  };
  std::array<Slot, kPublishers> slots_{};
  uint64_t tick_ = 0;
};

}  // namespace birotor
