// Position references for the flight controller: sequences of quintic moves
// (zero velocity and acceleration at both ends, as in the thesis) built from a
// scenario's waypoints or from seeded random steps.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "controller/reference_point.h"
#include "simulator/scenario.h"

namespace birotor {

struct QuinticMove {
  double start_s = 0.0;
  double duration_s = 1.0;
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_m = Eigen::Vector2d::Zero();
};

// p(t) = from + (to - from) s(tau), tau = (t - start) / T in [0, 1],
// s = 10 tau^3 - 15 tau^4 + 6 tau^5.
ReferencePoint EvaluateQuintic(const QuinticMove& move, double t_s);

class Trajectory {
 public:
  // Builds the moves for the whole scenario (random steps drawn from its seed).
  explicit Trajectory(const Scenario& scenario);

  // Reference at t_s; before the first move and between moves it holds the
  // last target. Moves are sorted by start time and must not overlap.
  ReferencePoint At(double t_s) const;

  const std::vector<QuinticMove>& moves() const { return moves_; }

 private:
  Eigen::Vector2d start_m_;
  std::vector<QuinticMove> moves_;
};

}  // namespace birotor
