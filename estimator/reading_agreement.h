// Whether the arm mode's readings agree with a mode (estimator/arm_mode_monitor.h):
// the mean of the signed relative readings and its standard error. Pure
// library: no allocation, a few flops per reading.
#pragma once

#include <cstdint>

namespace birotor {

// Whether the arm mode's readings confirm the tip mass in use: the mean of
// the signed readings since start-up (arm_mode_monitor.cc Judge: f over
// the range's nearer edge - 1, 0 within it) lies within half the limit by
// kSigmas of its standard errors. A reading is a fit with time constant
// tau, so a new one is independent every 2 tau: after T seconds of
// readings the mean's standard error is sd sqrt(2 tau / T), asked from
// T = tau on. A vehicle whose readings lie near the limit (tip mass +10 %
// reads -3.0 % with sd 0.7 %) is never confirmed, however long a stretch of
// them lies within half the limit; a matching vehicle (means within 0.7 %,
// sd 0.5-0.9 %) is at 1.1-2.1 s after lift-off (docs/mismatch.md).
class ReadingAgreement {
 public:
  static constexpr double kSigmas = 2.0;
  void Add(double relative_error, double dt_s) {
    sum_ += relative_error;
    sum2_ += relative_error * relative_error;
    seconds_ += dt_s;
    ++count_;
  }
  bool Confirms(double half_limit, double time_constant_s) const;
  // The mean lies beyond half the limit by kSigmas of its standard errors
  // (asked from T = tau on, as Confirms).
  bool Rejects(double half_limit, double time_constant_s) const;

 private:
  // The readings' mean and its standard error; false before T = tau.
  bool MeanAndError(double time_constant_s, double* mean, double* standard_error) const;
  double sum_ = 0, sum2_ = 0;  // of the readings and their squares [1]
  double seconds_ = 0;         // of readings [s]
  int64_t count_ = 0;
};

}  // namespace birotor
