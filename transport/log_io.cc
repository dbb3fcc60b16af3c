// LCM log files through lcm_eventlog_t.
#include "transport/log_io.h"

#include <lcm/eventlog.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>

namespace birotor {
namespace {

constexpr size_t kMaxChannelBytes = 63;  // LCM_MAX_CHANNEL_NAME_LENGTH
// Every event starts with this word (big-endian), then the event number,
// timestamp, channel length and data length.
constexpr uint32_t kSyncWord = 0xEDA1DA01;
constexpr int64_t kEventHeaderBytes = 4 + 8 + 8 + 4 + 4;

// Offset of the first sync word at or after the current position, which is
// where LCM's reader will take the next event from; -1 if there is none.
// Leaves the position unchanged.
int64_t FindSyncWord(FILE* file) {
  const off_t start = ftello(file);
  uint32_t window = 0;
  int64_t offset = static_cast<int64_t>(start);
  int64_t found = -1;
  for (int c; (c = std::fgetc(file)) != EOF; ++offset) {
    window = (window << 8) | static_cast<uint32_t>(c);
    if (offset - start >= 3 && window == kSyncWord) {
      found = offset - 3;
      break;
    }
  }
  std::clearerr(file);
  fseeko(file, start, SEEK_SET);
  return found;
}

int64_t CurrentFileSize(FILE* file) {
  struct stat info;
  if (fstat(fileno(file), &info) != 0) return 0;
  return static_cast<int64_t>(info.st_size);
}

}  // namespace

LogWriter::~LogWriter() { Close(); }

bool LogWriter::Open(const std::string& path, std::string* error) {
  Close();
  log_ = lcm_eventlog_create(path.c_str(), "w");
  if (log_ == nullptr) {
    if (error) *error = "cannot create log file '" + path + "': " + std::strerror(errno);
    return false;
  }
  events_written_ = 0;
  return true;
}

bool LogWriter::Write(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  if (log_ == nullptr || channel.empty() || channel.size() > kMaxChannelBytes ||
      size > static_cast<size_t>(std::numeric_limits<int32_t>::max()) || (data == nullptr && size > 0)) {
    return false;
  }
  lcm_eventlog_event_t event{};
  event.timestamp = timestamp_us;
  event.channellen = static_cast<int32_t>(channel.size());
  event.datalen = static_cast<int32_t>(size);
  // The C API takes non-const pointers but only reads through them.
  event.channel = const_cast<char*>(channel.data());
  event.data = const_cast<void*>(data);
  if (lcm_eventlog_write_event(log_, &event) != 0) return false;
  ++events_written_;
  return true;
}

bool LogWriter::Flush() { return log_ != nullptr && std::fflush(log_->f) == 0; }

bool LogWriter::Close() {
  if (log_ == nullptr) return true;
  const bool flushed = std::fflush(log_->f) == 0;
  lcm_eventlog_destroy(log_);
  log_ = nullptr;
  return flushed;
}

LogReader::~LogReader() { Close(); }

void LogReader::Close() {
  if (log_ != nullptr) lcm_eventlog_destroy(log_);
  log_ = nullptr;
}

bool LogReader::Open(const std::string& path, std::string* error) {
  Close();
  finished_ = false;
  tail_offset_ = 0;
  skipped_bytes_ = 0;
  log_ = lcm_eventlog_create(path.c_str(), "r");
  if (log_ == nullptr) {
    if (error) *error = "cannot open log file '" + path + "': " + std::strerror(errno);
    return false;
  }
  file_size_ = CurrentFileSize(log_->f);
  return true;
}

bool LogReader::Next(LogEvent* event) {
  if (log_ == nullptr || finished_) return false;
  // LCM's reader does not say where an event ends (after an event it peeks
  // at the next sync word, and leaves a partial one consumed), so find the
  // start here and add the event's length.
  const int64_t position = static_cast<int64_t>(ftello(log_->f));
  const int64_t event_start = FindSyncWord(log_->f);
  lcm_eventlog_event_t* raw = lcm_eventlog_read_next_event(log_);
  if (raw == nullptr || event_start < 0) {
    if (raw != nullptr) lcm_eventlog_free_event(raw);
    // A live log may have grown since Open: compare with the size now.
    finished_ = true;
    file_size_ = CurrentFileSize(log_->f);
    Close();
    return false;
  }
  event->event_number = raw->eventnum;
  event->timestamp_us = raw->timestamp;
  event->channel.assign(raw->channel, static_cast<size_t>(raw->channellen));
  const auto* bytes = static_cast<const uint8_t*>(raw->data);
  event->data.assign(bytes, bytes + raw->datalen);
  const int64_t length = kEventHeaderBytes + raw->channellen + raw->datalen;
  lcm_eventlog_free_event(raw);

  tail_offset_ = event_start + length;
  skipped_bytes_ += event_start - position;
  return true;
}

}  // namespace birotor
