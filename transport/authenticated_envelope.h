// The authenticated channels on the wire (docs/interface.md, "Authenticated
// channels"): MOTOR_COMMAND, SETPOINT, POSE and FORCE, whose forgery moves the
// vehicle, and the N-arm twins MOTOR_COMMAND_N and FORCE_N each have a sealed
// twin <type>_auth_t on <NAME>_AUTH:
//
//   plain  message: fingerprint(plain) | body
//   sealed message: fingerprint(sealed) | publisher | counter | body | tag[32]
//
// (LCM's encoding: big-endian int64 publisher and counter; body is the plain
// type's fields, the nested message). tag = MessageAuthenticator::Sign(
// counter, every sealed byte before the tag). Sealing and opening convert
// between the two without decoding the body, so every reader keeps its one
// checked decoder of the plain type. No allocation once the output buffer
// has grown to the message size.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "security/message_authenticator.h"
#include "transport/channels.h"

namespace birotor {

// The channels with a sealed twin.
enum class AuthenticatedChannel : int {
  kMotorCommand = 0,
  kSetpoint = 1,
  kPose = 2,
  kForce = 3,
  kMotorCommandN = 4,  // MOTOR_COMMAND_N (motor_command_n_t)
  kForceN = 5,         // FORCE_N (force_estimate_n_t)
};
constexpr int kNumAuthenticatedChannels = 6;

// One channel's two names and types.
struct AuthenticatedChannelNames {
  const char* base = "";  // base name of the plain channel ("POSE")
  std::string plain;      // full name of the plain channel
  std::string sealed;     // full name of its sealed twin
  uint64_t plain_hash = 0;
  uint64_t sealed_hash = 0;
};
AuthenticatedChannelNames NamesOf(const ChannelNames& channels, AuthenticatedChannel channel);

// Bytes the sealed message adds to the plain one: publisher and counter in
// place of nothing, and the tag.
constexpr size_t kSealOverheadBytes = 16 + MessageAuthenticator::kTagBytes;

// Writes the sealed twin of plain (a whole encoded plain message of
// names.plain_hash) into *sealed. False (and *sealed empty) when plain is
// not such a message.
bool SealMessage(const MessageAuthenticator& authenticator, const AuthenticatedChannelNames& names, uint64_t publisher,
                 uint64_t counter, const uint8_t* plain, size_t size, std::vector<uint8_t>* sealed);

enum class OpenVerdict {
  kAuthentic,  // the tag is right (or not checked: authenticator null)
  kMalformed,  // not a sealed message of this type (fingerprint, size, counter 0)
  kBadTag,     // the tag is wrong: forged, altered, or another key
};
// Stable lower-case name for counters and log lines.
const char* OpenVerdictName(OpenVerdict verdict);

// Checks the tag of a sealed message with authenticator (null: not checked,
// for tools that read a log without the key) and writes the plain message
// into *plain, the publisher and the counter. *plain is empty unless
// kAuthentic.
OpenVerdict OpenMessage(const MessageAuthenticator* authenticator, const AuthenticatedChannelNames& names,
                        const uint8_t* sealed, size_t size, std::vector<uint8_t>* plain, uint64_t* publisher,
                        uint64_t* counter);

// The channels a site lets through unauthenticated, from a list of base
// names ("POSE,SETPOINT"), "none" or "all". False with *error naming the
// unknown name and the allowed ones.
using ChannelSet = std::array<bool, kNumAuthenticatedChannels>;
bool ParseChannelSet(const std::string& list, ChannelSet* set, std::string* error);

}  // namespace birotor
