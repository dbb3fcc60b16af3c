// The offset-departure test (docs/mismatch.md, "Offsets that took a force"):
// whether the gauge offsets the method learned in flight left the range
// their anchor and their drift allow, in the direction a common force
// deflects the arms.
//
// In free flight the accelerometer weighs the total force against the file's
// body mass; what the gauges read beyond the forces that explains goes to the
// gauge offsets e_i (they are states of the filter). A payload the file does
// not carry, or every arm softer or every gauge reading high by the same
// share, is such a reading: the offsets take it and the filter stays
// consistent (white innovations), confident, and wrong by the payload's
// weight. What gives it away is where the offsets went: from the anchor a_i
// (the file's offsets, a tare, a state file, with one sigma s_a,i), with a
// random walk of q_i [rad^2/s] since the anchor at t_a, the departure along
// the common-force direction
//
//   z = sum_i w_i (o_i - a_i) / sqrt(sum_i w_i^2 (s_a,i^2 + q_i (t - t_a)))
//
// is N(0, 1) while the offsets are what the gauge model says; w_i is how far
// gauge i's raw reading moves when the vehicle weighs more (any common
// scale: the birotor's +-s_i, kArmSign_i times the gauge scale; for N arms
// the hover deflections with a payload minus without, CommonForceReadings).
// |z| above the limit
// for hold_s without a break in free flight: no offset within its prior and
// drift explains the readings, the test departs (MODEL_MISMATCH, "mass"), and
// stays departed until the next anchor (a tare, a new calibration): the
// offsets keep what they took, so the forces stay wrong.
//
// Near the ground (in the air within the may-touch band of the height the
// ground held the body) each gauge's own departure is judged too,
//
//   z_i = (o_i - a_i) / sqrt(s_a,i^2 + q_i (t - t_a)),
//
// by the same limit and hold. There a support the filter does not see (the
// body back on the ground after a rotor lost thrust, its rotors still
// carrying most of it) holds force and torque: the accelerometer reads the
// weight and the gyro no rotation, so the filter takes the lost thrust for
// one offset (the trirotor, 25 % off rotor 2 a second after lift-off: e_2
// 6.6 sigma from its anchor, forces VALID 3.0 N off, 2-sigma share 0.10).
// In free flight away from the ground a single offset is not judged: the
// gyro and the accelerometer pin each arm's force there, and an offset
// learned beyond its prior is a gauge zero that moved. Pure and
// allocation-free per sample.
#pragma once

#include <cstdint>

#include "samples/multi_arm_samples.h"

namespace birotor {

struct OffsetDepartureState {
  double z = 0;  // the newest departure [sigma]
  // The departure as a multiple c of the direction w: the offsets moved by
  // c w_i (least squares, c = sum_i w_i (o_i - a_i) / sum_i w_i^2) [1].
  double common_multiple = 0;
  // Near the ground: the largest |z_i| of one gauge's own departure, and
  // that gauge (0-based; -1: not judged) [sigma].
  double arm_z = 0;
  int arm = -1;
  double statistic = 0;         // max(|z|, arm_z) / limit, 0 while not judged (> 1: beyond) [1]
  double peak_abs_z = 0;        // largest |z| judged since the anchor [sigma]
  bool departed = false;        // beyond the limit for hold_s; held until the next anchor
  int64_t departed_utime = -1;  // when it departed [us]; -1 not since the anchor
  int departed_arm = -1;        // the gauge whose own departure departed; -1: the common force (or none)
  // The anchor, for a state file: offsets that departed took a force and
  // are not kept (nodes/gauge_state_file.cc PersistedGaugeState) [rad].
  double anchor_rad[kMaxSampleArms] = {};
  double anchor_std_rad[kMaxSampleArms] = {};
};

class OffsetDepartureTest {
 public:
  // limit_sigma: |z| beyond which the offsets are out of their range (0: the
  // test is off); hold_s: how long without a break [s]; arms: the gauges;
  // direction[i]: w_i; drift_psd_rad2_s[i]: q_i of the raw reading.
  OffsetDepartureTest(double limit_sigma, double hold_s, int arms, const double* direction,
                      const double* drift_psd_rad2_s);
  // A new calibration: offsets o_i [rad of the raw reading] with one sigma
  // each; the drift counts from the next Add. Clears a departure.
  void Anchor(const double* offset_rad, const double* offset_std_rad);
  // The offsets in use at utime [us] (the calibration plus what the method
  // learned, raw reading units); judged only in free flight, each gauge's
  // own departure only near_ground as well. True on the sample the test departs.
  bool Add(int64_t utime, const double* offset_rad, bool free_flight, bool near_ground = false);
  const OffsetDepartureState& state() const { return state_; }
  bool enabled() const { return limit_sigma_ > 0; }

 private:
  // The largest |z_i| into state_.arm_z and state_.arm (elapsed_s since t_a).
  void JudgeEachGauge(const double* offset_rad, double elapsed_s);

  double limit_sigma_;
  int64_t hold_us_;
  int arms_;
  double direction_[kMaxSampleArms] = {};
  double drift_psd_rad2_s_[kMaxSampleArms] = {};
  double anchor_rad_[kMaxSampleArms] = {};
  double anchor_variance_rad2_[kMaxSampleArms] = {};  // s_a,i^2
  int64_t anchor_utime_ = -1;                         // t_a: the first Add after the anchor
  int64_t beyond_since_utime_ = -1;                   // start of the current run beyond the limit
  OffsetDepartureState state_;
};

}  // namespace birotor
