// The decode fuzzer's table of message types and its selector rule, shared by
// fuzz/decode_fuzzer.cc and the test that pins the seed corpus to it
// (tests/fuzz/decode_corpus_test.cc).
//
// Selector rule (the first byte of an input; the rest is the packet):
//   - 0x80 .. 0x80 + kNumLaterTargets - 1: kLaterTargets[byte - 0x80], the types
//     added after the first nine (the N-arm types, the controller's and the
//     guard's status, the setpoint and the sealed envelopes). Append-only: a new
//     type goes at the end and takes the next byte.
//   - any other byte: kBirotorTargets[byte % 9], the original nine birotor
//     types in their original order. The first seeds (fuzz/corpus/decode_fuzzer/:
//     strain .. health, 0x00 .. 0x08, and status_gauge_source_length_int_min,
//     0xFA = 250, 250 % 9 = 7) depend on that order.
// Every lcmtypes/*.lcm type is in exactly one of the two tables.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <vector>

#include "birotor/controller_rotors_n_t.hpp"
#include "birotor/controller_status_t.hpp"
#include "birotor/estimator_learned_n_t.hpp"
#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_auth_t.hpp"
#include "birotor/force_estimate_n_auth_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/input_health_t.hpp"
#include "birotor/loadcell_n_t.hpp"
#include "birotor/loadcell_t.hpp"
#include "birotor/motor_command_auth_t.hpp"
#include "birotor/motor_command_n_auth_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/motor_n_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_auth_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_auth_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "birotor/strain_n_t.hpp"
#include "birotor/strain_t.hpp"
#include "birotor/truth_n_t.hpp"
#include "birotor/truth_t.hpp"
#include "birotor/vehicle_description_t.hpp"
#include "transport/lcm_codec.h"

namespace birotor::fuzz {

// Decodes the packet as Msg; a packet that decodes must re-encode to a
// canonical form that decodes and re-encodes to the same bytes, else abort.
template <class Msg>
void DecodeAndCheck(const uint8_t* data, size_t size) {
  Msg msg;
  if (DecodeMessage(data, size, &msg) != DecodeError::kNone) return;
  // Re-encoding gives a packet that decodes and re-encodes to the same bytes.
  // (It may differ from the input: LCM encodes strings up to their first NUL
  // and ignores the terminator byte, so the check is on the canonical form.)
  std::vector<uint8_t> encoded, again;
  EncodeMessage(msg, &encoded);
  // A string with an embedded NUL decodes but cannot be encoded by LCM (it
  // writes strings up to the first NUL); EncodeMessage refuses it, so such a
  // message can never be re-published. Nothing more to check then.
  if (encoded.empty()) return;
  Msg copy;
  if (DecodeMessage(encoded.data(), encoded.size(), &copy) != DecodeError::kNone) std::abort();
  EncodeMessage(copy, &again);
  if (again != encoded) std::abort();
}

// The checked decoder's verdict alone (for the corpus test).
template <class Msg>
DecodeError DecodeOnly(const uint8_t* data, size_t size) {
  Msg msg;
  return DecodeMessage(data, size, &msg);
}

template <class Msg>
uint64_t FingerprintOf() {
  return static_cast<uint64_t>(Msg::getHash());
}

// One message type of the fuzzer.
struct DecodeTarget {
  const char* type_name;
  void (*check)(const uint8_t* data, size_t size);  // DecodeAndCheck<Msg>
  DecodeError (*decode)(const uint8_t* data, size_t size);
  uint64_t (*fingerprint)();
};

template <class Msg>
constexpr DecodeTarget Target(const char* type_name) {
  return {type_name, DecodeAndCheck<Msg>, DecodeOnly<Msg>, FingerprintOf<Msg>};
}

// Selector data[0] % 9 (the first seeds depend on this order).
inline constexpr DecodeTarget kBirotorTargets[] = {
    Target<strain_t>("strain_t"),
    Target<motor_t>("motor_t"),
    Target<imu_t>("imu_t"),
    Target<pose_t>("pose_t"),
    Target<loadcell_t>("loadcell_t"),
    Target<truth_t>("truth_t"),
    Target<force_estimate_t>("force_estimate_t"),
    Target<estimator_status_t>("estimator_status_t"),
    Target<input_health_t>("input_health_t"),
};

// Selector 0x80 + index; append-only.
constexpr uint8_t kFirstLaterSelector = 0x80;
inline constexpr DecodeTarget kLaterTargets[] = {
    Target<strain_n_t>("strain_n_t"),                            // 0x80
    Target<motor_n_t>("motor_n_t"),                              // 0x81
    Target<loadcell_n_t>("loadcell_n_t"),                        // 0x82
    Target<truth_n_t>("truth_n_t"),                              // 0x83
    Target<force_estimate_n_t>("force_estimate_n_t"),            // 0x84
    Target<motor_command_n_t>("motor_command_n_t"),              // 0x85
    Target<vehicle_description_t>("vehicle_description_t"),      // 0x86
    Target<estimator_learned_n_t>("estimator_learned_n_t"),      // 0x87
    Target<controller_rotors_n_t>("controller_rotors_n_t"),      // 0x88
    Target<force_estimate_n_auth_t>("force_estimate_n_auth_t"),  // 0x89
    Target<motor_command_n_auth_t>("motor_command_n_auth_t"),    // 0x8A
    Target<motor_command_t>("motor_command_t"),                  // 0x8B
    Target<setpoint_t>("setpoint_t"),                            // 0x8C
    Target<controller_status_t>("controller_status_t"),          // 0x8D
    Target<guard_status_t>("guard_status_t"),                    // 0x8E
    Target<motor_command_auth_t>("motor_command_auth_t"),        // 0x8F
    Target<setpoint_auth_t>("setpoint_auth_t"),                  // 0x90
    Target<pose_auth_t>("pose_auth_t"),                          // 0x91
    Target<force_estimate_auth_t>("force_estimate_auth_t"),      // 0x92
};
constexpr size_t kNumLaterTargets = std::size(kLaterTargets);
static_assert(kFirstLaterSelector + kNumLaterTargets <= 0xFA, "the later range would reach the 0xFA seed");

// The type a selector byte picks (the rule above).
inline const DecodeTarget& TargetOf(uint8_t selector) {
  if (selector >= kFirstLaterSelector && selector - kFirstLaterSelector < kNumLaterTargets) {
    return kLaterTargets[selector - kFirstLaterSelector];
  }
  return kBirotorTargets[selector % std::size(kBirotorTargets)];
}

}  // namespace birotor::fuzz
