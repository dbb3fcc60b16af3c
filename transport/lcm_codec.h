// Checked decoding and allocation-free encoding of LCM messages. Every packet
// that arrives from the network or a log goes through DecodeMessage, which
// reports why a packet is rejected instead of crashing or throwing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "birotor/controller_rotors_n_t.hpp"
#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_n_auth_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/input_health_t.hpp"
#include "birotor/loadcell_n_t.hpp"
#include "birotor/motor_command_n_auth_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/motor_n_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "birotor/vehicle_description_t.hpp"

namespace birotor {

enum class DecodeError {
  kNone,            // decoded; the packet is exactly one message
  kTruncated,       // fewer bytes than the message (or its length fields) need
  kBadFingerprint,  // the 8-byte type hash is not the expected type's
  kMalformed,       // impossible length field, or trailing bytes after the message
};

// Stable lower-case name for counters and log lines ("truncated", ...).
const char* DecodeErrorName(DecodeError error);

namespace internal {

// Fingerprint as it appears on the wire: the first 8 bytes, big-endian.
uint64_t ReadFingerprint(const void* data);

// Walks the length fields (strings, variable-length arrays) of a packet before
// the generated decoder trusts them: a corrupt length would otherwise make it
// resize a vector by ~2^31 elements or copy 2 GB past the buffer. Types with
// only fixed-size fields need no check; a new type with a string or a
// variable-length array (its own or in a nested type) needs a specialisation
// here. The codec tests of every type catch a walker that disagrees with the
// .lcm file (round trips) and a missing one (a corrupt length that gets past
// the check makes the generated decoder throw).
template <class Msg>
DecodeError CheckLengthFields(const uint8_t* /*data*/, size_t /*size*/) {
  return DecodeError::kNone;
}
template <>
DecodeError CheckLengthFields<input_health_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<estimator_status_t>(const uint8_t* data, size_t size);
// The counted types (an int8_t count, then arrays of it): a negative count is
// malformed, arrays longer than the packet are truncated.
template <>
DecodeError CheckLengthFields<strain_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<motor_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<loadcell_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<truth_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<force_estimate_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<motor_command_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<vehicle_description_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<estimator_learned_n_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<controller_rotors_n_t>(const uint8_t* data, size_t size);
// The sealed twins of the counted types: the count of the nested message.
template <>
DecodeError CheckLengthFields<motor_command_n_auth_t>(const uint8_t* data, size_t size);
template <>
DecodeError CheckLengthFields<force_estimate_n_auth_t>(const uint8_t* data, size_t size);

}  // namespace internal

// Decodes one packet of type Msg. Rejects a packet that is shorter than the
// fingerprint, carries another type's fingerprint, ends early, has a corrupt
// length field or carries bytes after the message. Never throws. On error
// *out may be partly overwritten.
template <class Msg>
DecodeError DecodeMessage(const void* data, size_t size, Msg* out) {
  constexpr size_t kFingerprintBytes = 8;
  if (data == nullptr || size < kFingerprintBytes) return DecodeError::kTruncated;
  if (size > static_cast<size_t>(std::numeric_limits<int>::max())) {
    return DecodeError::kMalformed;  // the generated decoder takes an int length
  }
  if (internal::ReadFingerprint(data) != static_cast<uint64_t>(Msg::getHash())) {
    return DecodeError::kBadFingerprint;
  }
  const DecodeError length_check = internal::CheckLengthFields<Msg>(static_cast<const uint8_t*>(data), size);
  if (length_check != DecodeError::kNone) return length_check;
  try {
    const int consumed = out->decode(data, 0, static_cast<int>(size));
    // The generated primitives fail only when they run out of bytes.
    if (consumed < 0) return DecodeError::kTruncated;
    if (static_cast<size_t>(consumed) != size) return DecodeError::kMalformed;
  } catch (...) {  // std::length_error / std::bad_alloc from a string or vector
    return DecodeError::kMalformed;
  }
  return DecodeError::kNone;
}

// Encodes msg into *buffer, which ends up exactly the encoded size. The buffer
// keeps its capacity, so reusing it allocates only when a message grows.
// Leaves the buffer empty if the message cannot be encoded.
template <class Msg>
void EncodeMessage(const Msg& msg, std::vector<uint8_t>* buffer) {
  const int size = msg.getEncodedSize();
  if (size <= 0) {
    buffer->clear();
    return;
  }
  buffer->resize(static_cast<size_t>(size));
  if (msg.encode(buffer->data(), 0, size) != size) buffer->clear();
}

}  // namespace birotor
