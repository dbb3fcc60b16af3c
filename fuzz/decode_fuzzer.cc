// libFuzzer harness for every message decoder: the first byte picks the type
// (fuzz/decode_targets.h: 0x80 + i picks the i-th later type, any other byte
// one of the first nine birotor types by byte % 9), the rest is the packet. A
// packet that decodes must re-encode to a canonical form that round-trips;
// nothing may crash, leak or trip a sanitizer.
#include <cstddef>
#include <cstdint>

#include "fuzz/decode_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  birotor::fuzz::TargetOf(data[0]).check(data + 1, size - 1);
  return 0;
}
