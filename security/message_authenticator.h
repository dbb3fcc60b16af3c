// Message authentication under the site key (issue 37): libsodium's
// crypto_auth, HMAC-SHA-512-256, over the publisher's counter and the
// message bytes. Each publisher numbers its messages with its own counter;
// the counter is authenticated with them, so a receiver that keeps the last
// counter of each publisher can refuse a replayed message (the channels'
// job, next). The gauge state file uses counter 0 (nodes/gauge_state_file.h).
#pragma once

#include <sodium.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "security/site_key.h"

namespace birotor {

class MessageAuthenticator {
 public:
  static constexpr size_t kTagBytes = crypto_auth_hmacsha512256_BYTES;  // 32
  using Tag = std::array<uint8_t, kTagBytes>;

  // Keys the HMAC once: the key's two SHA-512 blocks are hashed here, not
  // per message. Calls InitSodium().
  explicit MessageAuthenticator(const SiteKey& key);
  ~MessageAuthenticator();  // wipes the keyed state

  // tag = HMAC-SHA-512-256(site key, counter as 8 bytes little-endian || bytes[0, size)),
  // the value crypto_auth() gives for that concatenation. No allocation.
  Tag Sign(uint64_t counter, const uint8_t* bytes, size_t size) const;

  // True when tag is Sign(counter, bytes, size). The compare is constant-time:
  // crypto_verify_32, the compare crypto_auth_verify() itself uses; the
  // streamed HMAC spares concatenating counter and message into a buffer.
  bool Verify(uint64_t counter, const uint8_t* bytes, size_t size, const Tag& tag) const;

 private:
  crypto_auth_hmacsha512256_state keyed_;
};

}  // namespace birotor
