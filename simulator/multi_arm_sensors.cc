// The sensors of MultiArmSimulator (multi_arm_simulator.h): the birotor's
// models (gauge_model.h, strain_faults.h, body_sensors.h) on N arms.
#include <limits>

#include "simulator/body_sensors.h"
#include "simulator/gauge_model.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

// b_meas_i = s_i b_i + o_i(t) + v_i + n_i (gauge_model.h) on the arms with a
// gauge, NaN on the others; then the strain faults (a spike drawn for an
// arm without a gauge leaves its NaN).
void MultiArmSimulator::EmitStrain(SampleSink* sink) {
  const double sigma = scenario_.sensors.strain_noise_rad;
  MultiArmStrainSample sample;
  sample.utime = utime();
  sample.seq = strain_seq_++;
  sample.n_arms = vehicle_.arm_count;
  const double jitter_s = strain_jitter_noise_.Normal(scenario_.sensors.strain_stamp_jitter_s);
  for (int i = 0; i < vehicle_.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    if (!vehicle_.arms[arm].has_gauge) {
      sample.deflection_rad[arm] = kNaN;
      continue;
    }
    const double b = JitteredDeflectionRad(state_(MultiArmQIndex(vehicle_, DeflectionIndex(i))),
                                           state_(MultiArmVIndex(vehicle_, DeflectionIndex(i))), jitter_s);
    sample.deflection_rad[arm] =
        GaugeReadingRad(scenario_.gauge, i, b, time_s(), rotor_angle_rad_[arm]) + strain_noise_.Normal(sigma);
  }
  const bool in_gap = InTimeWindow(scenario_.faults.strain_gap, sample.utime, utime_offset_us_);
  strain_faults_.Process(sample, vehicle_.arm_count, sigma, in_gap, &fault_noise_, &fault_events_,
                         [&](const MultiArmStrainSample& out) {
                           sink->OnStrainN(out);
                           ++emitted_.strain;
                         });
}

void MultiArmSimulator::EmitMotor(SampleSink* sink) {
  const SensorParams& sensors = scenario_.sensors;
  MultiArmMotorSample sample;
  sample.utime = utime();
  sample.seq = motor_seq_++;
  sample.n_rotors = vehicle_.arm_count;
  const bool in_gap = InTimeWindow(scenario_.faults.motor_telemetry_gap, sample.utime, utime_offset_us_);
  if (in_gap) fault_events_.push_back(FaultEvent{FaultKind::kMotorTelemetryGap, sample.utime, sample.seq, 0, kNaN});
  for (int i = 0; i < vehicle_.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    sample.omega_cmd_rad_s[arm] = ClampCommand(vehicle_.omega_max_rad_s, input_.omega_cmd_rad_s[arm]);
    sample.omega_meas_rad_s[arm] = MeasureRotorSpeed(state_(MultiArmOmegaIndex(vehicle_, i)),
                                                     sensors.motor_telemetry && !in_gap, sensors, &motor_noise_);
  }
  sink->OnMotorN(sample);
  ++emitted_.motor;
}

void MultiArmSimulator::EmitImu(const MultiArmPlantState& derivative, SampleSink* sink) {
  BodyMotion body;
  body.phi_rad = state_(MultiArmQIndex(vehicle_, kPhi));
  body.phi_dot_rad_s = state_(MultiArmVIndex(vehicle_, kPhi));
  body.x_ddot_m_s2 = derivative(MultiArmVIndex(vehicle_, kX));
  body.z_ddot_m_s2 = derivative(MultiArmVIndex(vehicle_, kZ));
  ImuSample sample;
  sample.utime = utime();
  sample.seq = imu_seq_++;
  MeasureImu(body, vehicle_.gravity_m_s2, scenario_.sensors, &imu_noise_, &sample);
  sink->OnImu(sample);
  ++emitted_.imu;
}

void MultiArmSimulator::EmitPose(SampleSink* sink) {
  BodyMotion body;
  body.x_m = state_(MultiArmQIndex(vehicle_, kX));
  body.z_m = state_(MultiArmQIndex(vehicle_, kZ));
  body.phi_rad = state_(MultiArmQIndex(vehicle_, kPhi));
  PoseSample sample;
  sample.utime = utime();
  sample.seq = pose_seq_++;
  MeasurePose(body, scenario_.sensors, &pose_noise_, &sample);
  sink->OnPose(sample);
  ++emitted_.pose;
}

// f_i + n per rotor (the bench's load cells).
void MultiArmSimulator::EmitLoadCell(SampleSink* sink) {
  MultiArmLoadCellSample sample;
  sample.utime = utime();
  sample.seq = loadcell_seq_++;
  sample.n_rotors = vehicle_.arm_count;
  for (int i = 0; i < vehicle_.arm_count; ++i)
    sample.force_n[static_cast<size_t>(i)] = TrueForce(i) + loadcell_noise_.Normal(scenario_.sensors.loadcell_noise_n);
  sink->OnLoadCellN(sample);
  ++emitted_.loadcell;
}

void MultiArmSimulator::EmitTruth(SampleSink* sink) {
  const VehicleDescription& v = vehicle_;
  MultiArmTruthSample sample;
  sample.utime = utime();
  sample.x_m = state_(MultiArmQIndex(v, kX));
  sample.z_m = state_(MultiArmQIndex(v, kZ));
  sample.phi_rad = state_(MultiArmQIndex(v, kPhi));
  sample.x_dot_m_s = state_(MultiArmVIndex(v, kX));
  sample.z_dot_m_s = state_(MultiArmVIndex(v, kZ));
  sample.phi_dot_rad_s = state_(MultiArmVIndex(v, kPhi));
  sample.n_arms = v.arm_count;
  for (int i = 0; i < v.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    sample.deflection_rad[arm] = state_(MultiArmQIndex(v, DeflectionIndex(i)));
    sample.deflection_dot_rad_s[arm] = state_(MultiArmVIndex(v, DeflectionIndex(i)));
    sample.omega_rad_s[arm] = state_(MultiArmOmegaIndex(v, i));
    sample.force_n[arm] = TrueForce(i);
    sample.thrust_scale[arm] = input_.thrust_scale[arm];
  }
  sink->OnTruthN(sample);
  ++emitted_.truth;
}

}  // namespace birotor
