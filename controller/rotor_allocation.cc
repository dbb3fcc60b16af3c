#include "controller/rotor_allocation.h"

#include <algorithm>
#include <cmath>

namespace birotor {

RotorAllocation AllocateAttitudeFirst(double total_force_n, double force_difference_n, const double (&max_force_n)[2]) {
  RotorAllocation out;
  const double max1 = std::max(max_force_n[0], 0.0), max2 = std::max(max_force_n[1], 0.0);
  // The largest |D| both rotors can make: f2 - f1 in [-max1, max2].
  const double difference = std::clamp(force_difference_n, -max1, max2);
  out.difference_limited = difference != force_difference_n;
  const double lowest = std::fabs(difference);
  const double highest = std::max(lowest, std::min(2.0 * max1 + difference, 2.0 * max2 - difference));
  const double total = std::clamp(total_force_n, lowest, highest);
  out.total_limited = total != total_force_n;
  out.force_n[0] = std::clamp(0.5 * (total - difference), 0.0, max1);
  out.force_n[1] = std::clamp(0.5 * (total + difference), 0.0, max2);
  return out;
}

}  // namespace birotor
