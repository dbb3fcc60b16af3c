// Deterministic random numbers for the simulator: a Gaussian source with its
// own Box-Muller transform on std::mt19937_64 (identical on every platform,
// unlike std::normal_distribution) and the first-order Gauss-Markov process of
// the rotor turbulence.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace birotor {

// Independent random streams of one scenario seed, so switching one sensor
// off does not change the noise of the others; the birotor and the N-arm
// simulators draw each noise from the same stream.
enum NoiseStream : uint64_t {
  kTurbulenceStream = 1,
  kStrainStream = 2,
  kMotorStream = 3,
  kImuStream = 4,
  kPoseStream = 5,
  kLoadCellStream = 6,
  kFaultStream = 7,
  kStrainJitterStream = 8,  // the strain gauges' sampling-instant jitter (sensors.strain.stamp_jitter_s)
};

class GaussianSource {
 public:
  // stream separates independent sources that share one scenario seed.
  GaussianSource(uint64_t seed, uint64_t stream) {
    std::seed_seq sequence{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                           static_cast<uint32_t>(stream)};
    engine_.seed(sequence);
  }

  // Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0); }

  // Standard normal sample (Box-Muller, second value cached).
  double Normal() {
    if (has_cached_) {
      has_cached_ = false;
      return cached_;
    }
    const double u1 = 1.0 - Uniform();  // (0, 1]
    const double u2 = Uniform();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * M_PI * u2;
    cached_ = radius * std::sin(angle);
    has_cached_ = true;
    return radius * std::cos(angle);
  }

  double Normal(double sigma) { return sigma == 0.0 ? 0.0 : sigma * Normal(); }

 private:
  std::mt19937_64 engine_;
  double cached_ = 0.0;
  bool has_cached_ = false;
};

// eta_dot = -eta / tau + w, stationary std sigma, sampled exactly every dt:
//   eta_{k+1} = a eta_k + sqrt(1 - a^2) sigma n_k,   a = exp(-dt / tau).
class GaussMarkov {
 public:
  GaussMarkov(double sigma, double correlation_time_s, double dt_s)
      : sigma_(sigma), decay_(std::exp(-dt_s / correlation_time_s)), drive_(sigma * std::sqrt(1.0 - decay_ * decay_)) {}

  // Starts in the stationary distribution (or at 0 when sigma is 0).
  void Reset(GaussianSource* source) { value_ = source->Normal(sigma_); }
  double Advance(GaussianSource* source) {
    value_ = decay_ * value_ + source->Normal(drive_);
    return value_;
  }
  double value() const { return value_; }

 private:
  double sigma_;
  double decay_;
  double drive_;
  double value_ = 0.0;
};

}  // namespace birotor
