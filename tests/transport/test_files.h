// Files for the tests of file readers and writers (transport/log_io.h,
// transport/output_file.h, the programs on crafted logs): a fresh temporary
// folder per test, whole files as bytes, and hand-made LCM log event headers.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "transport/log_io.h"

namespace birotor::test_files {

// A new folder <tmp>/<prefix>.XXXXXX; empty on failure.
inline std::string MakeTempDirectory(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + ".XXXXXX")).string();
  return mkdtemp(pattern.data()) != nullptr ? pattern : std::string();
}

// A fixture whose every test gets its own temporary folder, removed after it.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string made = MakeTempDirectory("birotor_test");
    ASSERT_FALSE(made.empty());
    directory_ = made;
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }
  std::string Path(const std::string& name) const { return (directory_ / name).string(); }
  int FilesInDirectory() const {
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(directory_)) count += entry.exists() ? 1 : 0;
    return count;
  }

  std::filesystem::path directory_;
};

inline std::vector<uint8_t> ReadBytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

inline std::string ReadText(const std::string& path) {
  const std::vector<uint8_t> bytes = ReadBytes(path);
  return {bytes.begin(), bytes.end()};
}

inline void WriteBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// One LCM log event header, big-endian: sync word, event number, timestamp
// [us], channel length and data length [bytes] (lcm/eventlog.c's layout).
inline std::vector<uint8_t> LogEventHeader(int64_t number, int64_t timestamp_us, int32_t channel_bytes,
                                           int32_t data_bytes) {
  std::vector<uint8_t> bytes;
  auto put = [&](uint64_t value, int size) {
    for (int i = size - 1; i >= 0; --i) bytes.push_back(static_cast<uint8_t>(value >> (8 * i)));
  };
  put(kLogSyncWord, 4);
  put(static_cast<uint64_t>(number), 8);
  put(static_cast<uint64_t>(timestamp_us), 8);
  put(static_cast<uint32_t>(channel_bytes), 4);
  put(static_cast<uint32_t>(data_bytes), 4);
  return bytes;
}

// Issue 16 item 2: the 138-byte log whose one event declares 0x7fffffff data
// bytes (LCM's reader called fread into a NULL buffer: exit 139).
inline std::vector<uint8_t> HugeDataLengthLog() {
  std::vector<uint8_t> bytes = LogEventHeader(0, 1000, 14, 0x7fffffff);
  const std::string channel = "BIROTOR_STRAIN";
  bytes.insert(bytes.end(), channel.begin(), channel.end());
  bytes.resize(138, 0xAB);
  return bytes;
}

}  // namespace birotor::test_files
