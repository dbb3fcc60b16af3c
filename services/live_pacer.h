// birotor-sim's live pacing, one copy for the birotor and any vehicle
// description: simulated time runs at speed x wall time, checked (and slept
// for) at most once per millisecond of simulated time.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>

namespace birotor {

class LivePacer {
 public:
  // speed: simulated seconds per wall second; step_s: the simulator's step [s].
  LivePacer(double speed, double step_s)
      : speed_(speed),
        steps_per_check_(std::max<int64_t>(1, std::llround(1e-3 / step_s))),
        start_(std::chrono::steady_clock::now()) {}

  // After each step: sleeps until the wall clock reaches simulated_s / speed.
  void AfterStep(double simulated_s) {
    if (++steps_ % steps_per_check_ != 0) return;
    const auto due = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(simulated_s / speed_));
    std::this_thread::sleep_until(due);
  }

 private:
  double speed_;
  int64_t steps_per_check_;  // 4 steps at 4 kHz
  int64_t steps_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace birotor
