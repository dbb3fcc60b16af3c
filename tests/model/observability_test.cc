// Observability and controllability of the augmented hover model (thesis ch. 4, 6).
#include "model/observability.h"

#include <gtest/gtest.h>

#include "model/linearization.h"

namespace birotor {
namespace {

SubspaceReport Observe(const std::vector<std::string>& measured) {
  const BirotorParams p;
  const AugMatrix a = AugmentWithForces(LinearizeAtHover(p));
  Eigen::MatrixXd c;
  std::string unknown;
  EXPECT_TRUE(SelectionMatrix(AugmentedStateNames(), measured, &c, &unknown)) << unknown;
  return AnalyzeObservability(a, c, AugmentedStateNames());
}

TEST(Observability, DeflectionsOnlyGiveRankSix) {
  const SubspaceReport r = Observe({"b1", "b2"});
  EXPECT_EQ(r.rank, 6);
  EXPECT_EQ(r.hidden_states, (std::vector<std::string>{"x", "z", "phi", "x_dot", "z_dot", "phi_dot"}));
}

TEST(Observability, PositionGivesFullRank) { EXPECT_EQ(Observe({"x", "z"}).rank, 12); }

TEST(Observability, AllMechanicalStatesGiveFullRank) {
  EXPECT_EQ(Observe({"x", "z", "phi", "b1", "b2", "x_dot", "z_dot", "phi_dot", "b1_dot", "b2_dot"}).rank, 12);
}

TEST(Controllability, ForcesControlAllTenMechanicalStates) {
  const BirotorParams p;
  const LinearModel lin = LinearizeAtHover(p);
  std::vector<std::string> names(AugmentedStateNames().begin(), AugmentedStateNames().begin() + 10);
  const SubspaceReport r = AnalyzeControllability(lin.a, lin.b, names);
  EXPECT_EQ(r.rank, 10);
}

}  // namespace
}  // namespace birotor
