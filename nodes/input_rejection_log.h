// Rate-limited log lines for the input rejections that can stop FORCE or
// withhold VALID (the estimator library only counts them): invalid samples,
// out-of-order and duplicate stamps, time outliers, conflicting publishers.
// At most one line per input and class per interval, naming the channel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "estimator/estimator_pipeline.h"
#include "program/logging.h"

namespace birotor {

class InputRejectionLog {
 public:
  // channel_names[i]: full LCM channel name of InputChannel i; the array and
  // the strings must outlive this (read when a line is written).
  InputRejectionLog(double min_interval_s, const std::string* const* channel_names);

  // Compares the counters of `channel` with the last call and logs each class
  // that grew (at most once per interval, on the steady clock, read only then).
  void Check(const PipelineHealth& health, InputChannel channel);

 private:
  static constexpr int kNumClasses = 5;
  const std::string* const* channel_names_;
  int64_t seen_[kNumInputChannels][kNumClasses] = {};    // counter values at the last call
  int64_t logged_[kNumInputChannels][kNumClasses] = {};  // counter values at the last line
  std::vector<RateLimitedLog> limits_;                   // [channel * kNumClasses + class]
};

}  // namespace birotor
