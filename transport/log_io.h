// Reading and writing LCM log files (the format of lcm-logger and
// lcm-logplayer) for the simulator's recorder, the replay tools and tests.
// Each event is
//   u32 sync 0xEDA1DA01 | i64 event number | i64 timestamp [us] |
//   i32 channel length | i32 data length | channel | data    (big-endian)
// The reader is our own, not LCM's: it checks every header against the bytes
// left in the file before it allocates anything, skips a corrupt event to the
// next sync word (jumping over sparse holes), counts what it skipped, and
// refuses anything that is not a regular file. The writer goes through
// OutputFile (temporary file, renamed by Close on success).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "transport/lcm_codec.h"
#include "transport/output_file.h"

namespace birotor {

// One event of a log file.
struct LogEvent {
  int64_t event_number = 0;  // as recorded (lcm-logger counts from 0)
  int64_t timestamp_us = 0;  // receive time recorded by the logger [us]
  std::string channel;
  std::vector<uint8_t> data;  // the encoded message
};

inline constexpr uint32_t kLogSyncWord = 0xEDA1DA01;
inline constexpr int64_t kLogEventHeaderBytes = 4 + 8 + 8 + 4 + 4;
// Longest channel name in a log: LCM's limit (LCM_MAX_CHANNEL_NAME_LENGTH).
inline constexpr int32_t kLogMaxChannelBytes = 63;
// Largest event payload the reader accepts [bytes]. Our messages are below
// 1 kB; anything larger than this is a corrupt length field, not data.
inline constexpr int32_t kLogMaxEventDataBytes = 16 << 20;

// Default least share of a log's bytes that must be readable events for a
// tool to use it: a logger killed mid-write loses one event, a damaged log
// more; below this the tool refuses the log (option --min-usable-fraction).
inline constexpr double kDefaultMinUsableLogFraction = 0.9;

class LogReader;

// After a log was read to its end: false (with a one-line *error naming the
// file) when it is empty, has no readable event, or its events cover less
// than min_fraction of its bytes. *damage (optional) gets a one-line warning
// when anything was skipped or cut ("" for an intact log).
bool CheckLogUsable(const LogReader& reader, const std::string& path, double min_fraction, std::string* error,
                    std::string* damage = nullptr);

class LogWriter {
 public:
  LogWriter() = default;
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;

  // Starts writing path (a temporary file next to it until Close). Closes a
  // file already open; false (with *error) if the file cannot be created.
  bool Open(const std::string& path, std::string* error);
  bool is_open() const { return file_.is_open(); }

  // Appends one event. Fails when no file is open, the channel name is not
  // 1..63 bytes or the write fails.
  bool Write(const std::string& channel, int64_t timestamp_us, const void* data, size_t size);

  // Encodes msg into a buffer kept between calls (no allocation in steady state).
  template <class Msg>
  bool WriteMessage(const std::string& channel, int64_t timestamp_us, const Msg& msg) {
    EncodeMessage(msg, &buffer_);
    if (buffer_.empty()) return false;
    return Write(channel, timestamp_us, buffer_.data(), buffer_.size());
  }

  // Pushes buffered events to the operating system.
  bool Flush();
  // Commits the file (flush, fsync, rename over the target); false if any
  // write failed (error() says why), and then no file is left behind. Safe
  // to call twice.
  bool Close();
  // Drops everything written; the target keeps its old content.
  void Abandon() { file_.Abandon(); }
  const std::string& error() const { return error_; }

  int64_t events_written() const { return events_written_; }

 private:
  OutputFile file_;
  std::vector<uint8_t> buffer_;
  std::string error_;
  int64_t events_written_ = 0;
};

class LogReader {
 public:
  LogReader() = default;
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  // Opens a log. False (with a one-line *error) when the file cannot be
  // opened, is not a regular file (/dev/zero, a FIFO, a folder), or is not
  // empty and does not start with an event's sync word (not an LCM log).
  bool Open(const std::string& path, std::string* error);
  // Same over an open descriptor, which the reader then owns; name is used
  // in messages (for tests and the fuzz harness, e.g. a memfd).
  bool OpenDescriptor(int fd, const std::string& name, std::string* error);

  // Reads the next event into *event (reusing its buffers); false at the end
  // of the readable data. A header that does not fit the file (length fields
  // out of range, event running past the end, no sync word after it) is
  // skipped to the next sync word and counted in corrupt_events().
  bool Next(LogEvent* event);

  // After Next returned false: true if bytes remain that are not a complete
  // event (a logger killed mid-write, a cut or corrupt file). tail_offset() is
  // the byte offset where the readable part ends, file_size() the size then.
  bool TruncatedTail() const { return finished_ && tail_offset_ < file_size_; }
  int64_t tail_offset() const { return tail_offset_; }
  int64_t file_size() const { return file_size_; }
  // Bytes skipped between events while looking for the next sync word (0 in
  // an intact log), and the headers that were rejected.
  int64_t skipped_bytes() const { return skipped_bytes_; }
  int64_t corrupt_events() const { return corrupt_events_; }
  // Bytes of the file inside events that were read [bytes].
  int64_t event_bytes() const { return event_bytes_; }
  int64_t events_read() const { return events_read_; }

 private:
  void Close();
  // Pointer to bytes [offset, offset + size) of the file, through a window
  // buffer; nullptr if the file is shorter. size <= kWindowBytes.
  const uint8_t* Bytes(int64_t offset, int64_t size);
  // Offset of the first sync word at or after offset, or -1.
  int64_t FindSyncWord(int64_t offset);
  bool HeaderFits(int64_t offset, int32_t channel_bytes, int32_t data_bytes);

  int fd_ = -1;
  std::string name_;
  std::vector<uint8_t> window_;
  int64_t window_offset_ = 0;  // file offset of window_[0]
  int64_t window_bytes_ = 0;   // valid bytes in window_
  int64_t position_ = 0;       // where the next event is expected [bytes]
  bool finished_ = false;
  int64_t tail_offset_ = 0;  // end of the last complete event [bytes]
  int64_t file_size_ = 0;    // [bytes]
  int64_t skipped_bytes_ = 0;
  int64_t corrupt_events_ = 0;
  int64_t event_bytes_ = 0;
  int64_t events_read_ = 0;
};

}  // namespace birotor
