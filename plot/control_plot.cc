// gnuplot script of birotor-eval --control's figure.
#include "plot/control_plot.h"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "plot/gnuplot_driver.h"

namespace birotor {
namespace {

std::string Value(double value) { return std::isfinite(value) ? fmt::format("{:.8g}", value) : "NaN"; }

// Series of one panel: (column, label, unit scale).
struct Panel {
  int column;  // in the datablock: 1 time, 2 x error, 3 z error, 4 tilt
  const char* title;
  const char* y_label;
};

}  // namespace

std::string ControlPlotScript(const std::vector<ControlTrace>& traces, const std::string& title, double fault_time_s) {
  std::string script =
      "set terminal pngcairo size 1200,1000 noenhanced font 'sans,10'\nset grid\n"
      "set key top right box opaque\n";
  for (size_t n = 0; n < traces.size(); ++n) {
    const ControlTrace& trace = traces[n];
    script += fmt::format("$flight{} << EOD\n", n);
    for (size_t i = 0; i < trace.t_s.size(); ++i) {
      fmt::format_to(std::back_inserter(script), "{} {} {} {}\n", Value(trace.t_s[i]), Value(trace.x_error_m[i]),
                     Value(trace.z_error_m[i]), Value(trace.tilt_rad[i]));
    }
    script += "EOD\n";
  }
  if (fault_time_s >= 0) {
    script +=
        fmt::format("set arrow 1 from {0},graph 0 to {0},graph 1 nohead dt 2 lc rgb '#555555'\n", Value(fault_time_s));
  }
  script += fmt::format("set multiplot layout 3,1 title {}\n", GnuplotQuoted(title));
  const Panel panels[] = {{2, "x - x_ref", "[m]"}, {3, "z - z_ref", "[m]"}, {4, "tilt phi", "[rad]"}};
  const char* colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd"};
  for (const Panel& panel : panels) {
    script += fmt::format("set title {}\nset ylabel {}\nset xlabel 't [s]'\nplot ", GnuplotQuoted(panel.title),
                          GnuplotQuoted(panel.y_label));
    for (size_t n = 0; n < traces.size(); ++n) {
      script += fmt::format("{}$flight{} using 1:{} with lines lw 1.5 lc rgb '{}' title {}", n == 0 ? "" : ", ", n,
                            panel.column, colours[n % 4], GnuplotQuoted(traces[n].label));
    }
    script += "\n";
  }
  return script + "unset multiplot\n";
}

bool WriteControlPlot(const std::vector<ControlTrace>& traces, const std::string& title, double fault_time_s,
                      const std::string& png_path, std::string* error) {
  if (traces.empty() || traces.front().t_s.empty()) {
    *error = "no flight to plot";
    return false;
  }
  return RenderGnuplotPng(ControlPlotScript(traces, title, fault_time_s), png_path, error);
}

}  // namespace birotor
