#include "simulator/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/bench_dynamics.h"
#include "model/rk4.h"
#include "samples/rotor_count.h"
#include "simulator/body_sensors.h"
#include "simulator/gauge_model.h"
#include "simulator/sample_clock.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

Simulator::Simulator(const Scenario& scenario)
    : scenario_(scenario),
      vehicle_(BirotorModelOf(scenario.vehicle)),
      clamped_body_(scenario.mode == "bench"),
      step_us_(SecondsToUtime(scenario.step_s)),
      total_steps_(std::llround(scenario.duration_s / scenario.step_s)),
      equilibrium_(SolveHoverEquilibrium(vehicle_)),
      trajectory_(scenario),
      controller_(vehicle_, scenario.controller, 0.5 * (equilibrium_.force_n[0] + equilibrium_.force_n[1])),
      bench_(scenario.bench, scenario.seed),
      turbulence_{GaussMarkov(vehicle_.turbulence_std, vehicle_.turbulence_corr_time_s, scenario.step_s),
                  GaussMarkov(vehicle_.turbulence_std, vehicle_.turbulence_corr_time_s, scenario.step_s)},
      ground_(scenario),
      turbulence_noise_(scenario.seed, kTurbulenceStream),
      strain_noise_(scenario.seed, kStrainStream),
      strain_jitter_noise_(scenario.seed, kStrainJitterStream),
      motor_noise_(scenario.seed, kMotorStream),
      imu_noise_(scenario.seed, kImuStream),
      pose_noise_(scenario.seed, kPoseStream),
      loadcell_noise_(scenario.seed, kLoadCellStream),
      fault_noise_(scenario.seed, kFaultStream),
      strain_faults_(scenario.faults, StepsPerSample(scenario.sensors.strain.rate_hz, scenario.step_s) *
                                          SecondsToUtime(scenario.step_s)) {
  const SensorParams& sensors = scenario_.sensors;
  auto decimation = [&](const SensorRate& rate) {
    Decimation d;
    d.enabled = rate.enabled;
    d.every_steps = StepsPerSample(rate.rate_hz, scenario_.step_s);
    return d;
  };
  control_ = decimation(SensorRate{true, scenario_.controller.rate_hz});
  strain_ = decimation(sensors.strain);
  motor_ = decimation(sensors.motor);
  imu_ = decimation(sensors.imu);
  pose_ = decimation(sensors.pose);
  loadcell_ = decimation(sensors.loadcell);
  truth_ = decimation(sensors.truth);

  const FaultParams& faults = scenario_.faults;
  for (int i = 0; i < kBirotorRotors; ++i) efficiency_[i] = faults.initial_thrust_scale[i];
  for (const ThrustStep& step : faults.thrust_steps) {
    const int64_t index = FirstSampleAtOrAfter(SecondsToUtime(step.time_s), step_us_);
    thrust_steps_.push_back({index, step.rotor - 1, step.scale});
  }
  std::stable_sort(thrust_steps_.begin(), thrust_steps_.end(),
                   [](const ScheduledStep& a, const ScheduledStep& b) { return a.step < b.step; });
  fault_events_.reserve(4096);

  // Initial state: the exact hover equilibrium at the start position (flight),
  // at rest on the ground with the motors stopped (ground phase), or the
  // static arm deflection under the first bench command (bench).
  const BirotorParams& p = vehicle_;
  state_.setZero();
  for (int i = 0; i < kBirotorRotors; ++i) rotor_angle_rad_[i] = scenario_.gauge.rotor_angle_rad[i];
  if (clamped_body_ || ground_.enabled()) {
    command_ = clamped_body_ ? bench_.At(0.0) : RotorCommand();
    if (!clamped_body_) {
      state_(kPlantQ + kX) = scenario_.start_position_m[0];
      state_(kPlantQ + kZ) = scenario_.start_position_m[1];
    }
    for (int i = 0; i < kBirotorRotors; ++i) {
      const double omega = ClampCommand(p, command_.omega_cmd_rad_s[i]);
      const double force = RotorThrust(p, omega, efficiency_[i]);
      state_(kPlantOmega1 + i) = omega;
      state_(kPlantQ + kB1 + i) = StaticDeflectionRad(p, i, force);
    }
  } else {
    state_ = HoverPlantState(equilibrium_);
    state_(kPlantQ + kX) = scenario_.start_position_m[0];
    state_(kPlantQ + kZ) = scenario_.start_position_m[1];
  }
  for (GaussMarkov& eta : turbulence_) eta.Reset(&turbulence_noise_);
}

