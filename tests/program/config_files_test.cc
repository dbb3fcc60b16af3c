// Tests of transport/config_files.h: the search order of default files.
#include "program/config_files.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace birotor {
namespace {

// A private XDG_CONFIG_HOME for one test, restored afterwards.
class ConfigFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* old = std::getenv("XDG_CONFIG_HOME");
    had_old_ = old != nullptr;
    if (had_old_) old_ = old;
    xdg_ = ::testing::TempDir() + "/config_files_test_" + std::to_string(::getpid());
    std::filesystem::create_directories(xdg_ + "/birotor/scenarios");
    ::setenv("XDG_CONFIG_HOME", xdg_.c_str(), 1);
  }
  void TearDown() override {
    std::filesystem::remove_all(xdg_);
    if (had_old_) {
      ::setenv("XDG_CONFIG_HOME", old_.c_str(), 1);
    } else {
      ::unsetenv("XDG_CONFIG_HOME");
    }
  }
  std::string xdg_;
  std::string old_;
  bool had_old_ = false;
};

TEST_F(ConfigFilesTest, SearchOrderIsUserThenSiteThenShipped) {
  const std::vector<std::string> dirs = ConfigSearchDirs();
  ASSERT_EQ(dirs.size(), 3u);
  EXPECT_EQ(dirs[0], xdg_ + "/birotor");
  EXPECT_EQ(dirs[1], "/etc/birotor");
  // The test executable is build/tests/program/program_test: the shipped
  // folder is relative to it, never a compiled-in path.
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
  EXPECT_EQ(dirs[2], std::filesystem::path(exe).parent_path().parent_path().string() + "/share/birotor/config");
  EXPECT_EQ(ConfigSearchText("x.yaml"), "first of " + dirs[0] + "/x.yaml, /etc/birotor/x.yaml, " + dirs[2] + "/x.yaml");
}

TEST_F(ConfigFilesTest, UsersFileWinsAndAbsentFileNamesTheShippedPlace) {
  const std::string name = "config_files_test_" + std::to_string(::getpid()) + ".yaml";
  EXPECT_EQ(FindConfigFile(name), ConfigSearchDirs()[2] + "/" + name);
  std::ofstream(xdg_ + "/birotor/" + name) << "vehicle: {}\n";
  EXPECT_EQ(FindConfigFile(name), xdg_ + "/birotor/" + name);
}

TEST_F(ConfigFilesTest, BareScenarioNamesAreLookedUpPathsAreNot) {
  std::ofstream(xdg_ + "/birotor/scenarios/mine.yaml") << "scenario: {}\n";
  EXPECT_EQ(ResolveScenario("mine"), xdg_ + "/birotor/scenarios/mine.yaml");
  EXPECT_EQ(ResolveScenario("mine.yaml"), "mine.yaml");
  EXPECT_EQ(ResolveScenario("config/scenarios/hover.yaml"), "config/scenarios/hover.yaml");
  EXPECT_EQ(ResolveScenario("/abs/hover.yaml"), "/abs/hover.yaml");
}

}  // namespace
}  // namespace birotor
