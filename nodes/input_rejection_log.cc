#include "nodes/input_rejection_log.h"

#include <spdlog/spdlog.h>

#include <chrono>

namespace birotor {
namespace {

struct RejectionClass {
  int64_t InputCounters::*counter;
  const char* what;
};

// The order is the column order of seen_ and logged_.
constexpr RejectionClass kClasses[] = {
    {&InputCounters::rejected_invalid, "samples with non-finite or out-of-range fields dropped"},
    {&InputCounters::out_of_order, "samples older than the newest dropped (out of order)"},
    {&InputCounters::duplicates, "samples with a duplicate stamp dropped"},
    {&InputCounters::time_outliers, "samples stamped too far ahead of every input dropped (time outliers)"},
    {&InputCounters::conflicts,
     "conflicting publishers detected (stamps or seq jumping back and forth); "
     "FORCE is not VALID while it lasts"},
};
static_assert(sizeof(kClasses) / sizeof(kClasses[0]) == 5, "kNumClasses");

}  // namespace

InputRejectionLog::InputRejectionLog(double min_interval_s, const std::string* const* channel_names)
    : channel_names_(channel_names), limits_(kNumInputChannels * kNumClasses, RateLimitedLog(min_interval_s)) {}

void InputRejectionLog::Check(const PipelineHealth& health, InputChannel channel) {
  const int c = static_cast<int>(channel);
  const InputCounters& counters = health.inputs[c];
  for (int k = 0; k < kNumClasses; ++k) {
    const int64_t value = counters.*kClasses[k].counter;
    if (value == seen_[c][k]) continue;
    seen_[c][k] = value;
    const int64_t now_us =
        std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
            .count();
    if (!limits_[c * kNumClasses + k].ShouldLog(now_us)) continue;
    spdlog::warn("{}: {} {} since the last report ({} in total)", *channel_names_[c], value - logged_[c][k],
                 kClasses[k].what, value);
    logged_[c][k] = value;
  }
}

}  // namespace birotor