PlantState Simulator::Derivative(const PlantState& x) const {
  // On the ground the support holds the body level and still (x and z do not
  // enter the arm equations: a translated clamped body is the bench).
  return (clamped_body_ || ground_.on_ground()) ? ClampedBodyDerivative(vehicle_, x, input_)
                                                : PlantDerivative(vehicle_, x, input_);
}

RotorCommand Simulator::Command(double t_s) {
  if (clamped_body_) return bench_.At(t_s);
  RotorCommand command;
  double phase_omega_rad_s = 0.0;
  if (ground_.PhaseCommand(t_s, &phase_omega_rad_s)) {
    command.omega_cmd_rad_s[0] = command.omega_cmd_rad_s[1] = phase_omega_rad_s;
    return command;
  }
  if (external_commands_) {
    reference_ = ReferenceAt(t_s);
    return esc_->TimedOut(utime()) ? RotorCommand() : external_command_;
  }
  reference_ = ground_.FlightReference(t_s, trajectory_);
  return controller_.Update(state_, reference_);
}

void Simulator::UseExternalCommands(double command_timeout_s) {
  external_commands_ = true;
  esc_ = std::make_unique<EscCommandRule>(scenario_.esc, command_timeout_s);
  // Before the first command the ESCs run the speeds of the start state
  // (hover), for at most the timeout.
  for (int i = 0; i < kBirotorRotors; ++i) external_command_.omega_cmd_rad_s[i] = state_(kPlantOmega1 + i);
}

EscVerdict Simulator::OfferMotorCommand(int32_t seq, int64_t utime, const double (&omega_cmd_rad_s)[kBirotorRotors]) {
  if (!esc_) return EscVerdict::kStale;  // not flying on external commands
  const EscVerdict verdict =
      esc_->Offer(seq, utime, omega_cmd_rad_s, kBirotorRotors, vehicle_.omega_max_rad_s, this->utime());
  if (verdict == EscVerdict::kAccepted) {
    for (int i = 0; i < kBirotorRotors; ++i) external_command_.omega_cmd_rad_s[i] = omega_cmd_rad_s[i];
  }
  return verdict;
}

void Simulator::EmitSetpoints(double rate_hz) {
  setpoint_.enabled = true;
  setpoint_.every_steps = std::max<int64_t>(1, std::llround(1.0 / (rate_hz * scenario_.step_s)));
}

void Simulator::EmitSetpoint(int64_t utime, double t_s, SampleSink* sink) {
  sink->OnSetpoint(SetpointFromReference(ReferenceAt(t_s), utime, setpoint_seq_++));
}

double Simulator::GaugeOffsetRad(int gauge, double t_s) const {
  return birotor::GaugeOffsetRad(scenario_.gauge, gauge, t_s);
}

double Simulator::TrueForce(int rotor) const {
  return RotorThrust(vehicle_, state_(kPlantOmega1 + rotor), input_.thrust_scale[rotor]);
}

void Simulator::RecordFault(FaultKind kind, int64_t utime, int32_t seq, int rotor, double value) {
  fault_events_.push_back(FaultEvent{kind, utime, seq, rotor, value});
}

