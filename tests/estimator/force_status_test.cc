// The one composer of FORCE's status (estimator/force_status.h): each fact to
// its bits, and which facts withdraw VALID, as lcmtypes/force_estimate_t.lcm
// states them (and as the rooms set them before the composer: the published
// bits did not change, tests/replay/ekf_regression_trace_test.cc).
#include "estimator/force_status.h"

#include <gtest/gtest.h>

#include <cmath>

namespace birotor {
namespace {

ForceStatusFacts Converged() {
  ForceStatusFacts facts;
  facts.filter.convergence = FilterConvergence::kConverged;
  return facts;
}

// A converged filter that sees both rotors below the thrust map.
ForceStatusFacts ConvergedWithDeficit() {
  ForceStatusFacts facts = Converged();
  facts.filter.thrust_deficit = true;
  return facts;
}

TEST(ForceStatusTest, NoFactsNoBits) {
  // ESTIMATOR_STATUS before the first FORCE reads 0.
  EXPECT_EQ(ComposeForceStatus(ForceStatusFacts()), 0);
}

TEST(ForceStatusTest, EachFilterFactSetsItsBit) {
  ForceStatusFacts facts;
  facts.filter.convergence = FilterConvergence::kConverging;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusConverging);
  facts = Converged();
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid);
  facts.filter.measurement_rejected = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusMeasurementRejected);
  facts = Converged();
  facts.filter.rotor_fault[0] = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusRotor1Fault);
  facts = Converged();
  facts.filter.rotor_fault[1] = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusRotor2Fault);
  // A rotor fault and the deficit leave VALID standing.
  facts = ConvergedWithDeficit();
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusThrustDeficit);
}

TEST(ForceStatusTest, EachInputFactSetsItsBitAndStaleAndConflictWithdrawValid) {
  ForceStatusFacts facts = Converged();
  facts.input.no_motor_input = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusNoMotorInput);
  facts = Converged();
  facts.input.filter_reset = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusFilterReset);
  facts = Converged();
  facts.input.stale = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusInputStale);
  facts = Converged();
  facts.input.conflict = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusInputConflict);
  // Converging: the input bits stand beside CONVERGING.
  facts = ForceStatusFacts();
  facts.filter.convergence = FilterConvergence::kConverging;
  facts.input.stale = facts.input.no_motor_input = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusConverging | kStatusInputStale | kStatusNoMotorInput);
}

TEST(ForceStatusTest, AReplacedNonFiniteEstimateVoidsTheFilterFacts) {
  ForceStatusFacts facts = Converged();
  facts.filter.measurement_rejected = facts.filter.thrust_deficit = true;
  facts.filter.rotor_fault[0] = facts.filter.rotor_fault[1] = true;
  facts.input.non_finite_replaced = facts.input.filter_reset = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusConverging | kStatusFilterReset);
}

TEST(ForceStatusTest, AMismatchWithdrawsValidAndTheDeficit) {
  ForceStatusFacts facts = ConvergedWithDeficit();
  facts.filter.rotor_fault[1] = true;
  facts.consistency.mismatch = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusModelMismatch | kStatusRotor2Fault);
}

TEST(ForceStatusTest, AnUnconfirmedModelWithdrawsTheDeficitAndValidOnlyByOption) {
  ForceStatusFacts facts = ConvergedWithDeficit();
  facts.consistency.model_unconfirmed = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid);  // default: the controller does not wait
  facts.consistency.unconfirmed_withholds_valid = true;
  EXPECT_EQ(ComposeForceStatus(facts), 0);
  // The option alone, the model confirmed: nothing withdrawn.
  facts.consistency.model_unconfirmed = false;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusThrustDeficit);
}

TEST(ForceStatusTest, AnUnconfirmedTipMassWithdrawsValidOnlyByOption) {
  ForceStatusFacts facts = ConvergedWithDeficit();
  facts.consistency.tip_mass_unconfirmed = true;
  facts.consistency.tip_mass_force_std_n = 0.3;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusValid | kStatusThrustDeficit);
  facts.consistency.tip_mass_withholds_valid = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusThrustDeficit);
  EXPECT_FALSE(ValidWithdrawn(Converged()));
}

