// The tip mass from the symmetric arm mode: the model's f(m_p) and a 1-D filter.
#include "estimator/tip_mass_learning.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "estimator/arm_mode_monitor.h"

namespace birotor {
namespace {

constexpr double kRatioStep =
    (ArmModeTipMassMap::kHighestRatio - ArmModeTipMassMap::kLowestRatio) / (ArmModeTipMassMap::kPoints - 1);

double RatioOf(int j) { return ArmModeTipMassMap::kLowestRatio + j * kRatioStep; }

}  // namespace

ArmModeTipMassMap ArmModeTipMassMap::Tabulate(const std::function<double(double)>& mode_hz_at,
                                              double file_tip_mass_kg) {
  ArmModeTipMassMap map;
  for (int j = 0; j < kPoints; ++j) {
    const double hz = mode_hz_at(RatioOf(j));
    if (!(hz > 0)) return ArmModeTipMassMap();  // no mode somewhere in the range: no map
    map.log_hz_[j] = std::log(hz);
  }
  map.tip_mass_kg_ = file_tip_mass_kg;
  return map;
}

ArmModeTipMassMap ArmModeTipMassMap::Of(const BirotorParams& params) {
  BirotorParams p = params;
  return Tabulate(
      [&](double ratio) {
        p.tip_mass_kg = ratio * params.tip_mass_kg;
        return SymmetricArmModeHz(p);
      },
      params.tip_mass_kg);
}

ArmModeTipMassMap ArmModeTipMassMap::Of(const VehicleDescription& vehicle, int mode_index) {
  if (vehicle.arm_count < 1 || mode_index < 0) return ArmModeTipMassMap();
  VehicleDescription v = vehicle;
  return Tabulate(
      [&](double ratio) {
        for (int i = 0; i < vehicle.arm_count; ++i) {
          const size_t k = static_cast<size_t>(i);
          v.arms[k].tip_mass_kg = ratio * vehicle.arms[k].tip_mass_kg;
        }
        return ArmModeHz(v, mode_index);
      },
      MeanTipMassKg(vehicle));
}

double ArmModeTipMassMap::MeanTipMassKg(const VehicleDescription& vehicle) {
  if (vehicle.arm_count < 1) return 0.0;
  double sum_kg = 0;
  for (int i = 0; i < vehicle.arm_count; ++i) sum_kg += vehicle.arms[static_cast<size_t>(i)].tip_mass_kg;
  return sum_kg / vehicle.arm_count;
}

int ArmModeTipMassMap::Segment(double ratio) const {
  const int j = static_cast<int>(std::floor((ratio - kLowestRatio) / kRatioStep));
  return std::clamp(j, 0, kPoints - 2);
}

double ArmModeTipMassMap::LogHzSlope(double ratio) const {
  const int j = Segment(ratio);
  return (log_hz_[j + 1] - log_hz_[j]) / kRatioStep;
}

double ArmModeTipMassMap::LogHz(double ratio) const {
  const double r = std::clamp(ratio, kLowestRatio, kHighestRatio);
  const int j = Segment(r);
  return log_hz_[j] + (r - RatioOf(j)) * LogHzSlope(r);
}

double ArmModeTipMassMap::RatioAt(double hz) const {
  // ln f falls monotonically with r: bisection to 1e-9 of r (31 steps).
  const double target = std::log(hz);
  double low = kLowestRatio, high = kHighestRatio;
  if (!(target < LogHz(low))) return low;
  if (!(target > LogHz(high))) return high;
  for (int k = 0; k < 31; ++k) {
    const double mid = 0.5 * (low + high);
    (LogHz(mid) > target ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

double TipMassForArmModeHz(const BirotorParams& params, double hz, double low_kg, double high_kg) {
  BirotorParams p = params;
  const auto mode_at = [&](double m_p) {
    p.tip_mass_kg = m_p;
    return SymmetricArmModeHz(p);
  };
  if (!(hz <= mode_at(low_kg) && hz >= mode_at(high_kg))) return std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 50 && high_kg - low_kg > 1e-12 * params.tip_mass_kg; ++k) {
    const double mid = 0.5 * (low_kg + high_kg);
    (mode_at(mid) > hz ? low_kg : high_kg) = mid;
  }
  return 0.5 * (low_kg + high_kg);
}

TipMassLearner::TipMassLearner(const Options& options, const ArmModeTipMassMap& map) : options_(options), map_(map) {
  Forget();
}

double TipMassLearner::ReadingBiasInRatio() const {
  if (!(options_.reading_bias > 0) || !active()) return 0.0;
  const double slope = std::fabs(map_.LogHzSlope(ratio_));
  return slope > 0 ? options_.reading_bias / slope : 0.0;
}

double TipMassLearner::ratio_std() const {
  // The share of r the readings gave (0 at the prior, 1 once they alone
  // decide) carries their common bias.
  const double prior_variance = options_.prior_std * options_.prior_std;
  const double learned_share = prior_variance > 0 ? std::clamp(1.0 - variance_ / prior_variance, 0.0, 1.0) : 1.0;
  const double bias = learned_share * ReadingBiasInRatio();
  return std::sqrt(variance_ + bias * bias);
}

double TipMassLearner::LearnedHz() const { return std::exp(map_.LogHz(ratio_)); }

void TipMassLearner::AddReading(double read_hz, double centre_hz, double tau_s, double dt_s) {
  if (!active() || !(read_hz > 0) || !(dt_s > 0)) return;
  const double corrected_hz = CorrectedHz(read_hz, centre_hz);
  if (!(corrected_hz > 0)) return;
  // z = ln f_c, h(r) = ln f(r), H = d ln f / d r; R per sample so that the
  // samples of 2 tau weigh as one reading of reading_std.
  const double innovation = std::log(corrected_hz) - map_.LogHz(ratio_);
  const double h = map_.LogHzSlope(ratio_);
  const double r = options_.reading_std * options_.reading_std * (2.0 * tau_s / dt_s);
  const double s = h * variance_ * h + r;
  const double gain = variance_ * h / s;
  ratio_ = std::clamp(ratio_ + gain * innovation, ArmModeTipMassMap::kLowestRatio, ArmModeTipMassMap::kHighestRatio);
  variance_ *= 1.0 - gain * h;
  ++readings_;
}

void TipMassLearner::Forget() {  // the prior: the file's m_p, prior_std
  ratio_ = 1.0;
  variance_ = options_.prior_std * options_.prior_std;
  readings_ = 0;
}

bool TipMassLearner::Resume(double tip_mass_kg, double std_kg) {
  const double file_kg = map_.file_tip_mass_kg();
  if (!active() || !std::isfinite(tip_mass_kg) || !(tip_mass_kg > 0) || !std::isfinite(std_kg) || !(std_kg > 0)) {
    return false;
  }
  ratio_ = std::clamp(tip_mass_kg / file_kg, ArmModeTipMassMap::kLowestRatio, ArmModeTipMassMap::kHighestRatio);
  variance_ = (std_kg / file_kg) * (std_kg / file_kg);
  // A learned sigma holds the readings' bias already (ratio_std): the
  // filter's own share is what is left of it (at least a tenth of it).
  const double bias = ReadingBiasInRatio();
  variance_ -= std::min(bias * bias, 0.9 * variance_);
  return true;
}

}  // namespace birotor
