// The arm mode's readings against a mode: their mean and its standard error.
#include "estimator/reading_agreement.h"

#include <algorithm>
#include <cmath>

namespace birotor {

bool ReadingAgreement::MeanAndError(double time_constant_s, double* mean, double* standard_error) const {
  // Independent readings so far; asked from half of one on (T = tau).
  const double independent = seconds_ / (2.0 * time_constant_s);  // [1]
  if (count_ == 0 || !(independent >= 0.5)) return false;
  *mean = sum_ / static_cast<double>(count_);
  const double variance = std::max(sum2_ / static_cast<double>(count_) - *mean * *mean, 0.0);
  *standard_error = std::sqrt(variance / independent);
  return true;
}

bool ReadingAgreement::Confirms(double half_limit, double time_constant_s) const {
  double mean = 0, standard_error = 0;
  return MeanAndError(time_constant_s, &mean, &standard_error) &&
         std::fabs(mean) + kSigmas * standard_error < half_limit;
}

bool ReadingAgreement::Rejects(double half_limit, double time_constant_s) const {
  double mean = 0, standard_error = 0;
  return MeanAndError(time_constant_s, &mean, &standard_error) &&
         std::fabs(mean) - kSigmas * standard_error > half_limit;
}

}  // namespace birotor
