#include "simulator/simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/bench_dynamics.h"
#include "model/rk4.h"
#include "simulator/body_sensors.h"
#include "simulator/sample_clock.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

Simulator::Simulator(const Scenario& scenario)
    : scenario_(scenario),
      clamped_body_(scenario.mode == "bench"),
      step_us_(SecondsToUtime(scenario.step_s)),
      total_steps_(std::llround(scenario.duration_s / scenario.step_s)),
      equilibrium_(SolveHoverEquilibrium(scenario.vehicle)),
      trajectory_(scenario),
      controller_(scenario.vehicle, scenario.controller, 0.5 * (equilibrium_.force_n[0] + equilibrium_.force_n[1])),
      bench_(scenario.bench, scenario.seed),
      turbulence_{
          GaussMarkov(scenario.vehicle.turbulence_std, scenario.vehicle.turbulence_corr_time_s, scenario.step_s),
          GaussMarkov(scenario.vehicle.turbulence_std, scenario.vehicle.turbulence_corr_time_s, scenario.step_s)},
      turbulence_noise_(scenario.seed, kTurbulenceStream),
      strain_noise_(scenario.seed, kStrainStream),
      motor_noise_(scenario.seed, kMotorStream),
      imu_noise_(scenario.seed, kImuStream),
      pose_noise_(scenario.seed, kPoseStream),
      loadcell_noise_(scenario.seed, kLoadCellStream),
      fault_noise_(scenario.seed, kFaultStream) {
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
  for (int i = 0; i < 2; ++i) efficiency_[i] = faults.initial_thrust_scale[i];
  for (const ThrustStep& step : faults.thrust_steps) {
    const int64_t index = FirstSampleAtOrAfter(SecondsToUtime(step.time_s), step_us_);
    thrust_steps_.push_back({index, step.rotor - 1, step.scale});
  }
  std::stable_sort(thrust_steps_.begin(), thrust_steps_.end(),
                   [](const ScheduledStep& a, const ScheduledStep& b) { return a.step < b.step; });
  const int64_t strain_period_us = strain_.every_steps * step_us_;
  for (double t : faults.strain_nan_times_s)
    strain_nan_seq_.push_back(FirstSampleAtOrAfter(SecondsToUtime(t), strain_period_us));
  for (double t : faults.strain_out_of_order_times_s)
    strain_swap_seq_.push_back(FirstSampleAtOrAfter(SecondsToUtime(t), strain_period_us));
  std::sort(strain_nan_seq_.begin(), strain_nan_seq_.end());
  std::sort(strain_swap_seq_.begin(), strain_swap_seq_.end());
  fault_events_.reserve(4096);

  // Initial state: the exact hover equilibrium at the start position (flight),
  // at rest on the ground with the motors stopped (ground phase), or the
  // static arm deflection under the first bench command (bench).
  const VehicleParams& p = scenario_.vehicle;
  state_.setZero();
  for (int i = 0; i < 2; ++i) rotor_angle_rad_[i] = scenario_.gauge.rotor_angle_rad[i];
  const GroundParams& ground = scenario_.ground;
  if (ground.enabled) {
    on_ground_ = true;
    ground_z_m_ = scenario_.start_position_m[1];
    if (ground.land) {
      disarm_s_ = scenario_.duration_s - ground.rest_after_s;
      land_start_s_ = disarm_s_ - ground.landing_duration_s;
    }
  }
  if (clamped_body_ || ground.enabled) {
    command_ = clamped_body_ ? bench_.At(0.0) : RotorCommand();
    if (!clamped_body_) {
      state_(kPlantQ + kX) = scenario_.start_position_m[0];
      state_(kPlantQ + kZ) = scenario_.start_position_m[1];
    }
    for (int i = 0; i < 2; ++i) {
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
  return (clamped_body_ || on_ground_) ? ClampedBodyDerivative(scenario_.vehicle, x, input_)
                                       : PlantDerivative(scenario_.vehicle, x, input_);
}

RotorCommand Simulator::Command(double t_s) {
  if (clamped_body_) return bench_.At(t_s);
  const GroundParams& ground = scenario_.ground;
  RotorCommand command;
  if (ground.enabled) {
    if (t_s < ground.rest_s || (ground.land && t_s >= disarm_s_)) return command;  // stopped: 0 rad/s
    if (t_s < ground.FlightStartS()) {
      const double ramp = ground.spool_up_s > 0 ? (t_s - ground.rest_s) / ground.spool_up_s : 1.0;
      command.omega_cmd_rad_s[0] = command.omega_cmd_rad_s[1] = ground.idle_rad_s * ramp;
      return command;
    }
  }
  const double flight_s = t_s - ground.FlightStartS();
  if (external_commands_) {
    reference_ = trajectory_.At(flight_s);
    if (last_external_utime_ < 0) {
      // Before the first command the ESCs run the speeds of the start state
      // (hover), for at most the timeout.
      last_external_utime_ = utime();
      for (int i = 0; i < 2; ++i) external_command_.omega_cmd_rad_s[i] = state_(kPlantOmega1 + i);
    }
    const bool timed_out = utime() - last_external_utime_ > command_timeout_us_;
    if (timed_out && !command_timed_out_) ++command_timeouts_;
    command_timed_out_ = timed_out;
    return timed_out ? RotorCommand() : external_command_;
  }
  if (ground.enabled && ground.land && t_s >= land_start_s_) {
    if (!landing_planned_) {
      // Vertical descent from where the reference is to the support height.
      const ReferencePoint from = trajectory_.At(flight_s);
      landing_.start_s = land_start_s_;
      landing_.duration_s = ground.landing_duration_s;
      landing_.from_m = from.position_m;
      landing_.to_m = Eigen::Vector2d(from.position_m.x(), ground_z_m_);
      landing_planned_ = true;
    }
    reference_ = EvaluateQuintic(landing_, t_s);
  } else {
    reference_ = trajectory_.At(flight_s);
  }
  return controller_.Update(state_, reference_);
}

void Simulator::UseExternalCommands(double command_timeout_s) {
  external_commands_ = true;
  command_timeout_us_ = SecondsToUtime(command_timeout_s);
  SeqStreamLockParams lock;
  lock.silence_s = command_timeout_s;
  commander_ = SeqStreamLock(lock);
}

EscVerdict Simulator::OfferMotorCommand(int32_t seq, int64_t utime, const double (&omega_cmd_rad_s)[2]) {
  EscCounters& n = esc_counters_;
  ++n.received;
  const int64_t now_us = this->utime();
  if (utime > now_us + SecondsToUtime(kEscFutureWindowS)) {
    ++n.future;
    return EscVerdict::kFuture;
  }
  if (utime < now_us - command_timeout_us_ || (newest_command_utime_ >= 0 && utime <= newest_command_utime_)) {
    ++n.stale;
    return EscVerdict::kStale;
  }
  for (double omega : omega_cmd_rad_s) {
    if (!(omega >= 0.0 && omega <= scenario_.vehicle.omega_max_rad_s)) {
      ++n.out_of_range;
      return EscVerdict::kOutOfRange;
    }
  }
  const SeqStreamLock::Verdict verdict = commander_.Admit(seq, now_us);
  if (verdict == SeqStreamLock::Verdict::kForeign) {
    ++n.foreign;
    return EscVerdict::kForeign;
  }
  if (verdict == SeqStreamLock::Verdict::kDuplicate) {
    ++n.stale;
    return EscVerdict::kStale;
  }
  ++n.accepted;
  for (int i = 0; i < 2; ++i) external_command_.omega_cmd_rad_s[i] = omega_cmd_rad_s[i];
  newest_command_utime_ = utime;
  last_external_utime_ = now_us;
  return EscVerdict::kAccepted;
}

void Simulator::EmitSetpoints(double rate_hz) {
  setpoint_.enabled = true;
  setpoint_.every_steps = std::max<int64_t>(1, std::llround(1.0 / (rate_hz * scenario_.step_s)));
}

void Simulator::EmitSetpoint(int64_t utime, double t_s, SampleSink* sink) {
  sink->OnSetpoint(SetpointFromReference(ReferenceAt(t_s), utime, setpoint_seq_++));
}

void Simulator::UpdateGroundContact(int64_t now_us) {
  if (!on_ground_) return;
  // The support only pushes: the body leaves it when the free body would
  // accelerate upwards (thrust above the weight).
  if (PlantDerivative(scenario_.vehicle, state_, input_)(kPlantV + kZ) > 0.0) {
    on_ground_ = false;
    if (liftoff_utime_ < 0) liftoff_utime_ = now_us;
  }
}

double Simulator::GaugeOffsetRad(int gauge, double t_s) const {
  const GaugeParams& g = scenario_.gauge;
  const double drift_s = std::clamp(t_s - g.drift_window.start_s, 0.0, g.drift_window.duration_s);
  return g.offset_rad[gauge] + g.drift_rad_s[gauge] * drift_s;
}

double Simulator::TrueForce(int rotor) const {
  return RotorThrust(scenario_.vehicle, state_(kPlantOmega1 + rotor), input_.thrust_scale[rotor]);
}

bool Simulator::InWindow(const TimeWindow& window, int64_t t_us) const {
  const int64_t start_us = utime_offset_us_ + SecondsToUtime(window.start_s);
  return window.duration_s > 0.0 && t_us >= start_us && t_us < start_us + SecondsToUtime(window.duration_s);
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
  for (int i = 0; i < 2; ++i) input_.thrust_scale[i] = efficiency_[i] * (1.0 + turbulence_[i].value());

  // Controller (or bench profile) at its own rate; commands are held (ZOH).
  // External commands reach the ESCs at the step they arrive.
  if (control_.Due(k) || external_commands_) command_ = Command(t_s);
  input_.omega_cmd_rad_s[0] = command_.omega_cmd_rad_s[0];
  input_.omega_cmd_rad_s[1] = command_.omega_cmd_rad_s[1];
  UpdateGroundContact(now_us);

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

  const double omega_before[2] = {state_(kPlantOmega1), state_(kPlantOmega2)};
  state_ = Rk4StepFrom(state_, k1, dt, [this](const PlantState& x) { return Derivative(x); });
  for (int i = 0; i < 2; ++i) {
    // Trapezoidal rotor angle, kept in [0, 2 pi) so its precision does not decay.
    const double angle = rotor_angle_rad_[i] + 0.5 * dt * (omega_before[i] + state_(kPlantOmega1 + i));
    rotor_angle_rad_[i] = angle - 2.0 * M_PI * std::floor(angle / (2.0 * M_PI));
  }
  if (scenario_.ground.enabled && !on_ground_ && state_(kPlantQ + kZ) <= ground_z_m_) {
    // Touchdown: an inelastic contact that levels the body (arms keep their state).
    on_ground_ = true;
    state_(kPlantQ + kZ) = ground_z_m_;
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
  const FaultParams& faults = scenario_.faults;
  const double sigma = scenario_.sensors.strain_noise_rad;
  const int32_t seq = strain_seq_++;
  StrainSample sample;
  sample.utime = utime;
  sample.seq = seq;
  const GaugeParams& gauge = scenario_.gauge;
  const double t_s = static_cast<double>(utime - utime_offset_us_) * 1e-6;
  for (int i = 0; i < 2; ++i) {
    // b_meas = s b + o(t) + v(t) + n (scenario.h); exactly b + n for the ideal gauge.
    double reading = gauge.scale[i] * state_(kPlantQ + kB1 + i) + GaugeOffsetRad(i, t_s);
    if (gauge.harmonic_1x_rad[i] != 0.0 || gauge.harmonic_2x_rad[i] != 0.0) {
      const double theta = rotor_angle_rad_[i];
      reading += gauge.harmonic_1x_rad[i] * std::sin(theta) +
                 gauge.harmonic_2x_rad[i] * std::sin(2.0 * theta + gauge.harmonic_2x_phase_rad[i]);
    }
    sample.deflection_rad[i] = reading + strain_noise_.Normal(sigma);
  }

  // Fault draws happen for every sample so the fault pattern does not depend
  // on which other faults are configured.
  const double spike_draw = fault_noise_.Uniform();
  const double spike_shape = fault_noise_.Uniform();
  const bool in_gap = InWindow(faults.strain_gap, utime);
  const bool is_nan = std::binary_search(strain_nan_seq_.begin(), strain_nan_seq_.end(), seq);
  if (in_gap) {
    RecordFault(FaultKind::kStrainGap, utime, seq, 0, 0.0);
  } else if (is_nan) {
    sample.deflection_rad[0] = sample.deflection_rad[1] = kNaN;
    RecordFault(FaultKind::kStrainNan, utime, seq, 0, kNaN);
  } else if (spike_draw < faults.strain_spike_probability) {
    // One arm (first half of spike_shape: arm 1), sign from the rest.
    const int arm = spike_shape < 0.5 ? 0 : 1;
    const double sign = std::fmod(spike_shape * 4.0, 2.0) < 1.0 ? 1.0 : -1.0;
    const double spike = sign * faults.strain_spike_sigmas * sigma;
    sample.deflection_rad[arm] += spike;
    RecordFault(FaultKind::kStrainSpike, utime, seq, arm + 1, spike);
  }
  if (in_gap) {
    // Not emitted; a sample held for swapping still goes out.
  } else if (std::binary_search(strain_swap_seq_.begin(), strain_swap_seq_.end(), seq)) {
    RecordFault(FaultKind::kStrainOutOfOrder, utime, seq, 0, 0.0);
    held_strain_ = sample;
    has_held_strain_ = true;
    return;
  } else {
    sink->OnStrain(sample);
    ++emitted_.strain;
  }
  if (has_held_strain_) {
    sink->OnStrain(held_strain_);
    ++emitted_.strain;
    has_held_strain_ = false;
  }
}

void Simulator::EmitMotor(int64_t utime, SampleSink* sink) {
  const SensorParams& sensors = scenario_.sensors;
  MotorSample sample;
  sample.utime = utime;
  sample.seq = motor_seq_++;
  const bool in_gap = InWindow(scenario_.faults.motor_telemetry_gap, utime);
  if (in_gap) RecordFault(FaultKind::kMotorTelemetryGap, utime, sample.seq, 0, kNaN);
  for (int i = 0; i < 2; ++i) {
    sample.omega_cmd_rad_s[i] = ClampCommand(scenario_.vehicle, command_.omega_cmd_rad_s[i]);
    const double noise = motor_noise_.Normal(sensors.motor_speed_noise_rad_s);
    // An ESC reports no negative speed (near 0 while the motors are stopped).
    sample.omega_meas_rad_s[i] =
        (sensors.motor_telemetry && !in_gap) ? std::max(0.0, state_(kPlantOmega1 + i) + noise) : kNaN;
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
  MeasureImu(body, scenario_.vehicle.gravity_m_s2, scenario_.sensors, &imu_noise_, &sample);
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
  for (int i = 0; i < 2; ++i)
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
  for (int i = 0; i < 2; ++i) {
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
