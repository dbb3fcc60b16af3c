// The site key: 32 random bytes shared by the site's hosts, the key of every
// message authentication (issue 37). Read once at start-up from a key file
// (deploy/postinst makes /etc/birotor/keys/site.key; docs/deploy.md) that
// holds exactly the 32 raw bytes, nothing else (no hex, no newline).
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace birotor {

// Calls sodium_init() once per process (later calls return its first
// result). False if libsodium cannot start (no usable random source).
bool InitSodium();

class SiteKey {
 public:
  static constexpr size_t kBytes = 32;  // crypto_auth_hmacsha512256_KEYBYTES
  using Bytes = std::array<uint8_t, kBytes>;

  explicit SiteKey(const Bytes& bytes) : bytes_(bytes) {}
  ~SiteKey();  // wipes the bytes (sodium_memzero)
  SiteKey(const SiteKey&) = default;
  SiteKey& operator=(const SiteKey&) = default;

  // Reads the key file at path. False with a one-line *error naming the file
  // and the reason, *key unchanged, for: a path that is not a regular file
  // (a symbolic link, a FIFO, a device, a folder), a file writable by its
  // group or by others (mode & 022: anyone but the owner could plant a key),
  // a file that is not exactly 32 bytes, or one that cannot be opened.
  static bool Load(const std::string& path, SiteKey* key, std::string* error);

  const Bytes& bytes() const { return bytes_; }

 private:
  Bytes bytes_;
};

}  // namespace birotor
