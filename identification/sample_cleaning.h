// Dropping the bad samples of a recorded log before identification, and
// counting them by reason, so that one corrupt event (a NaN, a stamp of
// INT64_MIN, a duplicated or late packet) costs one sample, not the log.
#pragma once

#include <cstdint>

#include "samples/sensor_log.h"

namespace birotor {

// Samples of one stream dropped, by reason.
struct DroppedSamples {
  int64_t non_finite = 0;    // a measured field is NaN or +-Inf (MOTOR telemetry may be NaN: absent)
  int64_t bad_stamp = 0;     // utime outside [0, 2^53) us, or a jump forward that no later sample confirms
  int64_t out_of_order = 0;  // utime older than the newest sample kept
  int64_t duplicate = 0;     // utime equal to the newest sample kept
  int64_t total() const { return non_finite + bad_stamp + out_of_order + duplicate; }
  DroppedSamples& operator+=(const DroppedSamples& other);
};

// Per stream, for the report (words: params/identified_parameter_file.h
// DroppedSamplesText).
struct SampleCleaningReport {
  DroppedSamples strain, motor, imu, pose, loadcell;
  int64_t total() const;
  SampleCleaningReport& operator+=(const SampleCleaningReport& other);
};

// Keeps, per stream and in recorded order, the samples whose fields are
// finite and whose utime is in [0, 2^53) us and newer than the previous kept
// sample. A forward jump of more than max_forward_jump_us [us] is kept only
// when the next recorded sample continues within that bound after it (a real
// pause of the recording); otherwise it is a lone stamp from the future and
// dropped, so it cannot turn every later sample into "out of order". TRUTH
// (never fitted) is only sorted by time.
SampleCleaningReport CleanLog(SensorLog* log, int64_t max_forward_jump_us);

}  // namespace birotor