TEST(ForceStatusTest, TransportFactsSetConflictOrStaleAndWithdrawValid) {
  ForceStatusFacts facts = Converged();
  facts.transport.foreign_force = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusInputConflict);
  facts = Converged();
  facts.transport.no_strain_on_wall_clock = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusInputStale);
  // A FORCE that already says INPUT_CONFLICT keeps the one bit.
  facts.input.conflict = facts.transport.foreign_force = true;
  EXPECT_EQ(ComposeForceStatus(facts), kStatusInputStale | kStatusInputConflict);
}

TEST(ForceStatusTest, EveryWithdrawingFactAloneWithdrawsValid) {
  const auto withdrawals = {
      +[](ForceStatusFacts* f) { f->input.stale = true; },
      +[](ForceStatusFacts* f) { f->input.conflict = true; },
      +[](ForceStatusFacts* f) { f->consistency.mismatch = true; },
      +[](ForceStatusFacts* f) {
        f->consistency.model_unconfirmed = f->consistency.unconfirmed_withholds_valid = true;
      },
      +[](ForceStatusFacts* f) {
        f->consistency.tip_mass_unconfirmed = f->consistency.tip_mass_withholds_valid = true;
      },
      +[](ForceStatusFacts* f) { f->transport.foreign_force = true; },
      +[](ForceStatusFacts* f) { f->transport.no_strain_on_wall_clock = true; },
  };
  for (const auto& withdraw : withdrawals) {
    ForceStatusFacts facts = Converged();
    withdraw(&facts);
    EXPECT_TRUE(ValidWithdrawn(facts));
    EXPECT_EQ(ComposeForceStatus(facts) & kStatusValid, 0);
  }
}

// The unconfirmed tip mass's prior in quadrature (ModelConsistencyOptions
// arm_mode_unconfirmed_tip_mass_std 0.15 of m_p g = 2 N: 0.30 N):
// hypot(0.08, 0.30) = 0.3105 N; the method's sigma unchanged otherwise.
TEST(ForceStatusTest, ThePublishedSigmaCarriesTheTipMassOnlyWhileUnconfirmed) {
  ForceStatusFacts facts = Converged();
  facts.consistency.tip_mass_force_std_n = 0.15 * 2.0;
  EXPECT_EQ(PublishedForceStd(0.08, facts, 0), 0.08);
  facts.consistency.tip_mass_unconfirmed = true;
  EXPECT_DOUBLE_EQ(PublishedForceStd(0.08, facts, 0), std::sqrt(0.08 * 0.08 + 0.3 * 0.3));
  EXPECT_NEAR(PublishedForceStd(0.08, facts, 0), 0.3105, 5e-5);
}

// The offsets' departure, per rotor, in quadrature as well: rotor 1's 0.5 N
// (hypot(0.08, 0.5) = 0.5064 N), rotor 2 without one unchanged, bit for bit.
TEST(ForceStatusTest, ThePublishedSigmaCarriesTheOffsetsDeparturePerRotor) {
  ForceStatusFacts facts = Converged();
  facts.consistency.offset_force_std_n[0] = 0.5;
  EXPECT_DOUBLE_EQ(PublishedForceStd(0.08, facts, 0), std::hypot(0.08, 0.5));
  EXPECT_NEAR(PublishedForceStd(0.08, facts, 0), 0.5064, 5e-5);
  EXPECT_EQ(PublishedForceStd(0.08, facts, 1), 0.08);
  facts.consistency.tip_mass_unconfirmed = true;
  facts.consistency.tip_mass_force_std_n = 0.3;
  EXPECT_DOUBLE_EQ(PublishedForceStd(0.08, facts, 0), std::hypot(std::hypot(0.08, 0.5), 0.3));
}

}  // namespace
}  // namespace birotor
