// The force plot: what it marks and notes (read from its script) and the PNG
// it writes, for a made-up thrust loss with and without TRUTH.
#include "plot/force_plot.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/plot/plot_test_support.h"

namespace birotor {
namespace {

// 2 s at 1 kHz. Rotor 2 loses a quarter of its thrust at 1.000 s (truth
// 3.5 N -> 2.625 N); the estimate overshoots to 9 N for 3 ms (the transient
// issue 14 saw) and ROTOR2_FAULT rises at 1.030 s. The first message carries
// the start-up FILTER_RESET, which is not a rise.
struct ThrustLoss {
  std::vector<ForceEstimate> forces;
  std::vector<TruthSample> truth;
};

ThrustLoss MakeThrustLoss() {
  ThrustLoss run;
  for (int k = 0; k < 2000; ++k) {
    TruthSample t;
    t.utime = 1000 * k;
    const bool lost = k >= 1000;
    t.force_n[0] = 3.5;
    t.force_n[1] = lost ? 2.625 : 3.5;
    t.thrust_scale[1] = lost ? 0.75 : 1.0;
    ForceEstimate e;
    e.utime = t.utime;
    e.seq = k;
    e.force_n[0] = t.force_n[0] + 0.01;
    e.force_n[1] = (k >= 1001 && k <= 1003) ? 9.0 : t.force_n[1] - 0.01;
    e.force_std_n[0] = e.force_std_n[1] = 0.02;
    e.thrust_scale[1] = lost ? 0.76 : 1.0;
    e.status = kStatusValid | (k == 0 ? kStatusFilterReset : 0) | (k >= 1030 ? kStatusRotor2Fault : 0);
    run.truth.push_back(t);
    run.forces.push_back(e);
  }
  return run;
}

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ForcePlotTest, MarksFaultsStepAndClippedTransient) {
  const ThrustLoss run = MakeThrustLoss();
  ForcePlotOptions options;
  options.title = "thrust_loss - ekf";
  options.markers.push_back(ThrustStepMarker(2, 1.0));
  const std::string script = ForcePlotScript(run.forces, run.truth, options);
  EXPECT_TRUE(Has(script, "'ROTOR2_FAULT 1.030 s'"));
  EXPECT_TRUE(Has(script, "'true thrust step rotor 2 1.000 s'"));
  EXPECT_FALSE(Has(script, "'RESET 0.000 s'"));  // the start-up reset is not marked
  EXPECT_FALSE(Has(script, "'ROTOR1_FAULT "));
  // 3 of 2000 samples (0.15 %) at 9 N are outside the bulk (clip_fraction 0.2 %).
  EXPECT_TRUE(Has(script, "clipped to the bulk of the data: peak 9.00 N at 1.001 s"));
  EXPECT_TRUE(Has(script, "rotor fault below 0.90"));  // 1 - EkfOptions::rotor_fault_asymmetry
  EXPECT_TRUE(Has(script, "f2 est - true"));
  EXPECT_TRUE(Has(script, "±1σ, median 0.020 N"));  // MakeThrustLoss's std

  TemporaryFolder folder("birotor_force_plot_test_");
  std::string error;
  ASSERT_TRUE(WriteForcePlot(run.forces, run.truth, options, folder.path() + "/thrust loss.png", &error)) << error;
  const PngSize size = ReadPngSize(folder.path() + "/thrust loss.png");
  EXPECT_EQ(size.width, 1200u);  // ForcePlotOptions defaults
  EXPECT_EQ(size.height, 1300u);
  EXPECT_EQ(folder.Entries(), std::vector<std::string>{"thrust loss.png"});  // no .dat, no .gp
}

TEST(ForcePlotTest, WithoutTruthShowsEstimatesOnly) {
  const ThrustLoss run = MakeThrustLoss();
  ForcePlotOptions options;
  options.title = "vehicle";
  EkfOptions ekf;
  ekf.rotor_fault_asymmetry = 0.2;
  options.scale_lines = ThrustScaleLines(ekf);
  const std::string script = ForcePlotScript(run.forces, {}, options);
  EXPECT_TRUE(Has(script, "(no TRUTH: estimates only)"));
  EXPECT_FALSE(Has(script, "est - true"));
  EXPECT_FALSE(Has(script, "'true'"));
  EXPECT_TRUE(Has(script, "rotor fault below 0.80"));
  EXPECT_TRUE(Has(script, "'ROTOR2_FAULT 1.030 s'"));

  TemporaryFolder folder("birotor_force_plot_test_");
  std::string error;
  ASSERT_TRUE(WriteForcePlot(run.forces, {}, options, folder.path() + "/vehicle.png", &error)) << error;
  EXPECT_EQ(ReadPngSize(folder.path() + "/vehicle.png").width, 1200u);
  EXPECT_EQ(folder.Entries(), std::vector<std::string>{"vehicle.png"});
}

// A strain dropout leaves FORCE silent: the plot breaks its lines there and
// says so (sensor_faults.yaml drops strain for 150 ms at 6 s).
TEST(ForcePlotTest, MarksASilenceOfForce) {
  ThrustLoss run = MakeThrustLoss();
  run.forces.erase(run.forces.begin() + 600, run.forces.begin() + 750);  // 0.600 to 0.749 s missing
  const std::string script = ForcePlotScript(run.forces, run.truth, ForcePlotOptions{});
  EXPECT_TRUE(Has(script, "'no FORCE for 151 ms from 0.599 s'"));
  EXPECT_TRUE(Has(script, "\n\n0.750000 "));  // a blank line breaks every line at the gap
}

// The lane labels fit left of the axes: "MODEL_MISMATCH" (14 characters at
// 6.6 px, plus a 14 px gap: 106.4 px) of 1200 px puts every panel's left edge
// at 0.0887 (0.075 clipped it to "ODEL_MISMATCH"); the true μ is drawn after
// the estimated μ, dashed, so it is not hidden under it; the default title
// says what the plot shows.
TEST(ForcePlotTest, LaneLabelsFitAndTrueEfficiencyOnTop) {
  const ThrustLoss run = MakeThrustLoss();
  ForcePlotOptions options;
  options.title = ForcePlotTitle("/tmp/logs/thrust_loss.lcm");
  const std::string script = ForcePlotScript(run.forces, run.truth, options);
  EXPECT_TRUE(
      Has(script, "set multiplot title 'Rotor forces, thrust efficiencies and status flags of thrust_loss.lcm'"));
  EXPECT_TRUE(Has(script, "set lmargin at screen 0.0887\n"));
  EXPECT_FALSE(Has(script, "set lmargin at screen 0.075"));
  const size_t estimated = script.find("t 'estimated μ2'");
  const size_t true_mu = script.find("t 'true μ1'");
  ASSERT_NE(estimated, std::string::npos);
  ASSERT_NE(true_mu, std::string::npos);
  EXPECT_LT(estimated, true_mu);
  options.width_px = 2400;  // a wide page keeps the narrowest edge
  EXPECT_TRUE(Has(ForcePlotScript(run.forces, run.truth, options), "set lmargin at screen 0.0750\n"));
}

TEST(ForcePlotTest, RefusesAnEmptyStream) {
  TemporaryFolder folder("birotor_force_plot_test_");
  std::string error;
  EXPECT_FALSE(WriteForcePlot({}, {}, ForcePlotOptions{}, folder.path() + "/none.png", &error));
  EXPECT_EQ(error, "no FORCE message to plot");
  EXPECT_TRUE(folder.Entries().empty());
}

}  // namespace
}  // namespace birotor
