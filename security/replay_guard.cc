#include "security/replay_guard.h"

#include <sodium.h>

#include "security/site_key.h"

namespace birotor {

uint64_t RandomPublisherId() {
  InitSodium();
  uint64_t id = 0;
  while (id == 0) randombytes_buf(&id, sizeof(id));  // 0 marks an empty slot
  return id;
}

bool ReplayGuard::Admit(uint64_t publisher, uint64_t counter) {
  ++tick_;
  Slot* oldest = &slots_[0];
  for (Slot& slot : slots_) {
    if (slot.last_heard != 0 && slot.publisher == publisher) {
      if (counter <= slot.newest_counter) return false;
      slot.newest_counter = counter;
      slot.last_heard = tick_;
      return true;
    }
    if (slot.last_heard < oldest->last_heard) oldest = &slot;
  }
  *oldest = Slot{publisher, counter, tick_};
  return true;
}

}  // namespace birotor
