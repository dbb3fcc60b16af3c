#include "security/site_key.h"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace birotor {
namespace {

static_assert(SiteKey::kBytes == crypto_auth_hmacsha512256_KEYBYTES, "the site key is a crypto_auth key");

std::string ModeText(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof(text), "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

// Why the opened file is not a key file, "" if it is one.
std::string KeyFileProblem(const struct stat& status) {
  if (!S_ISREG(status.st_mode)) return "not a regular file";
  if ((status.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    return "writable by its group or by others (mode " + ModeText(status.st_mode) + "; chmod 0640 or stricter)";
  }
  if (status.st_size != static_cast<off_t>(SiteKey::kBytes)) {
    return "is " + std::to_string(status.st_size) + " bytes, a site key is exactly " + std::to_string(SiteKey::kBytes) +
           " raw bytes";
  }
  return "";
}

}  // namespace

bool InitSodium() {
  static const int result = sodium_init();  // 0 first time, 1 already done, -1 failed
  return result >= 0;
}

SiteKey::~SiteKey() { sodium_memzero(bytes_.data(), bytes_.size()); }

bool SiteKey::Load(const std::string& path, SiteKey* key, std::string* error) {
  // O_NOFOLLOW: a link is refused (ELOOP); O_NONBLOCK: a FIFO does not hang
  // the open, it is refused by the fstat check.
  const int fd = open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    *error = "site key " + path + ": " +
             (errno == ELOOP ? std::string("a symbolic link, not a regular file") : std::string(std::strerror(errno)));
    return false;
  }
  struct stat status;
  std::string problem = fstat(fd, &status) != 0 ? std::string(std::strerror(errno)) : KeyFileProblem(status);
  Bytes bytes{};
  if (problem.empty() && read(fd, bytes.data(), bytes.size()) != static_cast<ssize_t>(bytes.size())) {
    problem = "short read";
  }
  close(fd);
  if (!problem.empty()) {
    sodium_memzero(bytes.data(), bytes.size());
    *error = "site key " + path + ": " + problem + ": refused";
    return false;
  }
  *key = SiteKey(bytes);
  sodium_memzero(bytes.data(), bytes.size());
  return true;
}

}  // namespace birotor
