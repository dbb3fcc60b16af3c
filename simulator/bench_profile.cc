#include "simulator/bench_profile.h"

#include <cmath>

namespace birotor {
namespace {
constexpr uint64_t kBenchStream = 102;
}  // namespace

BenchCommander::BenchCommander(const BenchProfile& profile, uint64_t seed, int rotor_count)
    : profile_(profile), source_(seed, kBenchStream), rotor_count_(rotor_count) {}

const std::array<double, kMaxArms>& BenchCommander::Speeds(double t_s) {
  const double low = profile_.omega_low_rad_s, high = profile_.omega_high_rad_s;
  const int64_t segment = static_cast<int64_t>(std::floor(t_s / profile_.segment_s));
  const double t_in_segment = t_s - segment * profile_.segment_s;
  const size_t n = static_cast<size_t>(rotor_count_);
  if (segment % 2 == 0) {
    // Random steps: a new level per rotor every step_hold_s.
    const int64_t index = static_cast<int64_t>(std::floor(t_s / profile_.step_hold_s));
    while (step_index_ < index) {
      ++step_index_;
      for (size_t i = 0; i < n; ++i) step_level_rad_s_[i] = low + (high - low) * source_.Uniform();
    }
    for (size_t i = 0; i < n; ++i) speeds_rad_s_[i] = step_level_rad_s_[i];
  } else {
    // Linear chirp: phase = 2 pi (f0 t + (f1 - f0) t^2 / (2 T)); even rotors in antiphase.
    const double f0 = profile_.chirp_start_hz, f1 = profile_.chirp_end_hz, T = profile_.segment_s;
    const double phase = 2.0 * M_PI * (f0 * t_in_segment + 0.5 * (f1 - f0) * t_in_segment * t_in_segment / T);
    const double mid = 0.5 * (low + high), amplitude = 0.5 * (high - low);
    for (size_t i = 0; i < n; ++i)
      speeds_rad_s_[i] = i % 2 == 0 ? mid + amplitude * std::sin(phase) : mid - amplitude * std::sin(phase);
  }
  return speeds_rad_s_;
}

RotorCommand BenchCommander::At(double t_s) {
  const std::array<double, kMaxArms>& speeds = Speeds(t_s);
  RotorCommand command;
  command.omega_cmd_rad_s[0] = speeds[0];
  command.omega_cmd_rad_s[1] = speeds[1];
  return command;
}

}  // namespace birotor
