// Files for the state-file tests (gauge_state_file_test,
// vehicle_state_file_test, multi_arm_state_persistence_test): a private path
// per test process, the whole text of a file, a file written with a text,
// and a site key of one repeated byte.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "security/message_authenticator.h"
#include "security/site_key.h"

namespace birotor {

inline std::string TempStatePath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".state";
}

inline std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

inline void Spit(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

inline MessageAuthenticator SiteKeyOfByte(uint8_t fill) {
  SiteKey::Bytes bytes;
  bytes.fill(fill);
  return MessageAuthenticator{SiteKey(bytes)};
}

}  // namespace birotor
