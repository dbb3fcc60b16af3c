// LCM log files: our own bounds-checked reader, and a writer through OutputFile.
#include "transport/log_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>

namespace birotor {
namespace {

// Read-ahead window of the reader [bytes]: large enough that a log of small
// messages costs one read call per thousand events; a smaller file gets a
// window of its own size (at least kMinWindowBytes).
constexpr int64_t kWindowBytes = 1 << 20;
constexpr int64_t kMinWindowBytes = 4096;

uint32_t ReadU32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

uint64_t ReadU64(const uint8_t* p) { return (uint64_t{ReadU32(p)} << 32) | ReadU32(p + 4); }

void PutU32(uint32_t value, uint8_t* p) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(value >> (24 - 8 * i));
}

void PutU64(uint64_t value, uint8_t* p) {
  PutU32(static_cast<uint32_t>(value >> 32), p);
  PutU32(static_cast<uint32_t>(value), p + 4);
}

// Reads up to size bytes at offset; the number read (short only at the end
// of the file or on an error).
int64_t ReadAt(int fd, uint8_t* data, int64_t size, int64_t offset) {
  int64_t done = 0;
  while (done < size) {
    const ssize_t n = ::pread(fd, data + done, static_cast<size_t>(size - done), static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += n;
  }
  return done;
}

int64_t SizeOf(int fd) {
  struct stat info;
  return ::fstat(fd, &info) == 0 ? static_cast<int64_t>(info.st_size) : 0;
}

}  // namespace

bool CheckLogUsable(const LogReader& reader, const std::string& path, double min_fraction, std::string* error,
                    std::string* damage) {
  const int64_t size = reader.file_size();
  if (damage != nullptr) {
    damage->clear();
    if (reader.corrupt_events() > 0 || reader.TruncatedTail()) {
      *damage = path + ": damaged log: " + std::to_string(reader.corrupt_events()) + " corrupt event headers, " +
                std::to_string(reader.skipped_bytes()) + " bytes skipped, " +
                std::to_string(size - reader.tail_offset()) + " bytes of unreadable tail; " +
                std::to_string(reader.events_read()) + " events read";
    }
  }
  if (size == 0) {
    *error = path + ": empty log (0 bytes)";
    return false;
  }
  if (reader.events_read() == 0) {
    *error = path + ": no readable event in " + std::to_string(size) + " bytes";
    return false;
  }
  const double usable = static_cast<double>(reader.event_bytes()) / static_cast<double>(size);
  if (usable < min_fraction) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  ": only %.1f %% of the file is readable events (%lld of %lld bytes; minimum %.0f %%)", 100.0 * usable,
                  static_cast<long long>(reader.event_bytes()), static_cast<long long>(size), 100.0 * min_fraction);
    *error = path + text;
    return false;
  }
  return true;
}

bool LogWriter::Open(const std::string& path, std::string* error) {
  events_written_ = 0;
  error_.clear();
  if (!file_.Open(path, error)) {
    error_ = *error;
    return false;
  }
  return true;
}

bool LogWriter::Write(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (!file_.is_open() || channel.empty() || channel.size() > static_cast<size_t>(kLogMaxChannelBytes) ||
      size > static_cast<size_t>(std::numeric_limits<int32_t>::max()) || (data == nullptr && size > 0)) {
    return false;
  }
  uint8_t header[kLogEventHeaderBytes];
  PutU32(kLogSyncWord, header);
  PutU64(static_cast<uint64_t>(events_written_), header + 4);
  PutU64(static_cast<uint64_t>(timestamp_us), header + 12);
  PutU32(static_cast<uint32_t>(channel.size()), header + 20);
  PutU32(static_cast<uint32_t>(size), header + 24);
  if (!file_.Write(header, sizeof(header)) || !file_.Write(channel.data(), channel.size()) ||
      !file_.Write(data, size)) {
    return false;
  }
  ++events_written_;
  return true;
}

bool LogWriter::Flush() { return file_.is_open() && std::fflush(file_.stream()) == 0; }

bool LogWriter::Close() {
  if (!file_.is_open()) return error_.empty();
  return file_.Commit(&error_);
}

LogReader::~LogReader() { Close(); }

void LogReader::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool LogReader::Open(const std::string& path, std::string* error) {
  // O_NONBLOCK: opening a FIFO without a writer must not hang; it is refused
  // as not regular right after.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    *error = "cannot open log file " + path + ": " + std::strerror(errno);
    return false;
  }
  return OpenDescriptor(fd, path, error);
}

bool LogReader::OpenDescriptor(int fd, const std::string& name, std::string* error) {
  Close();
  fd_ = fd;
  name_ = name;
  finished_ = false;
  window_offset_ = window_bytes_ = position_ = 0;
  tail_offset_ = skipped_bytes_ = corrupt_events_ = event_bytes_ = events_read_ = 0;
  struct stat info;
  if (::fstat(fd_, &info) != 0) {
    *error = "cannot read log file " + name + ": " + std::strerror(errno);
    Close();
    return false;
  }
  if (!S_ISREG(info.st_mode)) {
    *error = name + " is not a regular file (a device, FIFO or folder), so not an LCM log";
    Close();
    return false;
  }
  file_size_ = static_cast<int64_t>(info.st_size);
  window_.resize(static_cast<size_t>(std::clamp(file_size_, kMinWindowBytes, kWindowBytes)));
  if (file_size_ > 0) {
    const uint8_t* head = Bytes(0, 4);
    if (head == nullptr || ReadU32(head) != kLogSyncWord) {
      *error = name + " is not an LCM log (no event sync word at its start)";
      Close();
      return false;
    }
  }
  return true;
}

