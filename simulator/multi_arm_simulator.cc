#include "simulator/multi_arm_simulator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "model/rk4.h"
#include "simulator/sample_clock.h"

namespace birotor {
namespace {

// The birotor simulator's turbulence stream of the seed (simulator.cc), so
// both draw their turbulence from the same independent stream.
constexpr uint64_t kTurbulenceStream = 1;

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
  const double* initial = scenario.faults.initial_thrust_scale;
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
      control_every_steps_(std::max<int64_t>(1, std::llround(1.0 / (scenario.controller.rate_hz * scenario.step_s)))),
      hover_(SolveMultiArmHover(vehicle)),
      trajectory_(scenario),
      autopilot_(vehicle, scenario.controller, hover_),
      turbulence_noise_(scenario.seed, kTurbulenceStream) {
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

bool MultiArmSimulator::Step() {
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

  state_ = StepMultiArmPlant(vehicle_, state_, input_, scenario_.step_s);
  for (GaussMarkov& eta : turbulence_) eta.Advance(&turbulence_noise_);
  ++step_index_;
  return true;
}

void MultiArmSimulator::Run() {
  while (Step()) {
  }
}

}  // namespace birotor
