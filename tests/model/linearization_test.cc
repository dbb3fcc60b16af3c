// Linearization at hover against thesis eq. 3.33-3.34 and the spec's numbers.
#include "model/linearization.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

// Index of a state in the 10-state [q; v] vector.
constexpr int Pos(int coordinate) { return coordinate; }
constexpr int Vel(int coordinate) { return kNumCoordinates + coordinate; }

// Thesis eq. 3.33-3.34 (d = 0) in sum/difference coordinates.
LinearModel ThesisModel(const BirotorParams& p) {
  const double m = p.body_mass_kg, mp = p.tip_mass_kg, L = p.arm_length_m, J = p.body_inertia_kg_m2,
               k = p.arm_stiffness_n_m_rad, g = p.gravity_m_s2;
  LinearModel t;
  t.a.setZero();
  t.b.setZero();
  t.a.topRightCorner<5, 5>().setIdentity();
  // Coordinates in sum/difference form: kB1 slot holds b_s, kB2 slot holds b_d.
  t.a(Vel(kX), Pos(kPhi)) = -g;
  t.a(Vel(kX), Pos(kB1)) = -g * (m + mp) / (m + 2 * mp);
  t.a(Vel(kZ), Pos(kB2)) = -k / (L * m);
  t.a(Vel(kPhi), Pos(kB1)) = k / J;
  t.a(Vel(kB1), Pos(kB1)) = -k * (2 * mp * L * L + J) / (J * L * L * mp);
  t.a(Vel(kB2), Pos(kB2)) = -k * (m + 2 * mp) / (L * L * m * mp);
  t.b(Vel(kB1), 0) = -1.0 / (L * mp);
  t.b(Vel(kB1), 1) = 1.0 / (L * mp);
  t.b(Vel(kB2), 0) = -1.0 / (L * mp);
  t.b(Vel(kB2), 1) = -1.0 / (L * mp);
  return t;
}

// Relative error of each entry, against the larger of the entry and 1e-6 of its row's scale.
double WorstRelativeError(const MechMatrix& ours, const MechMatrix& thesis, MechMatrix::Index* row,
                          MechMatrix::Index* col) {
  double worst = 0;
  for (int i = 0; i < kMechStateSize; ++i) {
    const double row_scale = std::max(1.0, thesis.row(i).cwiseAbs().maxCoeff());
    for (int j = 0; j < kMechStateSize; ++j) {
      const double err = std::abs(ours(i, j) - thesis(i, j)) / std::max(std::abs(thesis(i, j)), row_scale);
      if (err > worst) {
        worst = err;
        *row = i;
        *col = j;
      }
    }
  }
  return worst;
}

// At the exact equilibrium two entries differ from the thesis by O(b0^2)
// (b0 = 1.87e-3 rad): z/b_d by 6.7e-6 and b_d/b_d by 1.5e-6 relative, from
// cos(b1 - b2) factors that the thesis's small-angle simplification drops.
// Every other entry agrees to 1e-6.
double ThesisError(const BirotorParams& p, MechMatrix::Index* r, MechMatrix::Index* c) {
  const LinearModel ours = ToSumDifferenceCoordinates(LinearizeAtHover(p));
  const LinearModel thesis = ThesisModel(p);
  for (int i = 0; i < kMechStateSize; ++i)
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(ours.b(i, j), thesis.b(i, j), 1e-6 * std::max(1.0, std::abs(thesis.b(i, j)))) << i << "," << j;
  return WorstRelativeError(ours.a, thesis.a, r, c);
}

TEST(Linearization, MatchesThesisTermByTerm) {
  BirotorParams p;
  p.arm_damping_n_m_s_rad = 0.0;
  MechMatrix::Index r = 0, c = 0;
  EXPECT_LT(ThesisError(p, &r, &c), 1e-5) << "worst entry A(" << r << "," << c << ")";
}

TEST(Linearization, DifferenceFromThesisIsTheSmallAngleTerm) {
  // Stiffer arms shrink b0 a hundredfold; the O(b0^2) difference falls 1e4-fold.
  BirotorParams p;
  p.arm_damping_n_m_s_rad = 0.0;
  p.arm_stiffness_n_m_rad *= 100.0;
  MechMatrix::Index r = 0, c = 0;
  EXPECT_LT(ThesisError(p, &r, &c), 1e-8) << "worst entry A(" << r << "," << c << ")";
}

TEST(Linearization, SpecNumbers) {
  BirotorParams p;
  p.arm_damping_n_m_s_rad = 0.0;
  const LinearModel lin = LinearizeAtHover(p);
  EXPECT_NEAR(lin.b(Vel(kB1), 0), -13.883, 1e-3);
  EXPECT_NEAR(lin.a(Vel(kB1), Pos(kB1)) / -2.0901e5, 1.0, 1e-4);
  EXPECT_NEAR(lin.a(Vel(kB1), Pos(kB2)) / -4.2048e4, 1.0, 1e-4);
  EXPECT_NEAR(lin.a(Vel(kPhi), Pos(kB1)) / 5.256e4, 1.0, 1e-3);
  EXPECT_NEAR(lin.a(Vel(kPhi), Pos(kB2)) / 5.256e4, 1.0, 1e-3);
}

TEST(Linearization, ArmModesWithDamping) {
  const BirotorParams p;
  const std::vector<Mode> modes = OscillatoryModes(LinearizeAtHover(p).a);
  ASSERT_EQ(modes.size(), 2u);
  EXPECT_NEAR(modes[0].frequency_hz, 65.03, 0.01);
  EXPECT_NEAR(modes[0].damping_ratio, 0.019, 0.0005);
  EXPECT_NEAR(modes[1].frequency_hz, 79.75, 0.01);
  EXPECT_NEAR(modes[1].damping_ratio, 0.024, 0.0005);
}

}  // namespace
}  // namespace birotor
