#include "estimator/fusion_counters.h"

#include <cmath>
#include <limits>

namespace birotor {

InputChannel InputChannelOf(FusionSource source) {
  switch (source) {
    case FusionSource::kStrain:
      return InputChannel::kStrain;
    case FusionSource::kTelemetry:
      return InputChannel::kMotor;
    case FusionSource::kGyro:
    case FusionSource::kAccelerometer:
      return InputChannel::kImu;
  }
  return InputChannel::kStrain;
}

bool GatedSourceOf(InputChannel channel, FusionSource* source) {
  switch (channel) {
    case InputChannel::kStrain:
      *source = FusionSource::kStrain;
      return true;
    case InputChannel::kMotor:
      *source = FusionSource::kTelemetry;
      return true;
    case InputChannel::kImu:
      *source = FusionSource::kGyro;
      return true;
    case InputChannel::kPose:
      return false;
  }
  return false;
}

double EkfGateNis(const EkfOptions& options, FusionSource source) {
  switch (source) {
    case FusionSource::kStrain:
      return options.strain_gate_nis;
    case FusionSource::kTelemetry:
      return options.telemetry_gate_nis;
    case FusionSource::kGyro:
      return options.gyro_gate_nis;
    case FusionSource::kAccelerometer:
      return options.accel_gate_nis;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

void CountFusionReport(const FusionReport& report, InputCounters inputs[kNumInputChannels],
                       InputCounters* accelerometer) {
  InputCounters& c = report.source == FusionSource::kAccelerometer
                         ? *accelerometer
                         : inputs[static_cast<int>(InputChannelOf(report.source))];
  switch (report.outcome) {
    case FusionOutcome::kFused:
      ++c.fused;
      break;
    case FusionOutcome::kRejectedGate:
      ++c.rejected_gate;
      break;
    case FusionOutcome::kNotFused:
      ++c.not_fused;
      break;
  }
  if (std::isfinite(report.nis)) {
    c.nis_sum += report.nis;
    if (report.nis > c.nis_max) c.nis_max = report.nis;
    ++c.nis_count;
  }
}

void CountAccelerometerSample(int64_t utime, int32_t seq, InputCounters* accelerometer) {
  ++accelerometer->received;
  ++accelerometer->accepted_in_period;
  accelerometer->last_utime = utime;
  accelerometer->last_seq = seq;
}

void ClearPeriod(InputCounters* counters) {
  counters->accepted_in_period = 0;
  counters->nis_sum = 0;
  counters->nis_max = 0;
  counters->nis_count = 0;
}

}  // namespace birotor
