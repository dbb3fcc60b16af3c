// The fusion reports of one strain step of a method whose other inputs are
// taken on arrival (the N-arm linear methods and inversion; the EKF queues
// its inputs and reports them all in its strain step).
#pragma once

#include "estimator/fusion_report.h"

namespace birotor {

// From the first call after the previous strain step up to the
// newest one. Each call opens (Open: the first after a Close clears the
// previous step's); the strain step closes after its own reports.
class StepFusionReports {
 public:
  void Open() {
    if (!closed_) return;
    reports_.clear();
    closed_ = false;
  }
  void Add(const FusionReport& report) { reports_.Add(report); }
  void Close() { closed_ = true; }
  const FusionReports* reports() const { return &reports_; }

 private:
  FusionReports reports_;
  bool closed_ = true;
};

}  // namespace birotor