bool Simulator::Step(SampleSink* sink) {
  if (done()) return false;
  const int64_t k = step_index_;
  const int64_t now_us = utime();
  const double t_s = time_s();

  // Thrust efficiency steps take effect at the first step at or after their time.
  while (next_thrust_step_ < thrust_steps_.size() && thrust_steps_[next_thrust_step_].step <= k) {
    const ScheduledStep& step = thrust_steps_[next_thrust_step_++];
    efficiency_[step.rotor] = step.scale;
    RecordFault(FaultKind::kThrustStep, now_us, -1, step.rotor + 1, step.scale);
  }
  // mu_i = s_i (1 + eta_i), held over this step.
  for (int i = 0; i < kBirotorRotors; ++i) input_.thrust_scale[i] = efficiency_[i] * (1.0 + turbulence_[i].value());

  // Controller (or bench profile) at its own rate; commands are held (ZOH).
  // External commands reach the ESCs at the step they arrive.
  if (control_.Due(k) || external_commands_) command_ = Command(t_s);
  input_.omega_cmd_rad_s[0] = command_.omega_cmd_rad_s[0];
  input_.omega_cmd_rad_s[1] = command_.omega_cmd_rad_s[1];
  // Lift-off before the step: the support only pushes.
  ground_.UpdateLiftoff(now_us, [this] { return PlantDerivative(vehicle_, state_, input_)(kPlantV + kZ); });

  // RK4, keeping k1 = f(x_k, u_k) for the accelerometer.
  const double dt = scenario_.step_s;
  const PlantState k1 = Derivative(state_);

  if (sink != nullptr) {
    if (setpoint_.Due(k)) EmitSetpoint(now_us, t_s, sink);
    if (strain_.Due(k)) EmitStrain(now_us, sink);
    if (motor_.Due(k)) EmitMotor(now_us, sink);
    if (imu_.Due(k)) EmitImu(now_us, k1, sink);
    if (pose_.Due(k)) EmitPose(now_us, sink);
    if (loadcell_.Due(k)) EmitLoadCell(now_us, sink);
    if (truth_.Due(k)) EmitTruth(now_us, sink);
  }

  const double omega_before[kBirotorRotors] = {state_(kPlantOmega1), state_(kPlantOmega2)};
  state_ = Rk4StepFrom(state_, k1, dt, [this](const PlantState& x) { return Derivative(x); });
  for (int i = 0; i < kBirotorRotors; ++i)
    rotor_angle_rad_[i] = AdvanceRotorAngleRad(rotor_angle_rad_[i], omega_before[i], state_(kPlantOmega1 + i), dt);
  if (ground_.Touchdown(state_(kPlantQ + kZ))) {
    // Touchdown: an inelastic contact that levels the body (arms keep their state).
    state_(kPlantQ + kZ) = ground_.support_z_m();
    state_(kPlantQ + kPhi) = 0.0;
    for (int c : {kX, kZ, kPhi}) state_(kPlantV + c) = 0.0;
  }

  for (GaussMarkov& eta : turbulence_) eta.Advance(&turbulence_noise_);
  ++step_index_;
  return true;
}

void Simulator::Run(SampleSink* sink) {
  while (Step(sink)) {
  }
}

void Simulator::EmitStrain(int64_t utime, SampleSink* sink) {
  const double sigma = scenario_.sensors.strain_noise_rad;
  StrainSample sample;
  sample.utime = utime;
  sample.seq = strain_seq_++;
  const double t_s = static_cast<double>(utime - utime_offset_us_) * 1e-6;
  const double jitter_s = strain_jitter_noise_.Normal(scenario_.sensors.strain_stamp_jitter_s);
  for (int i = 0; i < kBirotorRotors; ++i) {
    const double b = JitteredDeflectionRad(state_(kPlantQ + kB1 + i), state_(kPlantV + kB1 + i), jitter_s);
    sample.deflection_rad[i] =
        GaugeReadingRad(scenario_.gauge, i, b, t_s, rotor_angle_rad_[i]) + strain_noise_.Normal(sigma);
  }
  strain_faults_.Process(sample, 2, sigma, InWindow(scenario_.faults.strain_gap, utime), &fault_noise_, &fault_events_,
                         [&](const StrainSample& out) {
                           sink->OnStrain(out);
                           ++emitted_.strain;
                         });
}

