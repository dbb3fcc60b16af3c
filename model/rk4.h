// The one classical fourth-order Runge-Kutta step of the project: the plant
// (model/plant.h), the EKF prediction, the simulator and identification's arm
// models on Ceres Jets all integrate with it.
//   k1 = f(x, start), k2 = f(x + dt/2 k1, middle), k3 = f(x + dt/2 k2, middle),
//   k4 = f(x + dt k3, end),  x+ = x + dt/6 (k1 + 2 k2 + 2 k3 + k4).
// f is f(x) when the input is held over the step, or f(x, stage) when it
// varies within it (identification interpolates the measured forces).
#pragma once

#include <type_traits>

namespace birotor {

// Where in the step a stage's derivative is evaluated: t, t + dt/2, t + dt.
enum class Rk4Stage { kStart, kMiddle, kEnd };

namespace rk4_internal {
template <typename State, typename Derivative>
State Evaluate(const Derivative& f, const State& x, Rk4Stage stage) {
  if constexpr (std::is_invocable_v<const Derivative&, const State&, Rk4Stage>) {
    return f(x, stage);
  } else {
    return f(x);
  }
}
}  // namespace rk4_internal

// One step from x over dt_s [s] when k1 = f(x, start) is already known (the
// simulator keeps it for the accelerometer).
template <typename State, typename Derivative>
State Rk4StepFrom(const State& x, const State& k1, double dt_s, const Derivative& f) {
  const State k2 = rk4_internal::Evaluate<State>(f, State(x + (0.5 * dt_s) * k1), Rk4Stage::kMiddle);
  const State k3 = rk4_internal::Evaluate<State>(f, State(x + (0.5 * dt_s) * k2), Rk4Stage::kMiddle);
  const State k4 = rk4_internal::Evaluate<State>(f, State(x + dt_s * k3), Rk4Stage::kEnd);
  return x + (dt_s / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

// One step of x_dot = f(x) (or f(x, stage)) from x over dt_s [s].
template <typename State, typename Derivative>
State Rk4Step(const State& x, double dt_s, const Derivative& f) {
  return Rk4StepFrom(x, rk4_internal::Evaluate<State>(f, x, Rk4Stage::kStart), dt_s, f);
}

}  // namespace birotor
