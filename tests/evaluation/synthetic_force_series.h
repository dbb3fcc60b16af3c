// Hand-made 1 kHz FORCE and TRUTH series for the metric tests: estimate k at
// utime 1e6 + 1000 k [us] of a 10 N force on both rotors, sigma 0.1 N
// (2 sigma = 0.2 N); the status and the error [N] of estimate k come from
// the callbacks.
#pragma once

#include <cstdint>
#include <vector>

#include "samples/samples.h"

namespace birotor {

struct SyntheticForceSeries {
  std::vector<ForceEstimate> forces;
  std::vector<TruthSample> truth;
};

template <typename StatusOf, typename ErrorOf>
SyntheticForceSeries MakeForceSeries(int64_t count, StatusOf status_of, ErrorOf error_of) {
  SyntheticForceSeries s;
  for (int64_t k = 0; k < count; ++k) {
    TruthSample t;
    t.utime = 1000000 + k * 1000;
    t.force_n[0] = t.force_n[1] = 10.0;
    ForceEstimate e;
    e.utime = t.utime;
    e.status = status_of(k);
    for (int i = 0; i < 2; ++i) {
      e.force_n[i] = 10.0 + error_of(k);
      e.force_std_n[i] = 0.1;
    }
    s.truth.push_back(t);
    s.forces.push_back(e);
  }
  return s;
}

}  // namespace birotor
