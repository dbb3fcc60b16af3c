// Logging set-up shared by every program (spdlog to stderr, one pattern), a
// rate limiter for warnings raised per sample, and a file checksum for the
// start-up line that records which parameter file a run used.
#pragma once

#include <cstdint>
#include <string>

namespace birotor {

// First keeps descriptors 0-2 open (KeepStandardStreamsOpen of
// transport/shutdown.h), then makes the spdlog default logger write to stderr as
// "[2024-01-01 12:00:00.000] [program] [info] message" at `level` (trace,
// debug, info, warn, error, off; anything else means info, with a warning).
void SetupLogging(const std::string& program, const std::string& level);

// At most one line per interval for a message that can fire at sample rate:
//   if (limit.ShouldLog(now_us)) spdlog::warn("... ({} suppressed)", limit.suppressed());
class RateLimitedLog {
 public:
  explicit RateLimitedLog(double min_interval_s);

  // True if a line may be written at now_us [us]; otherwise counts it as
  // suppressed. A clock that jumps backwards (log replay) allows a line.
  bool ShouldLog(int64_t now_us);

  // Calls suppressed between the previous allowed line and the latest one.
  int64_t suppressed() const { return suppressed_; }
  // Calls suppressed since construction.
  int64_t total_suppressed() const { return total_suppressed_; }

 private:
  int64_t min_interval_us_;
  bool has_logged_ = false;
  int64_t last_log_us_ = 0;
  int64_t pending_ = 0;     // suppressed since the last allowed line
  int64_t suppressed_ = 0;  // pending_ when the last line was allowed
  int64_t total_suppressed_ = 0;
};

// FNV-1a 64-bit hash of a file's bytes as 16 lower-case hex digits, or "" if
// the file cannot be read. Identifies a file in a log line, not a security check.
std::string FileChecksum(const std::string& path);
// The same hash of a text.
std::string TextChecksum(const std::string& text);

}  // namespace birotor
