#include "simulator/multi_arm_simulator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/rk4.h"
#include "simulator/flown_vehicle.h"
#include "simulator/gauge_model.h"
#include "simulator/sample_clock.h"

namespace birotor {
namespace {

static_assert(kMaxSampleArms == kMaxArms, "samples/multi_arm_samples.h holds every arm");

std::string Join(const std::vector<std::string>& problems) {
  std::ostringstream out;
  for (size_t i = 0; i < problems.size(); ++i) out << (i > 0 ? "; " : "") << problems[i];
  return out.str();
}

// The vehicle the scenario flies (FlownVehicle), after the checks.
VehicleDescription CheckedFlownVehicle(const VehicleDescription& description, const Scenario& scenario) {
  VehicleDescription flown = FlownVehicle(description, scenario.vehicle);
  const std::vector<std::string> problems = MultiArmScenarioProblems(flown, scenario);
  if (!problems.empty()) throw std::invalid_argument(Join(problems));
  return flown;
}

}  // namespace

std::vector<std::string> MultiArmScenarioProblems(const VehicleDescription& vehicle, const Scenario& scenario) {
  std::vector<std::string> problems = PlausibilityProblems(vehicle);
  const std::string where = "scenario '" + scenario.name + "' on vehicle '" + vehicle.name + "': ";
  if (scenario.arm_count != vehicle.arm_count) {
    problems.push_back(where + "its per-arm lists were loaded for " + std::to_string(scenario.arm_count) +
                       " arms, the vehicle has " + std::to_string(vehicle.arm_count) +
                       " (LoadScenario(file, overrides, arm_count))");
  }
  for (size_t k = 0; k < scenario.faults.thrust_steps.size(); ++k) {
    const int rotor = scenario.faults.thrust_steps[k].rotor;
    if (rotor < 1 || rotor > vehicle.arm_count) {
      problems.push_back(where + "faults.thrust_steps[" + std::to_string(k) + "].rotor = " + std::to_string(rotor) +
                         ": the vehicle has rotors 1 to " + std::to_string(vehicle.arm_count));
    }
  }
  return problems;
}

MultiArmSimulator::MultiArmSimulator(const VehicleDescription& vehicle, const Scenario& scenario)
    : vehicle_(CheckedFlownVehicle(vehicle, scenario)),
      scenario_(scenario),
      clamped_body_(scenario.mode == "bench"),
      step_us_(SecondsToUtime(scenario.step_s)),
      total_steps_(std::llround(scenario.duration_s / scenario.step_s)),
      control_every_steps_(StepsPerSample(scenario.controller.rate_hz, scenario.step_s)),
      hover_(SolveMultiArmHover(vehicle_)),
      trajectory_(scenario),
      autopilot_(vehicle_, scenario.controller, hover_),
      bench_(scenario.bench, scenario.seed, vehicle_.arm_count),
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
  if (!hover_.converged) throw std::invalid_argument("vehicle '" + vehicle_.name + "': no hover equilibrium");
  const int n_arms = vehicle_.arm_count;
  const FaultParams& faults = scenario_.faults;
  for (int i = 0; i < n_arms; ++i)
    efficiency_[static_cast<size_t>(i)] = faults.initial_thrust_scale[static_cast<size_t>(i)];
  for (const ThrustStep& step : faults.thrust_steps) {
    thrust_steps_.push_back({FirstSampleAtOrAfter(SecondsToUtime(step.time_s), step_us_), step.rotor - 1, step.scale});
  }
  std::stable_sort(thrust_steps_.begin(), thrust_steps_.end(),
                   [](const ScheduledStep& a, const ScheduledStep& b) { return a.step < b.step; });
  fault_events_.reserve(4096);
  const SensorParams& sensors = scenario_.sensors;
  strain_every_ = SensorEvery(sensors.strain);
  motor_every_ = SensorEvery(sensors.motor);
  imu_every_ = SensorEvery(sensors.imu);
  pose_every_ = SensorEvery(sensors.pose);
  loadcell_every_ = SensorEvery(sensors.loadcell);
  truth_every_ = SensorEvery(sensors.truth);
  rotor_angle_rad_ = scenario_.gauge.rotor_angle_rad;
  SetInitialState();
  for (int i = 0; i < n_arms; ++i) {
    turbulence_.emplace_back(vehicle_.turbulence_std, vehicle_.turbulence_corr_time_s, scenario_.step_s);
    turbulence_.back().Reset(&turbulence_noise_);
  }
}

