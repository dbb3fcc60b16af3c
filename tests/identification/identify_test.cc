// Recovery of known parameters from simulated bench and flight logs,
// consistency of the reported uncertainties, and the refusals on bad input.
#include "identification/identify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "identification/flight_fit.h"
#include "tests/identification/simulated_logs.h"

namespace birotor {
namespace {

const ParameterEstimate* Find(const IdentificationResult& r, const std::string& symbol) {
  for (const ParameterEstimate& e : r.estimates) {
    if (e.symbol == symbol) return &e;
  }
  return nullptr;
}

std::string Errors(const IdentificationResult& r) {
  std::string text;
  for (const std::string& e : r.errors) text += e + "\n";
  return text;
}

// Checks |value - truth| <= rel_tol truth and, when n_sigma > 0, <= n_sigma sigma.
void ExpectRecovered(const IdentificationResult& r, const std::string& symbol, double truth, double rel_tol,
                     double n_sigma) {
  const ParameterEstimate* e = Find(r, symbol);
  ASSERT_NE(e, nullptr) << symbol;
  EXPECT_TRUE(e->determined) << symbol;
  EXPECT_NEAR(e->value, truth, rel_tol * truth) << symbol << " sigma " << e->sigma;
  EXPECT_GT(e->sigma, 0.0) << symbol;
  if (n_sigma > 0) {
    EXPECT_LE(std::abs(e->value - truth), n_sigma * e->sigma) << symbol << " sigma " << e->sigma;
  }
}

// The information-share line of `symbol` names both logs.
void ExpectShareOfBothLogs(const IdentificationResult& r, const std::string& symbol, const std::string& log_a,
                           const std::string& log_b) {
  bool found = false;
  for (const LogShares& line : r.log_shares) {
    if (line.symbol != symbol) continue;
    found = true;
    ASSERT_TRUE(line.logs.size() == 2 && line.shares.size() == 2) << symbol;
    EXPECT_NE(line.logs[0].find(log_a), std::string::npos) << line.logs[0];
    EXPECT_NE(line.logs[1].find(log_b), std::string::npos) << line.logs[1];
    EXPECT_NEAR(line.shares[0] + line.shares[1], 1.0, 1e-12) << symbol;  // shares of one information sum
  }
  EXPECT_TRUE(found) << symbol;
}

// Logs of two vehicles: refused, the error names the disagreement on k and the log.
void ExpectRefusedAsTwoVehicles(const std::vector<SensorLog>& logs, const std::string& named_log) {
  const IdentificationResult r = Identify(logs, BirotorParams(), IdentificationOptions());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(Errors(r).find("logs disagree on k"), std::string::npos) << Errors(r);
  EXPECT_NE(Errors(r).find(named_log), std::string::npos) << Errors(r);
}

// A base file that is wrong by a few percent, so the fits have to move.
BirotorParams PerturbedBase(const BirotorParams& truth) {
  BirotorParams base = truth;
  base.arm_stiffness_n_m_rad *= 1.05;
  base.thrust_coeff_n_s2_rad2 *= 0.95;
  base.motor_time_constant_s *= 1.1;
  base.arm_damping_n_m_s_rad *= 1.5;
  return base;
}

class BenchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    log_ = new SensorLog(testing::SimulateScenario("bench", {"scenario.duration_s=30"}, &truth_));
  }
  static void TearDownTestSuite() { delete log_; }
  static SensorLog* log_;
  static BirotorParams truth_;
};
SensorLog* BenchTest::log_ = nullptr;
BirotorParams BenchTest::truth_;

