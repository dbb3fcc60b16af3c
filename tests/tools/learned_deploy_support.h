// Helpers of the tests that deploy what the estimator learned with
// birotor-identify (BIROTOR_IDENTIFY_BIN): files, a temporary folder, the
// program run with its stderr, and a site key file as the package makes it.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "security/site_key.h"

namespace birotor {
namespace testing_support {

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The shipped config/estimator.yaml, which learns the tip mass
// (arm_mode_learn_tip_mass on), at path (BIROTOR_SOURCE_DIR: the source tree).
inline void WriteLearningConfig(const std::string& path) {
  const std::string text = ReadText(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
  ASSERT_NE(text.find("arm_mode_learn_tip_mass: true"), std::string::npos);
  std::ofstream(path) << text;
}

// birotor-identify with args; its exit status, its stderr in *err (optional).
inline int RunIdentify(const std::vector<std::string>& args, std::string* err = nullptr) {
  const std::string err_path = ::testing::TempDir() + "/learned_deploy_stderr_" + std::to_string(getpid());
  std::string command = std::string(BIROTOR_IDENTIFY_BIN) + " --log-level warn";
  for (const std::string& a : args) command += " '" + a + "'";
  command += " 2> '" + err_path + "'";
  const int status = std::system(command.c_str());
  const std::string text = ReadText(err_path);
  if (err != nullptr) *err = text;
  std::fputs(text.c_str(), stderr);
  std::remove(err_path.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A fresh folder under /tmp, removed with everything in it.
struct Folder {
  Folder() {
    char pattern[] = "/tmp/learned_deploy_XXXXXX";
    path = mkdtemp(pattern);
  }
  ~Folder() { std::filesystem::remove_all(path); }
  std::string path;
};

// A site key file as deploy/postinst makes it: 32 random bytes, mode 0600.
inline SiteKey WriteKeyFile(const std::string& path) {
  SiteKey::Bytes bytes;
  std::random_device random;
  for (uint8_t& b : bytes) b = static_cast<uint8_t>(random());
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  EXPECT_GE(fd, 0) << path;
  EXPECT_EQ(write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  close(fd);
  return SiteKey(bytes);
}

}  // namespace testing_support
}  // namespace birotor
