// Tests of transport/logging.h.
#include "program/logging.h"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace birotor {
namespace {

TEST(RateLimitedLogTest, OneLinePerIntervalCountingTheRest) {
  RateLimitedLog limit(1.0);
  EXPECT_TRUE(limit.ShouldLog(0));
  EXPECT_EQ(limit.suppressed(), 0);
  EXPECT_FALSE(limit.ShouldLog(500000));
  EXPECT_FALSE(limit.ShouldLog(999999));
  EXPECT_TRUE(limit.ShouldLog(1000000));
  EXPECT_EQ(limit.suppressed(), 2);
  EXPECT_FALSE(limit.ShouldLog(1500000));
  EXPECT_EQ(limit.suppressed(), 2);  // still the count reported with the last line
  EXPECT_TRUE(limit.ShouldLog(3000000));
  EXPECT_EQ(limit.suppressed(), 1);
  EXPECT_EQ(limit.total_suppressed(), 3);
}

TEST(RateLimitedLogTest, ClockGoingBackwardsAllowsALine) {
  RateLimitedLog limit(1.0);
  EXPECT_TRUE(limit.ShouldLog(5000000));
  EXPECT_TRUE(limit.ShouldLog(0));  // replay restarted
  EXPECT_FALSE(limit.ShouldLog(100));
}

TEST(RateLimitedLogTest, ZeroIntervalNeverSuppresses) {
  RateLimitedLog limit(0.0);
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(limit.ShouldLog(42));
  EXPECT_EQ(limit.total_suppressed(), 0);
}

TEST(FileChecksumTest, Fnv1a64OfKnownContents) {
  const std::string path = (std::filesystem::temp_directory_path() / "logging_test_checksum").string();
  std::ofstream(path, std::ios::binary) << "";
  EXPECT_EQ(FileChecksum(path), "cbf29ce484222325");  // FNV-1a 64 offset basis
  std::ofstream(path, std::ios::binary) << "a";
  EXPECT_EQ(FileChecksum(path), "af63dc4c8601ec8c");
  std::ofstream(path, std::ios::binary) << "foobar";
  EXPECT_EQ(FileChecksum(path), "85944171f73967e8");
  std::remove(path.c_str());
  EXPECT_EQ(FileChecksum(path), "");
  EXPECT_EQ(FileChecksum(std::filesystem::temp_directory_path().string()), "");
}

TEST(SetupLoggingTest, PatternAndLevel) {
  ::testing::internal::CaptureStderr();
  SetupLogging("estimator_node", "warn");
  spdlog::info("hidden");
  spdlog::warn("shown {}", 3);
  spdlog::default_logger()->flush();
  const std::string output = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::warn);
  EXPECT_EQ(output.find("hidden"), std::string::npos);
  // "[2024-01-31 12:34:56.789] [estimator_node] [warning] shown 3\n"
  const std::string tail = "] [estimator_node] [warning] shown 3\n";
  ASSERT_EQ(output.size(), 24 + tail.size()) << output;
  EXPECT_EQ(output.substr(24), tail) << output;
  EXPECT_EQ(output[0], '[');
  EXPECT_EQ(output[5], '-');
  EXPECT_EQ(output[11], ' ');
  EXPECT_EQ(output[20], '.');
}

TEST(SetupLoggingTest, UnknownLevelFallsBackToInfo) {
  ::testing::internal::CaptureStderr();
  SetupLogging("p", "loud");
  const std::string output = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::info);
  EXPECT_NE(output.find("unknown log level 'loud'"), std::string::npos) << output;
  SetupLogging("p", "off");
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::off);
}

}  // namespace
}  // namespace birotor