void MultiArmSimulator::SetInitialState() {
  const VehicleDescription& v = vehicle_;
  if (!clamped_body_ && !ground_.enabled()) {
    state_ = MultiArmHoverPlantState(v, hover_);
    state_(MultiArmQIndex(v, kX)) = scenario_.start_position_m[0];
    state_(MultiArmQIndex(v, kZ)) = scenario_.start_position_m[1];
    return;
  }
  state_ = MultiArmPlantState::Zero(MultiArmPlantSize(v));
  if (!clamped_body_) {
    state_(MultiArmQIndex(v, kX)) = scenario_.start_position_m[0];
    state_(MultiArmQIndex(v, kZ)) = scenario_.start_position_m[1];
  }
  std::array<double, kMaxArms> first_command{};  // motors stopped on the ground
  if (clamped_body_) first_command = bench_.Speeds(0.0);
  for (int i = 0; i < v.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    const double omega = ClampCommand(v.omega_max_rad_s, first_command[arm]);
    const double force_n = RotorThrust(v.arms[arm].thrust_coeff_n_s2_rad2, omega, efficiency_[arm]);
    state_(MultiArmOmegaIndex(v, i)) = omega;
    state_(MultiArmQIndex(v, DeflectionIndex(i))) = MultiArmStaticDeflectionRad(v, i, force_n);
  }
}

double MultiArmSimulator::TrueForce(int arm) const {
  return RotorThrust(vehicle_.arms[static_cast<size_t>(arm)].thrust_coeff_n_s2_rad2,
                     state_(MultiArmOmegaIndex(vehicle_, arm)), input_.thrust_scale[static_cast<size_t>(arm)]);
}

int64_t MultiArmSimulator::SensorEvery(const SensorRate& rate) const {
  return rate.enabled ? StepsPerSample(rate.rate_hz, scenario_.step_s) : 0;
}

MultiArmPlantState MultiArmSimulator::Derivative(const MultiArmPlantState& x) const {
  // On the support the body is held level and still (x and z do not enter
  // the arm rows: a translated clamped body is the bench).
  return (clamped_body_ || ground_.on_ground()) ? MultiArmSupportedDerivative(vehicle_, x, input_)
                                                : MultiArmPlantDerivative(vehicle_, x, input_);
}

void MultiArmSimulator::UpdateCommand(double t_s) {
  double phase_omega_rad_s = 0.0;
  if (clamped_body_ || ground_.PhaseCommand(t_s, &phase_omega_rad_s)) {
    command_ = MultiArmRotorCommand();
    const std::array<double, kMaxArms>* bench = clamped_body_ ? &bench_.Speeds(t_s) : nullptr;
    for (int i = 0; i < vehicle_.arm_count; ++i) {
      const size_t arm = static_cast<size_t>(i);
      command_.omega_cmd_rad_s[arm] = bench != nullptr ? (*bench)[arm] : phase_omega_rad_s;
    }
    flying_external_ = false;
    return;
  }
  reference_ = ground_.FlightReference(t_s, trajectory_);
  if (external_commands_) {
    flying_external_ = true;
    command_ = MultiArmRotorCommand();
    command_.omega_cmd_rad_s = external_omega_rad_s_;
    return;
  }
  command_ = autopilot_.Update(state_, reference_);
}

void MultiArmSimulator::UseExternalCommands() {
  external_commands_ = true;
  for (int i = 0; i < vehicle_.arm_count; ++i)
    external_omega_rad_s_[static_cast<size_t>(i)] = state_(MultiArmOmegaIndex(vehicle_, i));
}