const uint8_t* LogReader::Bytes(int64_t offset, int64_t size) {
  if (offset < 0 || size > kWindowBytes || offset > file_size_ - size) return nullptr;
  if (offset < window_offset_ || offset + size > window_offset_ + window_bytes_) {
    if (size > static_cast<int64_t>(window_.size())) window_.resize(static_cast<size_t>(kWindowBytes));
    window_offset_ = offset;
    const int64_t capacity = static_cast<int64_t>(window_.size());
    window_bytes_ = ReadAt(fd_, window_.data(), std::min(capacity, file_size_ - offset), offset);
    if (window_bytes_ < size) return nullptr;
  }
  return window_.data() + (offset - window_offset_);
}

int64_t LogReader::FindSyncWord(int64_t offset) {
  static const uint8_t kPattern[4] = {0xED, 0xA1, 0xDA, 0x01};
  while (offset + 4 <= file_size_) {
    // A hole of a sparse file reads as zeros and holds no sync word: jump
    // over it (a 2 GB sparse file costs one call, not 2 GB of reading).
    const off_t data = ::lseek(fd_, static_cast<off_t>(offset), SEEK_DATA);
    if (data < 0 && errno == ENXIO) return -1;  // only a hole remains
    if (data > offset) offset = static_cast<int64_t>(data);
    const int64_t chunk = std::min(static_cast<int64_t>(window_.size()), file_size_ - offset);
    if (chunk < 4) return -1;
    const uint8_t* bytes = Bytes(offset, chunk);
    if (bytes == nullptr) return -1;
    const void* found = ::memmem(bytes, static_cast<size_t>(chunk), kPattern, sizeof(kPattern));
    if (found != nullptr) return offset + (static_cast<const uint8_t*>(found) - bytes);
    offset += chunk - 3;  // a sync word may straddle two chunks
  }
  return -1;
}

bool LogReader::HeaderFits(int64_t offset, int32_t channel_bytes, int32_t data_bytes) {
  if (channel_bytes < 1 || channel_bytes > kLogMaxChannelBytes || data_bytes < 0 ||
      data_bytes > kLogMaxEventDataBytes) {
    return false;
  }
  const int64_t end = offset + kLogEventHeaderBytes + channel_bytes + data_bytes;
  if (end > file_size_) return false;
  // The next event must start right after this one: a length field that is
  // in range but wrong would otherwise make us read garbage as events.
  if (end + 4 > file_size_) return true;
  const uint8_t* next = Bytes(end, 4);
  return next != nullptr && ReadU32(next) == kLogSyncWord;
}

bool LogReader::Next(LogEvent* event) {
  while (fd_ >= 0 && !finished_) {
    const uint8_t* header = Bytes(position_, kLogEventHeaderBytes);
    if (header == nullptr && SizeOf(fd_) > file_size_) {
      file_size_ = SizeOf(fd_);  // a live log has grown
      continue;
    }
    bool valid = false;
    int32_t channel_bytes = 0;
    int32_t data_bytes = 0;
    if (header != nullptr && ReadU32(header) == kLogSyncWord) {
      const int64_t event_number = static_cast<int64_t>(ReadU64(header + 4));
      const int64_t timestamp_us = static_cast<int64_t>(ReadU64(header + 12));
      channel_bytes = static_cast<int32_t>(ReadU32(header + 20));
      data_bytes = static_cast<int32_t>(ReadU32(header + 24));
      valid = HeaderFits(position_, channel_bytes, data_bytes);
      if (valid) {
        event->event_number = event_number;
        event->timestamp_us = timestamp_us;
      }
    }
    if (!valid) {
      if (header != nullptr) ++corrupt_events_;
      const int64_t next = header == nullptr ? -1 : FindSyncWord(position_ + 1);
      if (next < 0) break;
      skipped_bytes_ += next - position_;
      position_ = next;
      continue;
    }
    const int64_t channel_offset = position_ + kLogEventHeaderBytes;
    const uint8_t* channel = Bytes(channel_offset, channel_bytes);
    if (channel == nullptr) break;
    event->channel.assign(reinterpret_cast<const char*>(channel), static_cast<size_t>(channel_bytes));
    // The length was checked against the file above, so this allocation is
    // bounded by the file's size (and by kLogMaxEventDataBytes).
    event->data.resize(static_cast<size_t>(data_bytes));
    const int64_t data_offset = channel_offset + channel_bytes;
    if (data_bytes <= kWindowBytes) {
      const uint8_t* data = Bytes(data_offset, data_bytes);
      if (data == nullptr) break;
      if (data_bytes > 0) std::memcpy(event->data.data(), data, static_cast<size_t>(data_bytes));
    } else if (ReadAt(fd_, event->data.data(), data_bytes, data_offset) != data_bytes) {
      break;
    }
    position_ = data_offset + data_bytes;
    tail_offset_ = position_;
    event_bytes_ += position_ - (channel_offset - kLogEventHeaderBytes);
    ++events_read_;
    return true;
  }
  if (fd_ >= 0) file_size_ = SizeOf(fd_);
  finished_ = true;
  Close();
  return false;
}

}  // namespace birotor