void Simulator::EmitMotor(int64_t utime, SampleSink* sink) {
  const SensorParams& sensors = scenario_.sensors;
  MotorSample sample;
  sample.utime = utime;
  sample.seq = motor_seq_++;
  const bool in_gap = InWindow(scenario_.faults.motor_telemetry_gap, utime);
  if (in_gap) RecordFault(FaultKind::kMotorTelemetryGap, utime, sample.seq, 0, kNaN);
  for (int i = 0; i < kBirotorRotors; ++i) {
    sample.omega_cmd_rad_s[i] = ClampCommand(vehicle_, command_.omega_cmd_rad_s[i]);
    sample.omega_meas_rad_s[i] =
        MeasureRotorSpeed(state_(kPlantOmega1 + i), sensors.motor_telemetry && !in_gap, sensors, &motor_noise_);
  }
  sink->OnMotor(sample);
  ++emitted_.motor;
}

void Simulator::EmitImu(int64_t utime, const PlantState& derivative, SampleSink* sink) {
  BodyMotion body;
  body.phi_rad = state_(kPlantQ + kPhi);
  body.phi_dot_rad_s = state_(kPlantV + kPhi);
  body.x_ddot_m_s2 = derivative(kPlantV + kX);
  body.z_ddot_m_s2 = derivative(kPlantV + kZ);
  ImuSample sample;
  sample.utime = utime;
  sample.seq = imu_seq_++;
  MeasureImu(body, vehicle_.gravity_m_s2, scenario_.sensors, &imu_noise_, &sample);
  sink->OnImu(sample);
  ++emitted_.imu;
}

void Simulator::EmitPose(int64_t utime, SampleSink* sink) {
  BodyMotion body;
  body.x_m = state_(kPlantQ + kX);
  body.z_m = state_(kPlantQ + kZ);
  body.phi_rad = state_(kPlantQ + kPhi);
  PoseSample sample;
  sample.utime = utime;
  sample.seq = pose_seq_++;
  MeasurePose(body, scenario_.sensors, &pose_noise_, &sample);
  sink->OnPose(sample);
  ++emitted_.pose;
}

void Simulator::EmitLoadCell(int64_t utime, SampleSink* sink) {
  LoadCellSample sample;
  sample.utime = utime;
  sample.seq = loadcell_seq_++;
  for (int i = 0; i < kBirotorRotors; ++i)
    sample.force_n[i] = TrueForce(i) + loadcell_noise_.Normal(scenario_.sensors.loadcell_noise_n);
  sink->OnLoadCell(sample);
  ++emitted_.loadcell;
}

void Simulator::EmitTruth(int64_t utime, SampleSink* sink) {
  TruthSample sample;
  sample.utime = utime;
  sample.x_m = state_(kPlantQ + kX);
  sample.z_m = state_(kPlantQ + kZ);
  sample.phi_rad = state_(kPlantQ + kPhi);
  sample.x_dot_m_s = state_(kPlantV + kX);
  sample.z_dot_m_s = state_(kPlantV + kZ);
  sample.phi_dot_rad_s = state_(kPlantV + kPhi);
  for (int i = 0; i < kBirotorRotors; ++i) {
    sample.deflection_rad[i] = state_(kPlantQ + kB1 + i);
    sample.deflection_dot_rad_s[i] = state_(kPlantV + kB1 + i);
    sample.omega_rad_s[i] = state_(kPlantOmega1 + i);
    sample.force_n[i] = TrueForce(i);
    sample.thrust_scale[i] = input_.thrust_scale[i];
  }
  sink->OnTruth(sample);
  ++emitted_.truth;
}

}  // namespace birotor