void MultiArmSimulator::OfferRotorCommands(const std::array<double, kMaxArms>& omega_cmd_rad_s) {
  external_omega_rad_s_ = omega_cmd_rad_s;
  if (flying_external_) command_.omega_cmd_rad_s = omega_cmd_rad_s;
}

bool MultiArmSimulator::Step(SampleSink* sink) {
  if (done()) return false;
  const int64_t k = step_index_;
  const int n_arms = vehicle_.arm_count;

  // Thrust efficiency steps take effect at the first step at or after their time.
  while (next_thrust_step_ < thrust_steps_.size() && thrust_steps_[next_thrust_step_].step <= k) {
    const ScheduledStep& step = thrust_steps_[next_thrust_step_++];
    efficiency_[static_cast<size_t>(step.rotor)] = step.scale;
    fault_events_.push_back(FaultEvent{FaultKind::kThrustStep, utime(), -1, step.rotor + 1, step.scale});
  }
  // mu_i = s_i (1 + eta_i), held over this step.
  for (int i = 0; i < n_arms; ++i) {
    const size_t arm = static_cast<size_t>(i);
    input_.thrust_scale[arm] = efficiency_[arm] * (1.0 + turbulence_[arm].value());
  }
  // Commands at the control rate, held (zero-order hold) in between.
  if (k % control_every_steps_ == 0) UpdateCommand(time_s());
  input_.omega_cmd_rad_s = command_.omega_cmd_rad_s;
  // Lift-off before the step: the support only pushes.
  ground_.UpdateLiftoff(
      utime(), [this] { return MultiArmPlantDerivative(vehicle_, state_, input_)(MultiArmVIndex(vehicle_, kZ)); });

  // RK4, keeping k1 = f(x_k, u_k) for the accelerometer.
  const MultiArmPlantState k1 = Derivative(state_);
  if (sink != nullptr) {
    const auto due = [k](int64_t every) { return every > 0 && k % every == 0; };
    if (due(strain_every_)) EmitStrain(sink);
    if (due(motor_every_)) EmitMotor(sink);
    if (due(imu_every_)) EmitImu(k1, sink);
    if (due(pose_every_)) EmitPose(sink);
    if (due(loadcell_every_)) EmitLoadCell(sink);
    if (due(truth_every_)) EmitTruth(sink);
  }
  std::array<double, kMaxArms> omega_before_rad_s{};
  for (int i = 0; i < n_arms; ++i) omega_before_rad_s[static_cast<size_t>(i)] = state_(MultiArmOmegaIndex(vehicle_, i));
  state_ = Rk4StepFrom(state_, k1, scenario_.step_s, [this](const MultiArmPlantState& x) { return Derivative(x); });
  AfterStep(omega_before_rad_s);
  for (GaussMarkov& eta : turbulence_) eta.Advance(&turbulence_noise_);
  ++step_index_;
  return true;
}

void MultiArmSimulator::AfterStep(const std::array<double, kMaxArms>& omega_before_rad_s) {
  const VehicleDescription& v = vehicle_;
  for (int i = 0; i < v.arm_count; ++i) {
    const size_t arm = static_cast<size_t>(i);
    rotor_angle_rad_[arm] = AdvanceRotorAngleRad(rotor_angle_rad_[arm], omega_before_rad_s[arm],
                                                 state_(MultiArmOmegaIndex(v, i)), scenario_.step_s);
  }
  if (ground_.Touchdown(state_(MultiArmQIndex(v, kZ)))) {
    // Touchdown: an inelastic contact that levels the body (arms keep their state).
    state_(MultiArmQIndex(v, kZ)) = ground_.support_z_m();
    state_(MultiArmQIndex(v, kPhi)) = 0.0;
    for (int c : {kX, kZ, kPhi}) state_(MultiArmVIndex(v, c)) = 0.0;
  }
}

void MultiArmSimulator::Run(SampleSink* sink) {
  while (Step(sink)) {
  }
}

}  // namespace birotor
