// The per-input fusion counters of ESTIMATOR_STATUS (fused, rejected by the
// gate, not fused, NIS over the period, the gate) from the methods'
// FusionReports, shared by the birotor's EstimatorPipeline and the N-arm
// MultiArmPipeline so both count alike. No allocation, no throw.
#pragma once

#include "estimator/estimator_config.h"
#include "estimator/fusion_report.h"
#include "estimator/input_admission.h"

namespace birotor {

// The input a measurement comes from (strain: STRAIN, telemetry: MOTOR, gyro
// and accelerometer: IMU).
InputChannel InputChannelOf(FusionSource source);

// The measurement whose gate an input's health shows (IMU: the gyro; the
// accelerometer has counters of its own); false for POSE (none).
bool GatedSourceOf(InputChannel channel, FusionSource* source);

// The EKF's chi-square gate on a measurement's NIS (estimator.ekf
// strain_gate_nis, telemetry_gate_nis, gyro_gate_nis, accel_gate_nis) [1].
double EkfGateNis(const EkfOptions& options, FusionSource source);

// Counts one report into its input's counters (the accelerometer's into
// *accelerometer): the outcome, and its NIS into the period's sum and maximum.
void CountFusionReport(const FusionReport& report, InputCounters inputs[kNumInputChannels],
                       InputCounters* accelerometer);

// An IMU sample with a finite a_z was accepted: the accelerometer's own
// received count, rate and newest stamp.
void CountAccelerometerSample(int64_t utime, int32_t seq, InputCounters* accelerometer);

// Clears the per-period fields (rate, NIS) after a status message.
void ClearPeriod(InputCounters* counters);

}  // namespace birotor
