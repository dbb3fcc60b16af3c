// The one percentile of the project: nearest rank, the smallest value with at
// least a fraction p of the n values at or below it,
//   index = min(n, ceil(p n)) - 1   (0-based, in sorted order, p in (0, 1]),
// used by birotor-eval's p95 error, the daemon's p99 processing time and the
// latency and soak tools.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace birotor {

// 0-based sorted-order index of the nearest-rank p-quantile of n > 0 values.
inline size_t NearestRankIndex(size_t n, double fraction) {
  return std::min(n - 1, static_cast<size_t>(std::ceil(fraction * static_cast<double>(n))) - 1);
}

// Nearest-rank p-quantile of [first, last); reorders the range in place
// (std::nth_element: linear time, no allocation). NaN for an empty range.
template <typename Iterator>
double Percentile(Iterator first, Iterator last, double fraction) {
  const size_t n = static_cast<size_t>(last - first);
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  const Iterator nth = first + static_cast<std::ptrdiff_t>(NearestRankIndex(n, fraction));
  std::nth_element(first, nth, last);
  return static_cast<double>(*nth);
}

// The same on a copy of values (leaves the caller's order alone).
template <typename T>
double Percentile(std::vector<T> values, double fraction) {
  return Percentile(values.begin(), values.end(), fraction);
}

}  // namespace birotor
