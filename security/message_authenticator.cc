#include "security/message_authenticator.h"

namespace birotor {

MessageAuthenticator::MessageAuthenticator(const SiteKey& key) {
  InitSodium();
  crypto_auth_hmacsha512256_init(&keyed_, key.bytes().data(), key.bytes().size());
}

MessageAuthenticator::~MessageAuthenticator() { sodium_memzero(&keyed_, sizeof(keyed_)); }

MessageAuthenticator::Tag MessageAuthenticator::Sign(uint64_t counter, const uint8_t* bytes, size_t size) const {
  uint8_t counter_le[8];
  for (int i = 0; i < 8; ++i) counter_le[i] = static_cast<uint8_t>(counter >> (8 * i));
  crypto_auth_hmacsha512256_state state = keyed_;
  crypto_auth_hmacsha512256_update(&state, counter_le, sizeof(counter_le));
  crypto_auth_hmacsha512256_update(&state, bytes, size);
  Tag tag;
  crypto_auth_hmacsha512256_final(&state, tag.data());
  sodium_memzero(&state, sizeof(state));
  return tag;
}

bool MessageAuthenticator::Verify(uint64_t counter, const uint8_t* bytes, size_t size, const Tag& tag) const {
  const Tag expected = Sign(counter, bytes, size);
  return crypto_verify_32(expected.data(), tag.data()) == 0;
}

}  // namespace birotor
