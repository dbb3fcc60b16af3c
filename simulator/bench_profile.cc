#include "simulator/bench_profile.h"

#include <cmath>

namespace birotor {
namespace {
constexpr uint64_t kBenchStream = 102;
}  // namespace

BenchCommander::BenchCommander(const BenchProfile& profile, uint64_t seed)
    : profile_(profile), source_(seed, kBenchStream) {}

RotorCommand BenchCommander::At(double t_s) {
  const double low = profile_.omega_low_rad_s, high = profile_.omega_high_rad_s;
  const int64_t segment = static_cast<int64_t>(std::floor(t_s / profile_.segment_s));
  const double t_in_segment = t_s - segment * profile_.segment_s;
  RotorCommand command;
  if (segment % 2 == 0) {
    // Random steps: a new level per rotor every step_hold_s.
    const int64_t index = static_cast<int64_t>(std::floor(t_s / profile_.step_hold_s));
    while (step_index_ < index) {
      ++step_index_;
      for (double& level : step_level_rad_s_) level = low + (high - low) * source_.Uniform();
    }
    command.omega_cmd_rad_s[0] = step_level_rad_s_[0];
    command.omega_cmd_rad_s[1] = step_level_rad_s_[1];
  } else {
    // Linear chirp: phase = 2 pi (f0 t + (f1 - f0) t^2 / (2 T)); rotor 2 in antiphase.
    const double f0 = profile_.chirp_start_hz, f1 = profile_.chirp_end_hz, T = profile_.segment_s;
    const double phase = 2.0 * M_PI * (f0 * t_in_segment + 0.5 * (f1 - f0) * t_in_segment * t_in_segment / T);
    const double mid = 0.5 * (low + high), amplitude = 0.5 * (high - low);
    command.omega_cmd_rad_s[0] = mid + amplitude * std::sin(phase);
    command.omega_cmd_rad_s[1] = mid - amplitude * std::sin(phase);
  }
  return command;
}

}  // namespace birotor
