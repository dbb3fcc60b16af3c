#include "transport/authenticated_envelope.h"

#include <cstring>
#include <sstream>

#include "birotor/force_estimate_auth_t.hpp"
#include "birotor/force_estimate_n_auth_t.hpp"
#include "birotor/motor_command_auth_t.hpp"
#include "birotor/motor_command_n_auth_t.hpp"
#include "birotor/pose_auth_t.hpp"
#include "birotor/setpoint_auth_t.hpp"

namespace birotor {
namespace {

constexpr size_t kFingerprintBytes = 8;
constexpr size_t kHeaderBytes = kFingerprintBytes + 16;  // fingerprint, publisher, counter
constexpr size_t kTagBytes = MessageAuthenticator::kTagBytes;

void WriteBigEndian(uint64_t value, uint8_t* out) {
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(value >> (56 - 8 * i));
}

uint64_t ReadBigEndian(const uint8_t* in) {
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | in[i];
  return value;
}

template <class Sealed, class Plain>
AuthenticatedChannelNames Names(const char* base, const std::string& plain, const std::string& sealed) {
  AuthenticatedChannelNames names;
  names.base = base;
  names.plain = plain;
  names.sealed = sealed;
  names.plain_hash = static_cast<uint64_t>(Plain::getHash());
  names.sealed_hash = static_cast<uint64_t>(Sealed::getHash());
  return names;
}

}  // namespace

AuthenticatedChannelNames NamesOf(const ChannelNames& c, AuthenticatedChannel channel) {
  switch (channel) {
    case AuthenticatedChannel::kMotorCommand:
      return Names<motor_command_auth_t, motor_command_t>(kMotorCommandChannel, c.motor_command, c.motor_command_auth);
    case AuthenticatedChannel::kSetpoint:
      return Names<setpoint_auth_t, setpoint_t>(kSetpointChannel, c.setpoint, c.setpoint_auth);
    case AuthenticatedChannel::kPose:
      return Names<pose_auth_t, pose_t>(kPoseChannel, c.pose, c.pose_auth);
    case AuthenticatedChannel::kForce:
      return Names<force_estimate_auth_t, force_estimate_t>(kForceChannel, c.force, c.force_auth);
    case AuthenticatedChannel::kMotorCommandN:
      return Names<motor_command_n_auth_t, motor_command_n_t>(kMotorCommandNChannel, c.motor_command_n,
                                                              c.motor_command_n_auth);
    case AuthenticatedChannel::kForceN:
      return Names<force_estimate_n_auth_t, force_estimate_n_t>(kForceNChannel, c.force_n, c.force_n_auth);
  }
  return {};
}

bool SealMessage(const MessageAuthenticator& authenticator, const AuthenticatedChannelNames& names, uint64_t publisher,
                 uint64_t counter, const uint8_t* plain, size_t size, std::vector<uint8_t>* sealed) {
  sealed->clear();
  if (plain == nullptr || size < kFingerprintBytes || ReadBigEndian(plain) != names.plain_hash) return false;
  const size_t body = size - kFingerprintBytes;
  sealed->resize(kHeaderBytes + body + kTagBytes);
  uint8_t* out = sealed->data();
  WriteBigEndian(names.sealed_hash, out);
  WriteBigEndian(publisher, out + 8);
  WriteBigEndian(counter, out + 16);
  std::memcpy(out + kHeaderBytes, plain + kFingerprintBytes, body);
  const MessageAuthenticator::Tag tag = authenticator.Sign(counter, out, kHeaderBytes + body);
  std::memcpy(out + kHeaderBytes + body, tag.data(), kTagBytes);
  return true;
}

const char* OpenVerdictName(OpenVerdict verdict) {
  switch (verdict) {
    case OpenVerdict::kAuthentic:
      return "authentic";
    case OpenVerdict::kMalformed:
      return "malformed";
    case OpenVerdict::kBadTag:
      return "bad_tag";
  }
  return "unknown";
}

OpenVerdict OpenMessage(const MessageAuthenticator* authenticator, const AuthenticatedChannelNames& names,
                        const uint8_t* sealed, size_t size, std::vector<uint8_t>* plain, uint64_t* publisher,
                        uint64_t* counter) {
  plain->clear();
  if (sealed == nullptr || size < kHeaderBytes + kTagBytes || ReadBigEndian(sealed) != names.sealed_hash) {
    return OpenVerdict::kMalformed;
  }
  *publisher = ReadBigEndian(sealed + 8);
  *counter = ReadBigEndian(sealed + 16);
  if (*counter == 0) return OpenVerdict::kMalformed;  // counters start at 1
  const size_t signed_bytes = size - kTagBytes;
  if (authenticator != nullptr) {
    MessageAuthenticator::Tag tag;
    std::memcpy(tag.data(), sealed + signed_bytes, kTagBytes);
    if (!authenticator->Verify(*counter, sealed, signed_bytes, tag)) return OpenVerdict::kBadTag;
  }
  const size_t body = signed_bytes - kHeaderBytes;
  plain->resize(kFingerprintBytes + body);
  WriteBigEndian(names.plain_hash, plain->data());
  std::memcpy(plain->data() + kFingerprintBytes, sealed + kHeaderBytes, body);
  return OpenVerdict::kAuthentic;
}

bool ParseChannelSet(const std::string& list, ChannelSet* set, std::string* error) {
  ChannelSet parsed{};
  const ChannelNames names = MakeChannelNames("");
  std::string allowed;
  for (int i = 0; i < kNumAuthenticatedChannels; ++i) {
    allowed += std::string(i ? ", " : "") + NamesOf(names, static_cast<AuthenticatedChannel>(i)).base;
  }
  std::stringstream items(list);
  std::string item;
  while (std::getline(items, item, ',')) {
    if (item == "none" || item.empty()) continue;
    if (item == "all") {
      parsed.fill(true);
      continue;
    }
    bool known = false;
    for (int i = 0; i < kNumAuthenticatedChannels; ++i) {
      if (item == NamesOf(names, static_cast<AuthenticatedChannel>(i)).base) parsed[i] = known = true;
    }
    if (!known) {
      *error = "unknown channel '" + item + "' (allowed: " + allowed + ", all, none)";
      return false;
    }
  }
  *set = parsed;
  return true;
}

}  // namespace birotor
