// Honest flight identification (issue 26 item 3): over simulated flight logs
// of hover, gentle, figure-eight, aggressive and flight_id flights, on
// vehicles within +-20 % of the reference in every identified parameter,
// with and without gauge errors, every parameter reported as determined has
// the truth within 3 sigma in at least 95 % of the logs and never beyond 5
// sigma. Logs of 8 s, the shortest that the flight fit accepts with room
// (min_duration_s 5 s); the base file is the reference vehicle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "identification/identify.h"
#include "params/identified_parameter_file.h"
#include "tests/identification/simulated_logs.h"

namespace birotor {
namespace {

using testing::Uniform;

// The figure eight of gauge_drift.yaml (through (+-0.5, 0.5) and (+-0.5,
// 1.0)) without its ground phase, its six moves in 1.3 s each (1.7 m/s^2),
// flown on gentle.yaml.
const char* kFigureEight =
    "trajectory.waypoints=[{start_s: 0.0, duration_s: 1.3, x_m: 0.5, z_m: 0.5}, "
    "{start_s: 1.3, duration_s: 1.3, x_m: 0.0, z_m: 0.75}, {start_s: 2.6, duration_s: 1.3, x_m: -0.5, z_m: 1.0}, "
    "{start_s: 3.9, duration_s: 1.3, x_m: -0.5, z_m: 0.5}, {start_s: 5.2, duration_s: 1.3, x_m: 0.0, z_m: 0.75}, "
    "{start_s: 6.5, duration_s: 1.3, x_m: 0.5, z_m: 1.0}]";

struct FlightCase {
  std::string kind;  // hover, gentle, figure_eight, aggressive, flight_id
  std::vector<std::string> overrides;
  BirotorParams truth;
  BirotorParams base;  // the reference vehicle, with the bench's gauge calibration when the gauge is not ideal
  IdentificationOptions options;
};

// Case n: kind n % 5; every identified vehicle parameter x U(0.8, 1.2);
// (n / 5) odd: real gauges (scale 0.97..1.03, offsets up to 3e-5 rad) whose
// calibration the base file carries as a bench gives it (scale 0.1 % off,
// passed as --gauge-scale-std 0.001).
FlightCase MakeCase(int n, double duration_s) {
  static const char* kKinds[] = {"hover", "gentle", "figure_eight", "aggressive", "flight_id"};
  std::mt19937 rng(2600 + n);
  FlightCase c;
  c.kind = kKinds[n % 5];
  BirotorParams& v = c.truth;
  v.arm_stiffness_n_m_rad *= Uniform(&rng, 0.8, 1.2);
  v.arm_damping_n_m_s_rad *= Uniform(&rng, 0.8, 1.2);
  v.tip_mass_kg *= Uniform(&rng, 0.8, 1.2);
  v.thrust_coeff_n_s2_rad2 *= Uniform(&rng, 0.8, 1.2);
  v.motor_time_constant_s *= Uniform(&rng, 0.8, 1.2);
  double scale[2] = {1.0, 1.0}, offset[2] = {0.0, 0.0};
  if ((n / 5) % 2 == 1) {
    for (int arm = 0; arm < 2; ++arm) {
      scale[arm] = Uniform(&rng, 0.97, 1.03);
      offset[arm] = Uniform(&rng, -3e-5, 3e-5);
      c.base.gauge_scale[arm] = scale[arm] * (1.0 + (arm == 0 ? 0.001 : -0.001));
      c.base.gauge_offset_rad[arm] = offset[arm];
    }
    c.options.calibration.gauge_scale_std = 0.001;
  }
  c.overrides = testing::VehicleOverrides(v, duration_s, 300 + n, scale, offset);
  if (c.kind == "figure_eight") c.overrides.push_back(kFigureEight);
  return c;
}

double TruthOf(const BirotorParams& v, const std::string& symbol) {
  if (symbol == "c_T") return v.thrust_coeff_n_s2_rad2;
  if (symbol == "tau_m") return v.motor_time_constant_s;
  if (symbol == "k") return v.arm_stiffness_n_m_rad;
  if (symbol == "d") return v.arm_damping_n_m_s_rad;
  if (symbol == "m_p") return v.tip_mass_kg;
  return std::nan("");
}

struct Tally {
  int determined = 0;
  int within_3_sigma = 0;
  double max_error_in_sigmas = 0.0;
};

TEST(FlightCoverageTest, DeterminedParametersWithinThreeSigmaIn95PercentOf25FlightLogs) {
  constexpr int kCases = 25;
  constexpr double kDurationS = 8.0;
  std::map<std::string, Tally> by_parameter;
  std::map<std::string, Tally> by_kind;  // key "kind symbol"
  std::map<std::string, int> tau_bases;  // tau_m's excitation: steps, continuous, not excited
  for (int n = 0; n < kCases; ++n) {
    const FlightCase c = MakeCase(n, kDurationS);
    const std::string scenario = c.kind == "figure_eight" ? "gentle" : c.kind;
    SensorLog log = testing::SimulateScenario(scenario, c.overrides);
    log.source = c.kind;
    const IdentificationResult r = Identify({log}, c.base, c.options, IdentificationMode::kFlight);
    ASSERT_TRUE(r.ok) << "case " << n << " " << c.kind;
    for (const ParameterEstimate& e : r.estimates) {
      // The report and the library agree (issue 39): what the report calls
      // determined is what --update-params writes, and no other.
      EXPECT_EQ(ReportStatus(e) == "determined", e.determined) << "case " << n << " " << e.symbol;
      if (e.symbol == "tau_m") {
        ++tau_bases[e.note.basis == EstimateBasis::kMotorFit             ? "steps"
                    : e.note.basis == EstimateBasis::kMotorFitContinuous ? "continuous"
                                                                         : "not excited"];
        std::printf("case %2d tau_m: %d + %d command steps\n", n, e.note.command_steps[0], e.note.command_steps[1]);
      }
      if (!e.determined) continue;
      const double truth = TruthOf(c.truth, e.symbol);
      ASSERT_TRUE(std::isfinite(truth)) << e.symbol;
      const double z = std::abs(e.value - truth) / e.sigma;
      for (Tally* t : {&by_parameter[e.symbol], &by_kind[c.kind + " " + e.symbol]}) {
        ++t->determined;
        if (z <= 3.0) ++t->within_3_sigma;
        t->max_error_in_sigmas = std::max(t->max_error_in_sigmas, z);
      }
      std::printf("case %2d %-12s %-5s %+.3f %% (sigma %.3f %%, %.2f sigma)\n", n, c.kind.c_str(), e.symbol.c_str(),
                  100.0 * (e.value / truth - 1.0), 100.0 * e.sigma / truth, z);
    }
  }
  std::printf("| flight / parameter | determined | within 3 sigma | max error / sigma |\n|---|---|---|---|\n");
  for (const auto* table : {&by_kind, &by_parameter}) {
    for (const auto& [name, t] : *table) {
      std::printf("| %s | %d | %d | %.2f |\n", name.c_str(), t.determined, t.within_3_sigma, t.max_error_in_sigmas);
    }
  }
  for (const auto& [basis, count] : tau_bases)
    std::printf("tau_m excited by %s: %d of %d\n", basis.c_str(), count, kCases);
  for (const auto& [symbol, t] : by_parameter) {
    EXPECT_GE(t.within_3_sigma, 0.95 * t.determined) << symbol;  // issue 26 item 3
    EXPECT_LE(t.max_error_in_sigmas, 5.0) << symbol;
  }
  for (const char* symbol : {"c_T", "k", "tau_m"}) EXPECT_GE(by_parameter[symbol].determined, 20) << symbol;
}

}  // namespace
}  // namespace birotor
