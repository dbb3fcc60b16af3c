// Helpers of the plotting tests: a private temporary folder, its listing, and
// the size a PNG file declares in its IHDR chunk.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace birotor {

// A fresh folder under $TMPDIR (or /tmp) named after `name`, removed with its content.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const std::string& name) {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/" + name + "XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    path_ = ::mkdtemp(buffer.data()) != nullptr ? std::string(buffer.data()) : std::string();
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
  }
  const std::string& path() const { return path_; }
  std::vector<std::string> Entries() const;

 private:
  std::string path_;
};

// Names of the entries of a folder, hidden ones included, sorted.
inline std::vector<std::string> FolderEntries(const std::string& path) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(path)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

inline std::vector<std::string> TemporaryFolder::Entries() const { return FolderEntries(path_); }

struct PngSize {
  uint32_t width = 0, height = 0;
};

// Width and height from the IHDR chunk (bytes 16..23, big endian; PNG
// specification 11.2.2); zero when the file is not a PNG.
inline PngSize ReadPngSize(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  unsigned char head[24] = {};
  file.read(reinterpret_cast<char*>(head), sizeof(head));
  PngSize size;
  if (!file || head[0] != 0x89 || head[1] != 'P' || head[2] != 'N' || head[3] != 'G') return size;
  size.width = (uint32_t{head[16]} << 24) | (uint32_t{head[17]} << 16) | (uint32_t{head[18]} << 8) | head[19];
  size.height = (uint32_t{head[20]} << 24) | (uint32_t{head[21]} << 16) | (uint32_t{head[22]} << 8) | head[23];
  return size;
}

inline std::string ReadFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

}  // namespace birotor
