// The strain sensor's faults of scenario.h's FaultParams (a gap, NaN
// samples, spikes on one arm, samples out of order), one copy for the
// birotor's StrainSample and the N-arm MultiArmStrainSample.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "simulator/fault_event.h"
#include "simulator/noise.h"
#include "simulator/sample_clock.h"
#include "simulator/scenario.h"

namespace birotor {

template <class Sample>
class StrainFaultInjector {
 public:
  // strain_period_us: time between two strain samples (the NaN and
  // out-of-order times are turned into the seq of the first sample at or
  // after them). Reserves the fault record once, here.
  StrainFaultInjector(const FaultParams& faults, int64_t strain_period_us) : faults_(faults) {
    for (double t : faults.strain_nan_times_s)
      nan_seq_.push_back(FirstSampleAtOrAfter(SecondsToUtime(t), strain_period_us));
    for (double t : faults.strain_out_of_order_times_s)
      swap_seq_.push_back(FirstSampleAtOrAfter(SecondsToUtime(t), strain_period_us));
    std::sort(nan_seq_.begin(), nan_seq_.end());
    std::sort(swap_seq_.begin(), swap_seq_.end());
  }

  // Applies the faults due at sample (seq, utime) of n_arms arms, whose noise
  // is sigma_rad, records them in *events and hands what goes out, in order,
  // to emit(const Sample&): nothing in the gap, the sample held back for a
  // swap, else the sample, then one held back. in_gap: the sample falls in
  // faults.strain_gap. Two uniforms are drawn for every sample, so the fault
  // pattern does not depend on which other faults are configured; a spike
  // hits arm floor(u N) (u uniform) with the sign from the rest of u.
  template <class Emit>
  void Process(Sample sample, int n_arms, double sigma_rad, bool in_gap, GaussianSource* fault_noise,
               std::vector<FaultEvent>* events, Emit&& emit) {
    const double spike_draw = fault_noise->Uniform();
    const double spike_shape = fault_noise->Uniform();
    const int32_t seq = sample.seq;
    const int64_t utime = sample.utime;
    const bool is_nan = std::binary_search(nan_seq_.begin(), nan_seq_.end(), seq);
    if (in_gap) {
      events->push_back(FaultEvent{FaultKind::kStrainGap, utime, seq, 0, 0.0});
    } else if (is_nan) {
      constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
      for (int i = 0; i < n_arms; ++i) sample.deflection_rad[static_cast<size_t>(i)] = kNaN;
      events->push_back(FaultEvent{FaultKind::kStrainNan, utime, seq, 0, kNaN});
    } else if (spike_draw < faults_.strain_spike_probability) {
      const int arm = std::min(n_arms - 1, static_cast<int>(spike_shape * n_arms));
      const double sign = std::fmod(spike_shape * 4.0, 2.0) < 1.0 ? 1.0 : -1.0;
      const double spike = sign * faults_.strain_spike_sigmas * sigma_rad;
      sample.deflection_rad[static_cast<size_t>(arm)] += spike;
      events->push_back(FaultEvent{FaultKind::kStrainSpike, utime, seq, arm + 1, spike});
    }
    if (in_gap) {
      // Not emitted; a sample held for swapping still goes out.
    } else if (std::binary_search(swap_seq_.begin(), swap_seq_.end(), seq)) {
      events->push_back(FaultEvent{FaultKind::kStrainOutOfOrder, utime, seq, 0, 0.0});
      held_ = sample;
      has_held_ = true;
      return;
    } else {
      emit(sample);
    }
    if (has_held_) {
      emit(held_);
      has_held_ = false;
    }
  }

 private:
  FaultParams faults_;
  std::vector<int64_t> nan_seq_;   // sample indices (seq values) that are NaN
  std::vector<int64_t> swap_seq_;  // sample indices emitted after the next one
  bool has_held_ = false;
  Sample held_;
};

}  // namespace birotor
