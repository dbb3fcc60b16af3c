// The tip mass m_p learned from the arms' symmetric mode (issue 36): the
// mode's frequency f is the model's for one m_p given the file's stiffness,
// so a reading of f with its sigma is a reading of m_p with a sigma.
// Pure library: no LCM, no logging, no allocation per sample (docs/mismatch.md,
// "Learning the tip mass").
#pragma once

#include <cstdint>
#include <functional>

#include "model/birotor_params.h"
#include "model/vehicle_description.h"

namespace birotor {

// The model's symmetric arm mode f(r) over the tip mass m_p = r m_p_file,
// every other parameter the file's (SymmetricArmModeHz, model/linearization.h:
// the body takes part, so f is not f_file r^-1/2), tabulated once at
// start-up; the inverse is a root find on the tabulated model.
class ArmModeTipMassMap {
 public:
  static constexpr int kPoints = 41;
  static constexpr double kLowestRatio = 0.4, kHighestRatio = 2.0;  // of m_p / m_p_file [1]

  // Empty: no model (the arm-mode test off, or a vehicle without a mode).
  ArmModeTipMassMap() = default;
  static ArmModeTipMassMap Of(const BirotorParams& params);
  // A described vehicle's arm mode `mode_index` (ArmModeHz) over every
  // arm's m_p,i = r m_p,i_file together; file_tip_mass_kg() is then the
  // arms' mean m_p (start-up: one hover linearisation per point).
  static ArmModeTipMassMap Of(const VehicleDescription& vehicle, int mode_index);
  // The arms' mean m_p,i of a description: file_tip_mass_kg() of its map,
  // the kg the learner's r is taken of [kg].
  static double MeanTipMassKg(const VehicleDescription& vehicle);

  bool empty() const { return !(tip_mass_kg_ > 0); }
  double file_tip_mass_kg() const { return tip_mass_kg_; }
  // ln f(r) by linear interpolation in r (clamped to the table) [ln Hz].
  double LogHz(double ratio) const;
  // d ln f / d r at r (the table's segment) [1].
  double LogHzSlope(double ratio) const;
  // The r with f(r) = hz: bisection on the interpolant (f falls with r),
  // clamped to [kLowestRatio, kHighestRatio] [1].
  double RatioAt(double hz) const;

 private:
  // The table of ln mode_hz_at(r_j), the file's m_p file_tip_mass_kg; empty
  // when some r_j has no mode (mode_hz_at not > 0).
  static ArmModeTipMassMap Tabulate(const std::function<double(double)>& mode_hz_at, double file_tip_mass_kg);
  int Segment(double ratio) const;
  double tip_mass_kg_ = 0;       // the file's m_p [kg]
  double log_hz_[kPoints] = {};  // ln f at r_j = kLowestRatio + j (kHighestRatio - kLowestRatio) / (kPoints - 1)
};

// The m_p [kg] within [low_kg, high_kg] whose symmetric mode is hz, by
// bisection on SymmetricArmModeHz itself (allocates: start-up and tests).
// NaN when hz is not within the modes of the two ends.
double TipMassForArmModeHz(const BirotorParams& params, double hz, double low_kg, double high_kg);

// A 1-D Kalman filter on r = m_p / m_p_file with the prior N(1,
// prior_std^2), fed the arm mode as read (ArmModeMonitor): one reading per
// strain sample, z = ln f_c with f_c = c + (f_read - c) / pull the reading
// freed of the band-pass's pull towards its centre c (the pull is 0 at c,
// where the monitor moves its band-pass as r is learned), h(r) = ln f(r)
// (ArmModeTipMassMap), R = reading_std^2 (2 tau / dt): consecutive readings
// of an exponentially weighted fit of time constant tau share their data,
// one independent reading per 2 tau. The vehicle does not change: no
// process noise; a landing or a filter reset keeps what was learned.
// A bias b the readings may share (reading_bias, a mode read on some
// gauges only) averages away with no number of readings: a consider
// parameter, its share of the learned r, (1 - P / P_prior) b / |H|, is
// added to the published sigma in quadrature and left out of the gain.
class TipMassLearner {
 public:
  struct Options {
    double prior_std = 0.15;     // of r [1]
    double reading_std = 0.015;  // relative, of one independent reading f_c [1]
    double band_pull = 0.75;     // (f_read - c) / (f - c) of the band-pass [1]
    double reading_bias = 0.0;   // relative 1-sigma bias every reading shares [1]
  };
  TipMassLearner() = default;
  TipMassLearner(const Options& options, const ArmModeTipMassMap& map);

  // One reading f_read [Hz] of the fit with the band-pass centred on
  // centre_hz, fit time constant tau_s, sample interval dt_s.
  void AddReading(double read_hz, double centre_hz, double tau_s, double dt_s);
  // Starts from what an earlier run learned (the gauge state file, issue
  // 36): r = tip_mass_kg / m_p_file (clamped to the map) with the one sigma
  // std_kg / m_p_file, in place of the prior N(1, prior_std^2); later
  // readings refine it. Ignored (false) without a model or for a value or
  // sigma that is not finite and positive.
  bool Resume(double tip_mass_kg, double std_kg);
  // Back to the prior N(1, prior_std^2), no readings: what a resumed value
  // the readings reject leaves.
  void Forget();
  // Readings taken since construction (AddReading that updated r) [1].
  int64_t readings() const { return readings_; }
  // The reading freed of the band-pass's pull [Hz].
  double CorrectedHz(double read_hz, double centre_hz) const {
    return centre_hz + (read_hz - centre_hz) / options_.band_pull;
  }
  bool active() const { return !map_.empty(); }
  double ratio() const { return ratio_; }
  // sqrt(P + ((1 - P / P_prior) reading_bias / |d ln f / d r|)^2) [1].
  double ratio_std() const;
  double tip_mass_kg() const { return ratio_ * map_.file_tip_mass_kg(); }
  // The mode of the learned m_p [Hz].
  double LearnedHz() const;
  const ArmModeTipMassMap& map() const { return map_; }
  const Options& options() const { return options_; }

 private:
  // reading_bias / |d ln f / d r| at r: the whole bias in r (0 without it) [1].
  double ReadingBiasInRatio() const;
  Options options_;
  ArmModeTipMassMap map_;
  double ratio_ = 1.0;     // r [1]
  double variance_ = 0.0;  // of r [1]
  int64_t readings_ = 0;
};

}  // namespace birotor
