// The closed-loop figure of birotor-eval --control: the position error
// (x and z against the reference) and the tilt over time for several
// controller modes of one scenario on one figure, with the fault marked.
#pragma once

#include <string>
#include <vector>

namespace birotor {

// One flight, sampled (e.g. every 10 ms of TRUTH).
struct ControlTrace {
  std::string label;              // e.g. "nominal", "force_feedback"
  std::vector<double> t_s;        // time since the start [s]
  std::vector<double> x_error_m;  // x - x_ref [m]
  std::vector<double> z_error_m;  // z - z_ref [m]
  std::vector<double> tilt_rad;   // phi [rad]
};

// The gnuplot script (data inline); fault_time_s < 0: no fault marker.
std::string ControlPlotScript(const std::vector<ControlTrace>& traces, const std::string& title, double fault_time_s);

// Writes the PNG atomically. False with *error when there is nothing to plot
// or gnuplot fails.
bool WriteControlPlot(const std::vector<ControlTrace>& traces, const std::string& title, double fault_time_s,
                      const std::string& png_path, std::string* error);

}  // namespace birotor