TEST_F(BenchTest, RecoversThrustMotorAndStiffnessWithin1PercentAnd3Sigma) {
  const IdentificationResult r = Identify({*log_}, PerturbedBase(truth_), IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  EXPECT_EQ(r.mode, "bench");
  ExpectRecovered(r, "c_T", truth_.thrust_coeff_n_s2_rad2, 0.01, 3.0);
  ExpectRecovered(r, "tau_m", truth_.motor_time_constant_s, 0.01, 3.0);
  ExpectRecovered(r, "k", truth_.arm_stiffness_n_m_rad, 0.01, 3.0);
  EXPECT_DOUBLE_EQ(r.params.arm_stiffness_n_m_rad, Find(r, "k")->value);
  EXPECT_DOUBLE_EQ(r.params.body_mass_kg, truth_.body_mass_kg);  // known, untouched
}

TEST_F(BenchTest, DeflectionForceMapMatchesStatics) {
  IdentificationOptions options;
  options.map_degree = 2;
  const IdentificationResult r = Identify({*log_}, truth_, options);
  ASSERT_TRUE(r.ok) << Errors(r);
  ASSERT_EQ(r.maps.size(), 2u);
  for (const DeflectionForceMap& map : r.maps) {
    ASSERT_EQ(map.coefficients.size(), 3u);
    // Statics k b = s L (f - m_p g): f = m_p g + s k b / L.
    const double slope = kArmSign[map.arm] * truth_.arm_stiffness_n_m_rad / truth_.arm_length_m;
    EXPECT_NEAR(map.coefficients[1], slope, 0.01 * std::abs(slope));
    EXPECT_NEAR(map.coefficients[0], truth_.tip_mass_kg * truth_.gravity_m_s2, 0.1);
    EXPECT_LT(map.residual_rms_n, 0.5);  // strain noise and arm dynamics
  }
}

TEST_F(BenchTest, SpikesDoNotMoveTheEstimates) {
  SensorLog spiked = *log_;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (StrainSample& s : spiked.strain) {
    if (u(rng) < 0.005) s.deflection_rad[u(rng) < 0.5 ? 0 : 1] += (u(rng) < 0.5 ? 50 : -50) * 2e-5;
  }
  const IdentificationResult r = Identify({spiked}, truth_, IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  ExpectRecovered(r, "k", truth_.arm_stiffness_n_m_rad, 0.01, 0.0);
}

TEST_F(BenchTest, NoLoadCellsInBenchModeSaysWhatIsMissing) {
  SensorLog log = *log_;
  log.loadcell.clear();
  const IdentificationResult r = Identify({log}, truth_, IdentificationOptions(), IdentificationMode::kBench);
  EXPECT_FALSE(r.ok);
  ASSERT_FALSE(r.errors.empty());
  EXPECT_NE(Errors(r).find("LOADCELL"), std::string::npos) << Errors(r);
  EXPECT_TRUE(r.estimates.empty());  // no numbers
}

TEST_F(BenchTest, NoTelemetrySaysWhatIsMissing) {
  SensorLog log = *log_;
  for (MotorSample& m : log.motor) m.omega_meas_rad_s[0] = m.omega_meas_rad_s[1] = std::nan("");
  const IdentificationResult r = Identify({log}, truth_, IdentificationOptions());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(Errors(r).find("telemetry"), std::string::npos) << Errors(r);
}

TEST_F(BenchTest, TooShortLogIsRefused) {
  SensorLog log = *log_;
  const int64_t end_us = log.strain.front().utime + 2000000;
  auto cut = [end_us](auto* v) {
    while (!v->empty() && v->back().utime > end_us) v->pop_back();
  };
  cut(&log.strain);
  cut(&log.motor);
  cut(&log.loadcell);
  const IdentificationResult r = Identify({log}, truth_, IdentificationOptions());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(Errors(r).find("too short"), std::string::npos) << Errors(r);
}

// Issue 11's vehicle (tip mass 0.30 kg, k 3100, tau_m 0.045, c_T 5e-5) on a
// base file with the reference tip mass 0.28812: the tip mass is identified
// (factory gauge scale), and k no longer absorbs the wrong mass.
TEST(BenchTipMassTest, IdentifiesTheTipMassWithTheFactoryGaugeScale) {
  BirotorParams truth;
  const SensorLog log = testing::SimulateScenario(
      "bench",
      {"scenario.duration_s=30", "vehicle.arm_stiffness_n_m_rad=3100", "vehicle.tip_mass_kg=0.30",
       "vehicle.motor_time_constant_s=0.045", "vehicle.thrust_coeff_n_s2_rad2=5.0e-5"},
      &truth);
  const IdentificationResult r = Identify({log}, BirotorParams(), IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  // Targets of issue 11 (bench): k 0.5 %, m_p 1 %, d 5 %; within 3 sigma.
  ExpectRecovered(r, "m_p", 0.30, 0.01, 3.0);
  ExpectRecovered(r, "k", 3100.0, 0.005, 3.0);
  ExpectRecovered(r, "d", truth.arm_damping_n_m_s_rad, 0.05, 3.0);
  EXPECT_DOUBLE_EQ(r.params.tip_mass_kg, Find(r, "m_p")->value);
  EXPECT_TRUE(r.has_calibration_fact && !r.calibration_fact.TipMassWeighed());  // the factory gauge scale
  EXPECT_EQ(Find(r, "s_1"), nullptr);                                           // held: the factory scale is the input
}

// bench_gauge (gauges.md: scales 1.03 / 0.98, offsets 1e-5 / -1e-5 rad) with
// the tip mass weighed: the gauge scales and offsets are identified.
TEST(BenchGaugeTest, IdentifiesGaugeScaleAndOffsetWithAWeighedTipMass) {
  BirotorParams truth;
  const SensorLog log = testing::SimulateScenario("bench_gauge", {}, &truth);
  IdentificationOptions options;
  options.calibration.tip_mass_kg = truth.tip_mass_kg;
  options.calibration.tip_mass_std_kg = 0.0001;  // a 0.1 g scale
  const IdentificationResult r = Identify({log}, BirotorParams(), options);
  ASSERT_TRUE(r.ok) << Errors(r);
  // Targets of issue 11 (bench): gauge scale 0.3 %, offset 2e-6 rad; within 3 sigma.
  ExpectRecovered(r, "s_1", 1.03, 0.003, 3.0);
  ExpectRecovered(r, "s_2", 0.98, 0.003, 3.0);
  for (const auto& [symbol, offset_rad] : {std::pair<std::string, double>{"o_1", 1.0e-5}, {"o_2", -1.0e-5}}) {
    const ParameterEstimate* e = Find(r, symbol);
    ASSERT_NE(e, nullptr) << symbol;
    EXPECT_NEAR(e->value, offset_rad, 2e-6) << symbol;
    EXPECT_LE(std::abs(e->value - offset_rad), 3.0 * e->sigma) << symbol;
  }
  ExpectRecovered(r, "k", truth.arm_stiffness_n_m_rad, 0.005, 3.0);
  EXPECT_DOUBLE_EQ(r.params.gauge_scale[0], Find(r, "s_1")->value);
  EXPECT_DOUBLE_EQ(r.params.gauge_offset_rad[1], Find(r, "o_2")->value);
  EXPECT_TRUE(r.has_calibration_fact && r.calibration_fact.tip_mass_kg == truth.tip_mass_kg);
}

// Several logs (issue 11 item 4): two runs of one vehicle give one joint fit
// and each log's share of every parameter; two vehicles are refused.
TEST(SeveralLogsTest, SameVehicleJointFitSaysWhichLogDeterminesWhat) {
  BirotorParams truth;
  SensorLog a = testing::SimulateScenario("bench", {"scenario.duration_s=12", "scenario.seed=21"}, &truth);
  SensorLog b = testing::SimulateScenario("bench", {"scenario.duration_s=12", "scenario.seed=22"});
  a.source = "a.lcm";
  b.source = "b.lcm";
  const IdentificationResult r = Identify({a, b}, truth, IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  ExpectRecovered(r, "k", truth.arm_stiffness_n_m_rad, 0.005, 3.0);
  ExpectRecovered(r, "m_p", truth.tip_mass_kg, 0.01, 3.0);
  ExpectShareOfBothLogs(r, "k", "a.lcm", "b.lcm");
}

TEST(SeveralLogsTest, TwoVehiclesAreRefusedAsInconsistent) {
  SensorLog a = testing::SimulateScenario("bench", {"scenario.duration_s=12"});
  SensorLog b = testing::SimulateScenario(
      "bench", {"scenario.duration_s=12", "vehicle.arm_stiffness_n_m_rad=3100", "vehicle.tip_mass_kg=0.30"});
  a.source = "reference.lcm";
  b.source = "other.lcm";
  ExpectRefusedAsTwoVehicles({a, b}, "reference.lcm");
}

// Issue 16 item 10: one STRAIN stamped INT64_MIN, duplicated STRAIN events,
// a sample from the future, two out of order and a NaN command made the
// identification refuse the log. They are dropped and counted; the fit stands.
TEST_F(BenchTest, BadSamplesAreDroppedAndCountedNotFatal) {
  SensorLog log = *log_;
  std::swap(log.strain[20000], log.strain[20001]);
  std::vector<StrainSample> doubled;
  for (const StrainSample& s : log.strain) {
    doubled.push_back(s);
    doubled.push_back(s);  // every event logged twice
  }
  const size_t n = log.strain.size();
  StrainSample future = doubled[10000];
  future.utime += 400000;  // 0.4 s ahead, nothing confirms it
  doubled.insert(doubled.begin() + 10000, future);
  StrainSample absurd = doubled[3000];
  absurd.utime = std::numeric_limits<int64_t>::min();
  doubled.insert(doubled.begin() + 3000, absurd);
  log.strain = doubled;
  log.motor[700].omega_cmd_rad_s[1] = std::nan("");

  const IdentificationResult r = Identify({log}, truth_, IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  ExpectRecovered(r, "k", truth_.arm_stiffness_n_m_rad, 0.01, 3.0);
  EXPECT_EQ(r.dropped.strain.bad_stamp, 2);
  EXPECT_EQ(r.dropped.strain.duplicate, static_cast<int64_t>(n) - 1);
  EXPECT_EQ(r.dropped.strain.out_of_order, 2);  // both copies of the late sample
  EXPECT_EQ(r.dropped.strain.non_finite, 0);
  EXPECT_EQ(r.dropped.motor.non_finite, 1);
  EXPECT_EQ(r.dropped.total(), static_cast<int64_t>(n) - 1 + 2 + 2 + 1);
}

// Constant commands: the speed never moves, so tau_m has no information.
TEST(IdentifyBadInputTest, NoMotorStepsMeansTauCannotBeIdentified) {
  const BirotorParams p;
  SensorLog log;
  log.source = "constant";
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  const double omega = 700.0, force = p.thrust_coeff_n_s2_rad2 * omega * omega;
  for (int i = 0; i < 10000; ++i) {
    const int64_t t = 1000 * static_cast<int64_t>(i);
    StrainSample s;
    s.utime = t;
    LoadCellSample c;
    c.utime = t;
    for (int a = 0; a < 2; ++a) {
      s.deflection_rad[a] =
          kArmSign[a] * p.arm_length_m * (force - p.tip_mass_kg * p.gravity_m_s2) / p.arm_stiffness_n_m_rad +
          2e-5 * n(rng);
      c.force_n[a] = force + 0.02 * n(rng);
    }
    log.strain.push_back(s);
    log.loadcell.push_back(c);
    if (i % 2 == 0) {
      MotorSample m;
      m.utime = t;
      for (int a = 0; a < 2; ++a) {
        m.omega_cmd_rad_s[a] = omega;
        m.omega_meas_rad_s[a] = omega + 5.0 * n(rng);
      }
      log.motor.push_back(m);
    }
  }
  const IdentificationResult r = Identify({log}, p, IdentificationOptions());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(Errors(r).find("tau_m cannot be identified"), std::string::npos) << Errors(r);
  EXPECT_NE(Errors(r).find("steps"), std::string::npos) << Errors(r);
}

TEST(IdentifyBadInputTest, EmptyLogSaysWhichChannelsAreMissing) {
  SensorLog log;
  log.source = "empty.lcm";
  const IdentificationResult r = Identify({log}, BirotorParams(), IdentificationOptions());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(Errors(r).find("empty.lcm: no STRAIN"), std::string::npos) << Errors(r);
  EXPECT_NE(Errors(r).find("no MOTOR"), std::string::npos) << Errors(r);
}

TEST(FlightIdentificationTest, RecoversStiffnessThrustAndMotorFromFreeFlight) {
  BirotorParams truth;
  const SensorLog log = testing::SimulateScenario("flight_id", {"scenario.duration_s=8"}, &truth);
  const IdentificationResult r = Identify({log}, PerturbedBase(truth), IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  EXPECT_EQ(r.mode, "flight");
  ExpectRecovered(r, "k", truth.arm_stiffness_n_m_rad, 0.03, 0.0);
  ExpectRecovered(r, "c_T", truth.thrust_coeff_n_s2_rad2, 0.03, 0.0);
  ExpectRecovered(r, "tau_m", truth.motor_time_constant_s, 0.05, 0.0);
  // The base file's m_p is the truth: the flight agrees with it, so it is
  // kept, marked not determined, and the warning says so (issue 26).
  const ParameterEstimate* m_p = Find(r, "m_p");
  ASSERT_NE(m_p, nullptr);
  EXPECT_FALSE(m_p->determined);
  EXPECT_DOUBLE_EQ(r.params.tip_mass_kg, truth.tip_mass_kg);
  EXPECT_EQ(m_p->note.basis, EstimateBasis::kTipMassAgreesWithBase);
  EXPECT_LE(m_p->note.distance_sigmas, IdentificationOptions().consistency_sigmas);
}

// Issue 11: the tip mass from a 60 s flight alone (flight_id). Measured with
// the rotor turbulence modelled and the reference base file: m_p +1.22 %
// (1.4 sigma, sigma 0.86 %), c_T +0.23 %, k -0.005 %, tau_m -0.23 %. A
// flight m_p that agrees with the base file within consistency_sigmas keeps
// the base value (issue 26), so the base here has m_p 5 % low: the flight
// must show it wrong and bring it within the 2 % target, within 3 sigma.
TEST(FlightIdentificationTest, TipMassFromTheSixtySecondFlightWithin2Percent) {
  BirotorParams truth;
  const SensorLog log = testing::SimulateScenario("flight_id", {}, &truth);
  BirotorParams base;
  base.tip_mass_kg *= 0.95;
  const IdentificationResult r = Identify({log}, base, IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  ExpectRecovered(r, "m_p", truth.tip_mass_kg, 0.02, 3.0);
  ExpectRecovered(r, "c_T", truth.thrust_coeff_n_s2_rad2, 0.02, 3.0);
  ExpectRecovered(r, "k", truth.arm_stiffness_n_m_rad, 0.02, 3.0);
  ExpectRecovered(r, "tau_m", truth.motor_time_constant_s, 0.03, 3.0);
  // The sandwich sigma from the scatter of the 40 windows, not the 0.29 %
  // of the inflated information matrix the errors contradict.
  const ParameterEstimate* m_p = Find(r, "m_p");
  ASSERT_NE(m_p, nullptr);
  EXPECT_GT(m_p->sigma, 0.005 * truth.tip_mass_kg);
}

// A flight reads its deflections through the base file's gauge scale: with
// gauges 1 % stronger than the file says, k and m_p come out ~1 % low at a
// sigma that knows nothing of it; --gauge-scale-std puts the scale's
// uncertainty into their sigma (c_T, from the accelerometer, stays right).
TEST(FlightIdentificationTest, GaugeScaleUncertaintyReachesTheSigmaOfKAndTipMass) {
  BirotorParams truth;
  const SensorLog log =
      testing::SimulateScenario("flight_id", {"scenario.duration_s=8", "gauge.scale=[1.01, 1.01]"}, &truth);
  IdentificationOptions options;
  options.calibration.gauge_scale_std = 0.01;
  const IdentificationResult r = Identify({log}, BirotorParams(), options);
  ASSERT_TRUE(r.ok) << Errors(r);
  const ParameterEstimate* k = Find(r, "k");
  ASSERT_NE(k, nullptr);
  std::printf("gauges 1 %% strong: k %+.3f %% (sigma %.3f %%)\n",
              100.0 * (k->value / truth.arm_stiffness_n_m_rad - 1.0), 100.0 * k->sigma / k->value);
  EXPECT_LT(k->value, truth.arm_stiffness_n_m_rad);  // seen through the scale
  ExpectRecovered(r, "k", truth.arm_stiffness_n_m_rad, 0.03, 3.0);
  EXPECT_GE(k->sigma, 0.01 * k->value);
  EXPECT_EQ(k->note.remarks, std::vector<EstimateRemark>{EstimateRemark::kGaugeScaleFloor});
  ExpectRecovered(r, "c_T", truth.thrust_coeff_n_s2_rad2, 0.03, 3.0);
}

// Issue 11 item 4: a bench log and a flight log of one vehicle in one Ceres
// problem (12 s bench, 8 s flight, reference file as base). Measured: k
// +0.0095 % (2.0 sigma), c_T -0.008 % (0.1), m_p +0.104 % (1.0), tau_m
// +0.23 % (2.1), d -3.4 % (1.2); shares c_T bench 54.8 % / flight 45.2 %,
// k 84.6 / 15.4, m_p 98.6 / 1.4. Asserted with a 1.5x margin (d: its 5 %
// target) and truth within 3 sigma.
TEST(JointBenchFlightTest, OneProblemOverBothLogsSaysWhichLogDeterminesWhat) {
  BirotorParams truth;
  SensorLog bench = testing::SimulateScenario("bench", {"scenario.duration_s=12"}, &truth);
  SensorLog flight = testing::SimulateScenario("flight_id", {"scenario.duration_s=8"});
  bench.source = "bench.lcm";
  flight.source = "flight.lcm";
  const IdentificationResult r = Identify({bench, flight}, BirotorParams(), IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  EXPECT_EQ(r.mode, "bench+flight");
  ExpectRecovered(r, "k", truth.arm_stiffness_n_m_rad, 1.5 * 0.000095, 3.0);
  ExpectRecovered(r, "c_T", truth.thrust_coeff_n_s2_rad2, 1.5 * 0.00008, 3.0);
  ExpectRecovered(r, "m_p", truth.tip_mass_kg, 1.5 * 0.00104, 3.0);
  ExpectRecovered(r, "tau_m", truth.motor_time_constant_s, 1.5 * 0.0023, 3.0);
  ExpectRecovered(r, "d", truth.arm_damping_n_m_s_rad, 0.05, 3.0);
  const ParameterEstimate* c_t = Find(r, "c_T");
  ASSERT_NE(c_t, nullptr);
  EXPECT_TRUE(c_t->note.basis == EstimateBasis::kFreeArmFit && c_t->note.joint);
  ExpectShareOfBothLogs(r, "c_T", "bench.lcm", "flight.lcm");
}

TEST(JointBenchFlightTest, BenchAndFlightOfDifferentVehiclesAreRefused) {
  SensorLog bench = testing::SimulateScenario("bench", {"scenario.duration_s=12"});
  SensorLog flight = testing::SimulateScenario(
      "flight_id", {"scenario.duration_s=8", "vehicle.arm_stiffness_n_m_rad=3100", "vehicle.tip_mass_kg=0.31"});
  bench.source = "reference_bench.lcm";
  flight.source = "other_flight.lcm";
  ExpectRefusedAsTwoVehicles({bench, flight}, "other_flight.lcm");
}

// Issue 26: the 12 s hover of the table gave m_p 0.675..0.788 kg
// (+134..+173 %) and c_T +17..+22 %, "determined" at 1.7 % / 0.5 %: the
// solver, started from zero turbulence with m_p free, fell into a far
// minimum. Solved with m_p held first, then judged (CheckTipMass) and freed.
// Measured on the reference base file (birotor-identify on birotor-sim
// --scenario hover --set scenario.duration_s=12): m_p +0.45 % (sigma 0.70 %),
// c_T -0.04 % (sigma 0.17 %), 100 % of m_p's information from the data. Here
// the base has m_p 5 % low (else the flight, agreeing with it, keeps it):
// asserted within the 2 % flight_id target and 3 sigma.
TEST(FlightDeterminabilityTest, HoverGivesTheTipMassWithinThreeSigmaNotAFarMinimum) {
  BirotorParams truth;
  const SensorLog log = testing::SimulateScenario("hover", {"scenario.duration_s=12"}, &truth);
  BirotorParams base;
  base.tip_mass_kg *= 0.95;
  const IdentificationResult r = Identify({log}, base, IdentificationOptions());
  ASSERT_TRUE(r.ok) << Errors(r);
  ExpectRecovered(r, "m_p", truth.tip_mass_kg, 0.02, 3.0);
  ExpectRecovered(r, "c_T", truth.thrust_coeff_n_s2_rad2, 0.02, 3.0);
  const ParameterEstimate* m_p = Find(r, "m_p");
  ASSERT_NE(m_p, nullptr);
  EXPECT_EQ(std::count(m_p->note.remarks.begin(), m_p->note.remarks.end(), EstimateRemark::kTipMassDataShare), 1);
  EXPECT_GT(m_p->note.data_share, 0.0);
}

// When the data's share of m_p's information is below flight_min_data_share
// (here above 1, which no log gives), m_p keeps the base value, is marked not determined, the
// warning says what to fly and the determined combination is named; c_T is
// that of the fit with m_p held, within 3 sigma (the default is never worse
// than holding m_p).
TEST(FlightDeterminabilityTest, UndeterminedTipMassKeepsTheBaseValueAndSaysWhatToFly) {
  BirotorParams truth;
  const SensorLog log = testing::SimulateScenario("hover", {"scenario.duration_s=8"}, &truth);
  IdentificationOptions options;
  options.flight_min_data_share = 1.01;  // no log can give more than all of the information
  const IdentificationResult r = Identify({log}, BirotorParams(), options);
  ASSERT_TRUE(r.ok) << Errors(r);
  const ParameterEstimate* m_p = Find(r, "m_p");
  ASSERT_NE(m_p, nullptr);
  EXPECT_FALSE(m_p->determined);
  EXPECT_DOUBLE_EQ(r.params.tip_mass_kg, BirotorParams().tip_mass_kg);
  // The warning says what to fly (its words: params/identified_parameter_file.h WarningText).
  bool advised = false;
  for (const IdentificationWarning& w : r.warnings) {
    advised = advised || (w.kind == WarningKind::kTipMassHeldInFlight && w.symbol == "m_p" &&
                          w.advice == ExcitationAdvice::kTipMassSteps);
  }
  EXPECT_TRUE(advised);
  ASSERT_FALSE(r.correlations.empty());
  EXPECT_EQ(r.correlations.back().kind, CombinationKind::kThrustOverTotalMass);
  EXPECT_DOUBLE_EQ(r.correlations.back().held_value, BirotorParams().tip_mass_kg);
  ExpectRecovered(r, "c_T", truth.thrust_coeff_n_s2_rad2, 0.01, 3.0);
}

// Stages a test can call (issue 22 item 5).
TEST(FlightStagesTest, WindowScanSpreadsTheWindowsEvenly) {
  std::vector<FlightWindow> candidates(10);
  for (size_t i = 0; i < candidates.size(); ++i) candidates[i].begin = i;
  const std::vector<FlightWindow> picked = SelectFlightWindows(candidates, 4);
  ASSERT_EQ(picked.size(), 4u);
  // (2 w + 1) 10 / 8 for w = 0..3: 1, 3, 6, 8.
  EXPECT_EQ(picked[0].begin, 1u);
  EXPECT_EQ(picked[1].begin, 3u);
  EXPECT_EQ(picked[2].begin, 6u);
  EXPECT_EQ(picked[3].begin, 8u);
  EXPECT_EQ(SelectFlightWindows(candidates, 0).size(), 10u);
}

TEST(FlightStagesTest, DataShareFromThePriorSensitivity) {
  // Unchanged sigma: all information from the data; sigma x4 under a x4
  // prior: none; r^2 = 2 / (1 + 1/16): half (D = P).
  EXPECT_DOUBLE_EQ(DataInformationShare({0.001, 0.001}, 4.0), 1.0);
  EXPECT_NEAR(DataInformationShare({0.001, 0.004}, 4.0), 0.0, 1e-12);
  EXPECT_NEAR(DataInformationShare({0.001, 0.001 * std::sqrt(2.0 / (1.0 + 1.0 / 16.0))}, 4.0), 0.5, 1e-12);
  EXPECT_EQ(DataInformationShare({std::numeric_limits<double>::infinity(), 1.0}, 4.0), 0.0);
}

TEST(FlightStagesTest, InitialWindowStateFromALineThroughTheFirstSamples) {
  std::vector<FreeArmWindowResidual::Sample> samples(10);
  for (size_t i = 0; i < samples.size(); ++i) {
    samples[i] = {0.001, {700.0, 700.0}, {1e-3 + 0.02 * 0.001 * i, -2e-3}, 0.3, {0.0, 9.81}};
  }
  const std::array<double, kFreeArmStateSize> x0 = InitialWindowState(samples);
  EXPECT_DOUBLE_EQ(x0[kFreePhiDot], 0.3);
  EXPECT_DOUBLE_EQ(x0[kFreeB1], 1e-3);
  EXPECT_NEAR(x0[kFreeB1Dot], 0.02, 1e-12);  // the slope of the line [rad/s]
  EXPECT_NEAR(x0[kFreeB2Dot], 0.0, 1e-12);
}

}  // namespace
}  // namespace birotor
