// The closed-loop figure: three panels, one line per mode in each, the fault
// marked; a real PNG of the size the script asks for (1200 x 1000).
#include "plot/control_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/plot/plot_test_support.h"

namespace birotor {
namespace {

std::vector<ControlTrace> TwoModes() {
  std::vector<ControlTrace> traces(2);
  traces[0].label = "nominal";
  traces[1].label = "force_feedback";
  for (int k = 0; k < 200; ++k) {
    for (ControlTrace& trace : traces) {
      const double t = 0.01 * k;
      trace.t_s.push_back(t);
      trace.x_error_m.push_back(0.01 * std::sin(t));
      trace.z_error_m.push_back(t > 1.0 ? -0.1 * std::exp(-(t - 1.0)) : 0.0);
      trace.tilt_rad.push_back(0.05 * std::sin(3.0 * t));
    }
  }
  return traces;
}

TEST(ControlPlotTest, ScriptHasThreePanelsWithBothModesAndTheFault) {
  const std::string script = ControlPlotScript(TwoModes(), "thrust_loss", 1.0);
  EXPECT_NE(script.find("set multiplot layout 3,1 title 'thrust_loss'"), std::string::npos);
  EXPECT_NE(script.find("set title 'z - z_ref'"), std::string::npos);
  EXPECT_NE(script.find("set title 'tilt phi'"), std::string::npos);
  EXPECT_NE(script.find("set arrow 1 from 1,graph 0"), std::string::npos);
  size_t lines = 0;
  for (size_t at = script.find("title 'force_feedback'"); at != std::string::npos;
       at = script.find("title 'force_feedback'", at + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 3u);
}

TEST(ControlPlotTest, WritesAPng) {
  TemporaryFolder folder("control_plot_test");
  ASSERT_FALSE(folder.path().empty());
  const std::string png = folder.path() + "/thrust_loss_control.png";
  std::string error;
  ASSERT_TRUE(WriteControlPlot(TwoModes(), "thrust_loss", 1.0, png, &error)) << error;
  const PngSize size = ReadPngSize(png);
  EXPECT_EQ(size.width, 1200u);
  EXPECT_EQ(size.height, 1000u);
  EXPECT_EQ(folder.Entries(), std::vector<std::string>{"thrust_loss_control.png"});
  EXPECT_FALSE(WriteControlPlot({}, "none", -1, png, &error));
}

}  // namespace
}  // namespace birotor
