// Files for the tests of params/: a parameter file written from text, and a
// file read back as text.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace birotor {
namespace testing {

// Writes text to a new file named after prefix, the running test and a
// counter, so that the parallel CTest processes and the calls of one test
// never share a file; returns its path.
inline std::string WriteTempFile(const std::string& prefix, const std::string& text) {
  static int counter = 0;
  const std::string path = ::testing::TempDir() + "/" + prefix +
                           ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
                           std::to_string(counter++) + ".yaml";
  std::ofstream(path) << text;
  return path;
}

// The whole file as text ("" if it cannot be read).
inline std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace testing
}  // namespace birotor
