#include "simulator/multi_arm_simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "model/rk4.h"
#include "simulator/body_sensors.h"
#include "simulator/sample_clock.h"

namespace birotor {
namespace {

static_assert(kMaxSampleArms == kMaxArms, "samples/multi_arm_samples.h holds every arm");
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string Join(const std::vector<std::string>& problems) {
  std::ostringstream out;
  for (size_t i = 0; i < problems.size(); ++i) out << (i > 0 ? "; " : "") << problems[i];
  return out.str();
}

const VehicleDescription& CheckedVehicle(const VehicleDescription& vehicle, const Scenario& scenario) {
  const std::vector<std::string> problems = MultiArmScenarioProblems(vehicle, scenario);
  if (!problems.empty()) throw std::invalid_argument(Join(problems));
  return vehicle;
}

}  // namespace

std::vector<std::string> MultiArmScenarioProblems(const VehicleDescription& vehicle, const Scenario& scenario) {
  std::vector<std::string> problems = PlausibilityProblems(vehicle);
  const std::string where = "scenario '" + scenario.name + "' on vehicle '" + vehicle.name + "': ";
  if (scenario.mode != "flight")
    problems.push_back(where + "mode '" + scenario.mode + "' is not simulated for N arms (flight only)");
  if (scenario.ground.enabled)
    problems.push_back(where + "ground.enabled: the ground phase is not simulated for N arms (false only)");
  for (size_t k = 0; k < scenario.faults.thrust_steps.size(); ++k) {
    const int rotor = scenario.faults.thrust_steps[k].rotor;
    if (rotor < 1 || rotor > vehicle.arm_count) {
      problems.push_back(where + "faults.thrust_steps[" + std::to_string(k) + "].rotor = " + std::to_string(rotor) +
                         ": the vehicle has rotors 1 to " + std::to_string(vehicle.arm_count));
    }
  }
  const double* initial = scenario.faults.initial_thrust_scale.data();
  if (vehicle.arm_count != kBirotorArmCount && initial[0] != initial[1]) {
    std::ostringstream out;
    out << where << "faults.initial_thrust_scale [" << initial[0] << ", " << initial[1] << "]: with "
        << vehicle.arm_count << " rotors both entries must agree (every rotor takes it)";
    problems.push_back(out.str());
  }
  return problems;
}

MultiArmSimulator::MultiArmSimulator(const VehicleDescription& vehicle, const Scenario& scenario)
    : vehicle_(CheckedVehicle(vehicle, scenario)),
      scenario_(scenario),
      step_us_(SecondsToUtime(scenario.step_s)),
      total_steps_(std::llround(scenario.duration_s / scenario.step_s)),
      control_every_steps_(StepsPerSample(scenario.controller.rate_hz, scenario.step_s)),
      hover_(SolveMultiArmHover(vehicle)),
      trajectory_(scenario),
      autopilot_(vehicle, scenario.controller, hover_),
      turbulence_noise_(scenario.seed, kTurbulenceStream),
      strain_noise_(scenario.seed, kStrainStream),
      motor_noise_(scenario.seed, kMotorStream),
      imu_noise_(scenario.seed, kImuStream),
      pose_noise_(scenario.seed, kPoseStream) {
  if (!hover_.converged) throw std::invalid_argument("vehicle '" + vehicle.name + "': no hover equilibrium");
  const int n_arms = vehicle_.arm_count;
  const FaultParams& faults = scenario_.faults;
  for (int i = 0; i < n_arms; ++i)
    efficiency_[static_cast<size_t>(i)] = faults.initial_thrust_scale[std::min(i, kBirotorArmCount - 1)];
  for (const ThrustStep& step : faults.thrust_steps) {
    thrust_steps_.push_back({FirstSampleAtOrAfter(SecondsToUtime(step.time_s), step_us_), step.rotor - 1, step.scale});
  }
  std::stable_sort(thrust_steps_.begin(), thrust_steps_.end(),
                   [](const ScheduledStep& a, const ScheduledStep& b) { return a.step < b.step; });
  fault_events_.reserve(thrust_steps_.size());
  const SensorParams& sensors = scenario_.sensors;
  strain_every_ = SensorEvery(sensors.strain);
  motor_every_ = SensorEvery(sensors.motor);
  imu_every_ = SensorEvery(sensors.imu);
  pose_every_ = SensorEvery(sensors.pose);
  truth_every_ = SensorEvery(sensors.truth);

  // The exact hover equilibrium at the start position.
  state_ = MultiArmHoverPlantState(vehicle_, hover_);
  state_(MultiArmQIndex(vehicle_, kX)) = scenario_.start_position_m[0];
  state_(MultiArmQIndex(vehicle_, kZ)) = scenario_.start_position_m[1];
  for (int i = 0; i < n_arms; ++i) {
    turbulence_.emplace_back(vehicle_.turbulence_std, vehicle_.turbulence_corr_time_s, scenario_.step_s);
    turbulence_.back().Reset(&turbulence_noise_);
  }
}

double MultiArmSimulator::TrueForce(int arm) const {
  return RotorThrust(vehicle_.arms[static_cast<size_t>(arm)].thrust_coeff_n_s2_rad2,
                     state_(MultiArmOmegaIndex(vehicle_, arm)), input_.thrust_scale[static_cast<size_t>(arm)]);
}

int64_t MultiArmSimulator::SensorEvery(const SensorRate& rate) const {
  return rate.enabled ? StepsPerSample(rate.rate_hz, scenario_.step_s) : 0;
}

bool MultiArmSimulator::Step(SampleSink* sink) {
  if (done()) return false;
  const int64_t k = step_index_;
  const int n_arms = vehicle_.arm_count;

  // Thrust efficiency steps take effect at the first step at or after their time.
  while (next_thrust_step_ < thrust_steps_.size() && thrust_steps_[next_thrust_step_].step <= k) {
    const ScheduledStep& step = thrust_steps_[next_thrust_step_++];
    efficiency_[static_cast<size_t>(step.rotor)] = step.scale;
    FaultEvent event;
    event.utime = utime();
    event.rotor = step.rotor + 1;
    event.value = step.scale;
    fault_events_.push_back(event);
  }
  // mu_i = s_i (1 + eta_i), held over this step.
  for (int i = 0; i < n_arms; ++i) {
    const size_t arm = static_cast<size_t>(i);
    input_.thrust_scale[arm] = efficiency_[arm] * (1.0 + turbulence_[arm].value());
  }
  // Autopilot at its own rate; commands held (zero-order hold) in between.
  if (k % control_every_steps_ == 0) {
    reference_ = trajectory_.At(time_s());
    command_ = autopilot_.Update(state_, reference_);
  }
  input_.omega_cmd_rad_s = command_.omega_cmd_rad_s;

  // RK4, keeping k1 = f(x_k, u_k) for the accelerometer.
  const auto derivative = [this](const MultiArmPlantState& x) { return MultiArmPlantDerivative(vehicle_, x, input_); };
  const MultiArmPlantState k1 = derivative(state_);
  if (sink != nullptr) {
    const auto due = [k](int64_t every) { return every > 0 && k % every == 0; };
    if (due(strain_every_)) EmitStrain(sink);
    if (due(motor_every_)) EmitMotor(sink);
    if (due(imu_every_)) EmitImu(k1, sink);
    if (due(pose_every_)) EmitPose(sink);
    if (due(truth_every_)) EmitTruth(sink);
  }
  state_ = Rk4StepFrom(state_, k1, scenario_.step_s, derivative);
  for (GaussMarkov& eta : turbulence_) eta.Advance(&turbulence_noise_);
  ++step_index_;
  return true;
}

void MultiArmSimulator::Run(SampleSink* sink) {
  while (Step(sink)) {
  }
}

// b_meas_i = b_i + n_i on the arms with a gauge, NaN on the others.
void MultiArmSimulator::EmitStrain(SampleSink* sink) {
  MultiArmStrainSample sample;
  sample.utime = utime();
  sample.seq = strain_seq_++;
  sample.n_arms = vehicle_.arm_count;
  for (int i = 0; i < vehicle_.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    sample.deflection_rad[arm] = vehicle_.arms[arm].has_gauge
                                     ? state_(MultiArmQIndex(vehicle_, DeflectionIndex(i))) +
                                           strain_noise_.Normal(scenario_.sensors.strain_noise_rad)
                                     : kNaN;
  }
  sink->OnStrainN(sample);
  ++emitted_.strain;
}

void MultiArmSimulator::EmitMotor(SampleSink* sink) {
  const SensorParams& sensors = scenario_.sensors;
  MultiArmMotorSample sample;
  sample.utime = utime();
  sample.seq = motor_seq_++;
  sample.n_rotors = vehicle_.arm_count;
  for (int i = 0; i < vehicle_.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    sample.omega_cmd_rad_s[arm] = input_.omega_cmd_rad_s[arm];
    sample.omega_meas_rad_s[arm] = sensors.motor_telemetry ? state_(MultiArmOmegaIndex(vehicle_, i)) +
                                                                 motor_noise_.Normal(sensors.motor_speed_noise_rad_s)
                                                           : kNaN;
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
