// gnuplot script of birotor-identify's fit plot.
#include "plot/fit_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>

#include "plot/gnuplot_driver.h"

namespace birotor {
namespace {

std::string Number(double value) { return std::isfinite(value) ? fmt::format("{:.10g}", value) : "NaN"; }

// One datablock per panel, sorted by abscissa so that the model draws as a line.
std::string DataBlock(const FitPlot& plot, size_t index) {
  std::vector<size_t> order(plot.x.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return plot.x[a] < plot.x[b]; });
  std::string block = fmt::format("$fit{} << EOD\n", index);
  for (size_t i : order) {
    fmt::format_to(std::back_inserter(block), "{} {} {}\n", Number(plot.x[i]), Number(plot.data[i]),
                   Number(plot.model[i]));
  }
  return block + "EOD\n";
}

}  // namespace

FitPlotText FitPlotLabels(const FitPlot& plot) {
  const std::string arm = std::to_string(plot.arm + 1);
  switch (plot.panel) {
    case FitPanel::kMotorResponse:
      return {fmt::format("motor: telemetry vs first-order model (tau_m = {:.4g} ms)", 1e3 * plot.value),
              "time in window [s]", "omega [rad/s]"};
    case FitPanel::kThrustMap:
      return {"thrust: load cell vs c_T omega^2 (both rotors)", "omega (telemetry) [rad/s]", "force [N]"};
    case FitPanel::kArmMap:
      return {fmt::format("arm {}: load cell force vs deflection map (degree {})", arm, plot.value),
              "deflection b" + arm + " [mrad]", "force [N]"};
    case FitPanel::kArmMapResidual:
      return {fmt::format("arm {}: map residual (RMS {:.4g} N)", arm, plot.value), "deflection b" + arm + " [mrad]",
              "force - map [N]"};
    case FitPanel::kFlightDeflection:
      return {fmt::format("free flight, window {} of {}: arm {} deflection", plot.window + 1, plot.windows, arm),
              "time in window [s]", "b" + arm + " [mrad]"};
  }
  return {};
}

bool WriteFitPlot(const std::vector<FitPlot>& plots, const std::string& title, const std::string& png_path,
                  std::string* error) {
  if (plots.empty()) {
    *error = "no fit to plot";
    return false;
  }
  const int columns = plots.size() > 1 ? 2 : 1;
  const int rows = static_cast<int>((plots.size() + columns - 1) / columns);
  std::string script =
      fmt::format("set terminal pngcairo size {},{} noenhanced font 'sans,9'\nset grid\nset key top left box opaque\n",
                  700 * columns, 380 * rows);
  for (size_t n = 0; n < plots.size(); ++n) script += DataBlock(plots[n], n);
  script += fmt::format("set multiplot layout {},{} title {}\n", rows, columns, GnuplotQuoted(title));
  for (size_t n = 0; n < plots.size(); ++n) {
    const FitPlotText text = FitPlotLabels(plots[n]);
    script += fmt::format(
        "set title {}\nset xlabel {}\nset ylabel {}\n"
        "plot $fit{} using 1:2 with points pt 7 ps 0.3 lc rgb '#1f77b4' title 'data', "
        "$fit{} using 1:3 with lines lw 2 lc rgb '#d62728' title 'fit'\n",
        GnuplotQuoted(text.title), GnuplotQuoted(text.x_label), GnuplotQuoted(text.y_label), n, n);
  }
  script += "unset multiplot\n";
  return RenderGnuplotPng(script, png_path, error);
}

}  // namespace birotor
