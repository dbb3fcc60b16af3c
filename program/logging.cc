// spdlog set-up, warning rate limiter and file checksum.
#include "program/logging.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "numerics/fnv1a.h"
#include "program/shutdown.h"

namespace birotor {

void SetupLogging(const std::string& program, const std::string& level) {
  // Closed standard streams: /dev/null in their place, before any socket or
  // pipe can take descriptor 2 and receive the log lines.
  KeepStandardStreamsOpen();
  std::string escaped_program;  // '%' would start a pattern flag
  for (char c : program) {
    escaped_program += c;
    if (c == '%') escaped_program += '%';
  }
  auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  auto logger = std::make_shared<spdlog::logger>(program, std::move(sink));
  logger->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [" + escaped_program + "] [%l] %v");

  const spdlog::level::level_enum parsed = spdlog::level::from_str(level);
  // from_str answers "off" for anything it does not know.
  const bool known = parsed != spdlog::level::off || level == "off";
  logger->set_level(known ? parsed : spdlog::level::info);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(logger);
  if (!known) spdlog::warn("unknown log level '{}', using info", level);
}

RateLimitedLog::RateLimitedLog(double min_interval_s)
    : min_interval_us_(std::isfinite(min_interval_s) && min_interval_s > 0
                           ? static_cast<int64_t>(std::llround(min_interval_s * 1e6))
                           : 0) {}

bool RateLimitedLog::ShouldLog(int64_t now_us) {
  if (has_logged_ && now_us >= last_log_us_ && now_us - last_log_us_ < min_interval_us_) {
    ++pending_;
    ++total_suppressed_;
    return false;
  }
  has_logged_ = true;
  last_log_us_ = now_us;
  suppressed_ = pending_;
  pending_ = 0;
  return true;
}

std::string FileChecksum(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) return "";
  uint64_t hash = kFnv1a64OffsetBasis;
  unsigned char chunk[4096];
  size_t count = 0;
  while ((count = std::fread(chunk, 1, sizeof(chunk), file.get())) > 0) hash = Fnv1a64(chunk, count, hash);
  if (std::ferror(file.get())) return "";  // e.g. a directory
  return ChecksumHex(hash);
}

std::string TextChecksum(const std::string& text) { return TextChecksumHex(text); }

}  // namespace birotor
