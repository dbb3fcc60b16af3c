// A site key for tests: 32 bytes counting up from first (first, first + 1,
// ...), so two tests' keys differ by their first byte.
#pragma once

#include <cstdint>

#include "security/site_key.h"

namespace birotor {

inline SiteKey CountingKeyFrom(uint8_t first) {
  SiteKey::Bytes bytes;
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<uint8_t>(first + i);
  return SiteKey(bytes);
}

}  // namespace birotor
