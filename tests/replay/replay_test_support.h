// Helpers shared by the replay tests: temporary paths, whole-file reads,
// reference scenarios and log contents by channel.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "params/scenario_yaml.h"
#include "transport/log_io.h"

namespace birotor {

inline std::string TempPath(const std::string& name) { return ::testing::TempDir() + "/birotor_replay_test_" + name; }

inline std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline Scenario ReferenceScenario(const std::string& name) {
  return LoadScenario(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml");
}

// Encoded messages of one channel of a log, in order.
inline std::vector<std::vector<uint8_t>> ChannelPayloads(const std::string& path, const std::string& channel) {
  std::vector<std::vector<uint8_t>> payloads;
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event;
  while (reader.Next(&event)) {
    if (event.channel == channel) payloads.push_back(event.data);
  }
  return payloads;
}

}  // namespace birotor
