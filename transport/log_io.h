// Reading and writing LCM log files (the format of lcm-logger and
// lcm-logplayer) through LCM's own eventlog API, for the simulator's recorder,
// replay tools and tests. The reader reports a corrupt or truncated tail.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "transport/lcm_codec.h"

struct _lcm_eventlog_t;  // lcm/eventlog.h, kept out of this header

namespace birotor {

// One event of a log file.
struct LogEvent {
  int64_t event_number = 0;  // position in the log, from 0
  int64_t timestamp_us = 0;  // receive time recorded by the logger [us]
  std::string channel;
  std::vector<uint8_t> data;  // the encoded message
};

class LogWriter {
 public:
  LogWriter() = default;
  ~LogWriter();
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;

  // Creates (or truncates) the file. Closes a file already open.
  bool Open(const std::string& path, std::string* error);
  bool is_open() const { return log_ != nullptr; }

  // Appends one event. Fails when no file is open, the channel name is not
  // 1..63 bytes (LCM's limit) or the disk write fails.
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
  // Flushes and closes; false if the final flush failed. Safe to call twice.
  bool Close();

  int64_t events_written() const { return events_written_; }

 private:
  _lcm_eventlog_t* log_ = nullptr;
  std::vector<uint8_t> buffer_;
  int64_t events_written_ = 0;
};

class LogReader {
 public:
  LogReader() = default;
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  bool Open(const std::string& path, std::string* error);

  // Reads the next event into *event (reusing its buffers); false at the end
  // of the file or where the file stops being a valid log.
  bool Next(LogEvent* event);

  // After Next returned false: true if bytes remain that are not a complete
  // event (a logger killed mid-write, a cut or corrupt file). tail_offset() is
  // the byte offset where the readable part ends, file_size() the size then.
  bool TruncatedTail() const { return finished_ && tail_offset_ < file_size_; }
  int64_t tail_offset() const { return tail_offset_; }
  int64_t file_size() const { return file_size_; }
  // Bytes between events that LCM's reader skipped while looking for the next
  // event's sync word (0 in an intact log).
  int64_t skipped_bytes() const { return skipped_bytes_; }

 private:
  void Close();

  _lcm_eventlog_t* log_ = nullptr;
  bool finished_ = false;
  int64_t tail_offset_ = 0;  // end of the last complete event [bytes]
  int64_t file_size_ = 0;    // [bytes]
  int64_t skipped_bytes_ = 0;
};

}  // namespace birotor
