// MotorLagLead: the command omega (tau s + 1) / (tau_f s + 1) on the
// thrust's change, and motor_lead_s x -omega / (2 e) de/dt while e falls.
// A rotor map of c_T 1e-5 N s^2/rad^2 and omega_max 1000 rad/s, the
// controller's period 2 ms (500 Hz), the defaults of
// controller/controller_params.h (tau 0.035 s, tau_f 0.005 s).
#include "controller/motor_lag_lead.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace birotor {
namespace {

constexpr double kDtS = 0.002;
const RotorMap kMap{1e-5, 1000.0};

// The thrust [N] the map makes at omega [rad/s] with efficiency e [1].
double ThrustAt(double omega_rad_s, double efficiency) {
  return efficiency * kMap.thrust_coeff_n_s2_rad2 * omega_rad_s * omega_rad_s;
}

// Leads omega at efficiency e (its thrust the map's) for one period.
double LeadAt(MotorLagLead* lead, const EfficiencyParams& params, double omega_rad_s, double efficiency = 1.0) {
  return lead->Lead(params, kMap, omega_rad_s, ThrustAt(omega_rad_s, efficiency), efficiency, kDtS);
}

// The rotor's speed after `seconds` of a step of the map's speed from
// 600 to 700 rad/s, the rotor a first-order lag tau_m = 0.035 s of the
// led command, as a fraction of the step.
double StepResponseAfter(const EfficiencyParams& params, double seconds) {
  MotorLagLead lead;
  double rotor_rad_s = 600.0;
  for (int k = 0; k < 10; ++k) rotor_rad_s += kDtS / 0.035 * (LeadAt(&lead, params, 600.0) - rotor_rad_s);
  const int periods = static_cast<int>(std::lround(seconds / kDtS));
  for (int k = 0; k < periods; ++k) rotor_rad_s += kDtS / 0.035 * (LeadAt(&lead, params, 700.0) - rotor_rad_s);
  return (rotor_rad_s - 600.0) / 100.0;
}

TEST(MotorLagLeadTest, AThrustStepIsLedThroughTheFilter) {
  const EfficiencyParams params;
  MotorLagLead lead;
  EXPECT_DOUBLE_EQ(LeadAt(&lead, params, 600.0), 600.0);  // no thrust before: nothing to lead
  EXPECT_DOUBLE_EQ(LeadAt(&lead, params, 600.0), 600.0);
  // (tau - tau_f) x 100 rad/s / dt through the low-pass: x dt / (tau_f + dt).
  const double first_lead_rad_s = (0.035 - 0.005) * 100.0 / (0.005 + kDtS);
  EXPECT_NEAR(LeadAt(&lead, params, 700.0), 700.0 + first_lead_rad_s, 1e-9);
  // Then it decays by tau_f / (tau_f + dt) a period.
  EXPECT_NEAR(LeadAt(&lead, params, 700.0), 700.0 + first_lead_rad_s * 0.005 / 0.007, 1e-9);
}

TEST(MotorLagLeadTest, TheRotorFollowsAStepFasterThanItsLag) {
  EfficiencyParams plain;
  plain.thrust_lead_s = 0.0;
  // Without the lead 1 - exp(-10 / 35) = 0.25 of the step after 10 ms;
  // led, the rotor lags about tau_f = 5 ms instead.
  EXPECT_NEAR(StepResponseAfter(plain, 0.010), 0.25, 0.02);
  EXPECT_GT(StepResponseAfter(EfficiencyParams{}, 0.010), 0.75);
  EXPECT_NEAR(StepResponseAfter(EfficiencyParams{}, 0.100), 1.0, 0.01);
}

TEST(MotorLagLeadTest, OnlyAFallingEfficiencyIsLed) {
  const EfficiencyParams params;
  MotorLagLead falling;
  LeadAt(&falling, params, 600.0, 1.0);
  // The same thrust at e 0.99: the map's speed sqrt(1 / 0.99) higher, and
  // motor_lead_s x omega / (2 e) x 0.01 / dt more.
  const double omega_rad_s = 600.0 / std::sqrt(0.99);
  const double expected_rad_s = omega_rad_s + 0.035 * omega_rad_s / (2.0 * 0.99) * 0.01 / kDtS;
  EXPECT_NEAR(falling.Lead(params, kMap, omega_rad_s, ThrustAt(600.0, 1.0), 0.99, kDtS), expected_rad_s, 1e-9);
  MotorLagLead rising;
  LeadAt(&rising, params, 600.0, 0.99);
  const double rising_rad_s = 600.0 * std::sqrt(0.99);
  EXPECT_DOUBLE_EQ(rising.Lead(params, kMap, rising_rad_s, ThrustAt(600.0, 0.99), 1.0, kDtS), rising_rad_s);
}

TEST(MotorLagLeadTest, ARotorNotDrivenIsNotLedAndForgetsItsLead) {
  const EfficiencyParams params;
  MotorLagLead lead;
  LeadAt(&lead, params, 600.0);
  EXPECT_GT(LeadAt(&lead, params, 700.0), 700.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(lead.Lead(params, kMap, nan, 4.9, 1.0, kDtS)));
  EXPECT_DOUBLE_EQ(lead.Lead(params, kMap, 0.0, 0.0, 0.0, kDtS), 0.0);  // e = 0: makes nothing
  // Driven again at the thrust of the period before: no lead left.
  EXPECT_DOUBLE_EQ(lead.Lead(params, kMap, 0.0, 0.0, 1.0, kDtS), 0.0);
  EXPECT_GT(LeadAt(&lead, params, 700.0), 700.0);  // a new step is led again
}

TEST(MotorLagLeadTest, APeriodWithoutTimeIsNotLed) {
  const EfficiencyParams params;
  MotorLagLead lead;
  LeadAt(&lead, params, 600.0);
  EXPECT_DOUBLE_EQ(lead.Lead(params, kMap, 700.0, ThrustAt(700.0, 1.0), 1.0, 0.0), 700.0);
}

}  // namespace
}  // namespace birotor
