// libFuzzer harness for every message decoder: the first byte picks the type,
// the rest is the packet. A packet that decodes must re-encode to the same
// bytes; nothing may crash, leak or trip a sanitizer.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <vector>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/input_health_t.hpp"
#include "birotor/loadcell_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_t.hpp"
#include "birotor/truth_t.hpp"
#include "transport/lcm_codec.h"

namespace {

template <class Msg>
void DecodeAndCheck(const uint8_t* data, size_t size) {
  Msg msg;
  if (birotor::DecodeMessage(data, size, &msg) != birotor::DecodeError::kNone) return;
  // Re-encoding gives a packet that decodes and re-encodes to the same bytes.
  // (It may differ from the input: LCM encodes strings up to their first NUL
  // and ignores the terminator byte, so the check is on the canonical form.)
  std::vector<uint8_t> encoded, again;
  birotor::EncodeMessage(msg, &encoded);
  // A string with an embedded NUL decodes but cannot be encoded by LCM (it
  // writes strings up to the first NUL); EncodeMessage refuses it, so such a
  // message can never be re-published. Nothing more to check then.
  if (encoded.empty()) return;
  Msg copy;
  if (birotor::DecodeMessage(encoded.data(), encoded.size(), &copy) != birotor::DecodeError::kNone) std::abort();
  birotor::EncodeMessage(copy, &again);
  if (again != encoded) std::abort();
}

// One decoder per selector value (data[0] % 9: the seed corpus depends on
// this order).
using DecodeCheck = void (*)(const uint8_t*, size_t);
constexpr DecodeCheck kDecodeChecks[] = {
    DecodeAndCheck<birotor::strain_t>,
    DecodeAndCheck<birotor::motor_t>,
    DecodeAndCheck<birotor::imu_t>,
    DecodeAndCheck<birotor::pose_t>,
    DecodeAndCheck<birotor::loadcell_t>,
    DecodeAndCheck<birotor::truth_t>,
    DecodeAndCheck<birotor::force_estimate_t>,
    DecodeAndCheck<birotor::estimator_status_t>,
    DecodeAndCheck<birotor::input_health_t>,
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t selector = data[0];
  kDecodeChecks[selector % std::size(kDecodeChecks)](data + 1, size - 1);
  return 0;
}
