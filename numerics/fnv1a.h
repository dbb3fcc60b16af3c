// The one checksum of the project: FNV-1a 64 (Fowler, Noll, Vo), as 16
// lower-case hex digits. It names a file or a vehicle in a log line, a state
// file or a status message, so that two runs can tell whether they used the
// same one; it is not a defence against a forged file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace birotor {

inline constexpr uint64_t kFnv1a64OffsetBasis = 14695981039346656037ull;

// FNV-1a 64 over size bytes, continuing from hash (kFnv1a64OffsetBasis to start).
inline uint64_t Fnv1a64(const void* data, size_t size, uint64_t hash = kFnv1a64OffsetBasis) {
  constexpr uint64_t kFnvPrime = 1099511628211ull;
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= kFnvPrime;
  }
  return hash;
}

// 16 lower-case hex digits, most significant first ("cbf29ce484222325").
inline std::string ChecksumHex(uint64_t hash) {
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

// ChecksumHex(Fnv1a64(text)).
inline std::string TextChecksumHex(const std::string& text) { return ChecksumHex(Fnv1a64(text.data(), text.size())); }

}  // namespace birotor
