// MessageAuthenticator (security/message_authenticator.h): the tag is
// HMAC-SHA-512-256 over counter || message, the value of libsodium's
// one-shot crypto_auth and of Python's hmac module; a changed byte, counter or
// key is refused.
#include "security/message_authenticator.h"

#include <gtest/gtest.h>
#include <sodium.h>

#include <string>
#include <vector>

namespace birotor {
namespace {

SiteKey CountingKey() {
  SiteKey::Bytes bytes;
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(i);  // 00 01 .. 1f
  return SiteKey(bytes);
}

std::vector<uint8_t> Bytes(const std::string& text) { return std::vector<uint8_t>(text.begin(), text.end()); }

std::string Hex(const MessageAuthenticator::Tag& tag) {
  char text[2 * MessageAuthenticator::kTagBytes + 1];
  sodium_bin2hex(text, sizeof(text), tag.data(), tag.size());
  return text;
}

TEST(MessageAuthenticatorTest, TagIsHmacSha512TruncatedOverCounterAndMessage) {
  const MessageAuthenticator authenticator(CountingKey());
  const std::vector<uint8_t> message = Bytes("motor command");
  // python3: hmac.new(bytes(range(32)), struct.pack('<Q', 7) + b'motor command',
  //                   hashlib.sha512).hexdigest()[:64]
  EXPECT_EQ(Hex(authenticator.Sign(7, message.data(), message.size())),
            "eccfb1037a551319fc2e349bc54be90155bf196d36799a416c488b70b371953d");
}

TEST(MessageAuthenticatorTest, TagIsWhatCryptoAuthGivesAndCryptoAuthVerifyAccepts) {
  const SiteKey key = CountingKey();
  const MessageAuthenticator authenticator(key);
  const std::vector<uint8_t> message =
      Bytes("a longer message of more than one SHA-512 block: " + std::string(200, 'x'));
  const uint64_t counter = 0x0102030405060708ULL;
  std::vector<uint8_t> joined = {8, 7, 6, 5, 4, 3, 2, 1};  // counter, little-endian
  joined.insert(joined.end(), message.begin(), message.end());
  MessageAuthenticator::Tag one_shot;
  crypto_auth(one_shot.data(), joined.data(), joined.size(), key.bytes().data());
  const MessageAuthenticator::Tag tag = authenticator.Sign(counter, message.data(), message.size());
  EXPECT_EQ(tag, one_shot);
  EXPECT_EQ(crypto_auth_verify(tag.data(), joined.data(), joined.size(), key.bytes().data()), 0);
  EXPECT_TRUE(authenticator.Verify(counter, message.data(), message.size(), tag));
}

TEST(MessageAuthenticatorTest, RefusesAChangedByteCounterTagOrKey) {
  const MessageAuthenticator authenticator(CountingKey());
  std::vector<uint8_t> message = Bytes("omega 812.5 830.1 rad/s");
  MessageAuthenticator::Tag tag = authenticator.Sign(41, message.data(), message.size());
  EXPECT_FALSE(authenticator.Verify(42, message.data(), message.size(), tag));  // a replayed tag, next counter
  message[6] ^= 0x01;
  EXPECT_FALSE(authenticator.Verify(41, message.data(), message.size(), tag));
  message[6] ^= 0x01;
  tag[31] ^= 0x80;
  EXPECT_FALSE(authenticator.Verify(41, message.data(), message.size(), tag));
  tag[31] ^= 0x80;
  SiteKey::Bytes other = CountingKey().bytes();
  other[0] ^= 0x01;
  EXPECT_FALSE(MessageAuthenticator(SiteKey(other)).Verify(41, message.data(), message.size(), tag));
  EXPECT_TRUE(authenticator.Verify(41, message.data(), message.size(), tag));
}

}  // namespace
}  // namespace birotor
